#pragma once

#include <Eigen/Core>
#include <algorithm>

namespace daep {

/** Distance from p to the segment a-b (Eigen vectors of any size: the plane or space). */
template <typename Vector>
double distanceToSegment(const Vector& p, const Vector& a, const Vector& b) {
    const Vector ab = b - a;
    const double length2 = ab.squaredNorm();
    const double s = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    return (a + s * ab - p).norm();
}

}  // namespace daep
