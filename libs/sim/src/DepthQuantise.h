#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>

namespace daep::sim {

/**
 * A depth (m) as a range-image value in steps of `units`: 0 for no return, else
 * clamp(std::round(depth / units), 1, 65535). A return never becomes "no return" through
 * rounding or noise. The rounding is std::round's (halves away from zero) without its libm
 * call, once per pixel: x - whole is exact below 2^23.
 */
inline std::uint16_t quantiseDepth(float depth, float units) {
    if (depth <= 0.0f)
        return 0;
    const float x = depth / units;
    constexpr std::uint16_t kMaxSteps = std::numeric_limits<std::uint16_t>::max();
    if (!(x < float(kMaxSteps)))
        return kMaxSteps;
    const float whole = static_cast<float>(static_cast<int>(x));
    const float steps = whole + static_cast<float>(x - whole >= 0.5f);  // no branch to mispredict
    return static_cast<std::uint16_t>(std::max(steps, 1.0f));
}

}  // namespace daep::sim
