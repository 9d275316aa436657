#pragma once

#include <Eigen/Core>

namespace daep {

/** Axis-aligned box, used for the exploration volume and for bounds. */
struct Aabb {
    Eigen::Vector3d min = Eigen::Vector3d::Zero();
    Eigen::Vector3d max = Eigen::Vector3d::Zero();

    Eigen::Vector3d size() const { return max - min; }
    Eigen::Vector3d center() const { return 0.5 * (min + max); }
    double volume() const { return size().prod(); }
    bool contains(const Eigen::Vector3d& p) const {
        return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
    }
};

/** A drone or sensor pose with roll = pitch = 0: position and heading (rad, CCW from +x). */
struct FlatPose {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    double yaw = 0.0;
};

/** Wraps an angle to (-pi, pi]. */
double wrapAngle(double a);

}  // namespace daep
