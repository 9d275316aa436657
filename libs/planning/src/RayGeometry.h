#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>

#include "daep/common/Types.h"

namespace daep::planning::detail {

constexpr double kTwoPi = 2.0 * M_PI;

/** How many equal steps of about `step` tile `extent` (at least one). */
inline int tileCount(double extent, double step) {
    return std::max(1, static_cast<int>(std::lround(extent / step)));
}

/** Distance along the unit ray from p (inside the box) to the box boundary. */
inline double exitDistance(const Aabb& box, const Eigen::Vector3d& p, const Eigen::Vector3d& dir) {
    double t = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (dir[a] > 0.0)
            t = std::min(t, (box.max[a] - p[a]) / dir[a]);
        if (dir[a] < 0.0)
            t = std::min(t, (box.min[a] - p[a]) / dir[a]);
    }
    return t;
}

}  // namespace daep::planning::detail
