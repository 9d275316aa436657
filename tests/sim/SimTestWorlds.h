#pragma once

#include <Eigen/Geometry>
#include <string>

#include "daep/world/WorldSpec.h"

namespace daep::sim::test {

inline world::BoxShape box(const std::string& name, const Eigen::Vector3d& center,
                           const Eigen::Vector3d& size, double yaw = 0.0) {
    world::BoxShape b;
    b.name = name;
    b.pose = Eigen::Translation3d(center) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
    b.size = size;
    return b;
}

/** Distance from p to the surface of a yawed box (|signed distance|). */
inline double distanceToBoxSurface(const Eigen::Vector3d& p, const world::BoxShape& b) {
    const Eigen::Vector3d local = b.pose.inverse() * p;
    const Eigen::Vector3d q = local.cwiseAbs() - 0.5 * b.size;
    const double outside = q.cwiseMax(0.0).norm();
    const double inside = std::min(q.maxCoeff(), 0.0);
    return std::abs(outside + inside);
}

}  // namespace daep::sim::test
