#pragma once

#include <Eigen/Core>
#include <random>

#include "daep/common/Types.h"

namespace daep::mapping {
class ExplorationMap;
}

namespace daep::planning {

// Where the drone may fly and how planners sample it: the parts every planner's tree, roadmap
// or escape shares.

/** `to`, moved towards `from` so that it lies at most maxStep away. */
Eigen::Vector3d steer(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double maxStep);

/**
 * Whether the drone can fly a -> b with its capsule of `radius` in known free space. With
 * `leavingBlockedRoot` (the drone is at a, but its own ball is not known free: cells around it
 * unseen, or an obstacle nearer than the radius) the first radius is skipped, the rest must not
 * touch occupied cells and b must be known free: the drone is physically at a and must be able
 * to leave.
 */
bool segmentFlyable(const mapping::ExplorationMap& map, const Eigen::Vector3d& a,
                    const Eigen::Vector3d& b, double radius, bool leavingBlockedRoot);

/** The box shrunk by margin on every side (collapsing to its centre along too-thin axes). */
Aabb shrink(const Aabb& box, double margin);

/** A uniform point in the box. */
Eigen::Vector3d sampleInBox(const Aabb& box, std::mt19937_64& rng);

/** A uniform yaw in [-pi, pi). */
double sampleYaw(std::mt19937_64& rng);

}  // namespace daep::planning
