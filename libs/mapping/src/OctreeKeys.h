#pragma once

#include <octomap/OcTreeKey.h>

#include <cmath>

#include "daep/mapping/DenseGridIndex.h"

namespace daep::mapping {

/**
 * OctoMap's coordToKeyChecked on one axis, bit for bit (the tests compare them), for a tree
 * whose resolution factor (1 / resolution) is `scale`: floor(scale * c) + 2^15 and the range
 * check, without the libm floor call, and defined beyond int (OctoMap casts unchecked there,
 * found by UBSan). Keys span +-2^15 cells; anything farther is outside the tree.
 */
template <bool kFloored = false>
inline bool octreeAxisKey(double scale, double c, octomap::key_type& k) {
    constexpr double kHalfSpan = 32768.0;
    const double v = scale * c;
    if (!(v >= -kHalfSpan && v < kHalfSpan))
        return false;  // also NaN
    // With kFloored the floor is std::floor: one instruction in code built for SSE4.1, the same
    // integer (both floors are exact here).
    k = octomap::key_type((kFloored ? int(std::floor(v)) : floorToInt(v)) + int(kHalfSpan));
    return true;
}

}  // namespace daep::mapping
