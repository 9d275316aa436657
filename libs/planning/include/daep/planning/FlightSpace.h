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
 * unseen, or an obstacle nearer than the radius) b must be known free, and either the move past
 * its first radius keeps the radius from occupied cells, or the whole move keeps at least the
 * clearance the drone has at a: the drone is physically at a and must be able to leave. Then
 * what hems it in may stay that near, but nothing else may come within the radius sideways or
 * `halfHeight` (its body's) above or below. With no clearance left (an imprint in its own
 * cell or touching it: under radius / 64), the move's line must leave that cell within
 * `halfHeight` of the drone's height and enter no occupied cell after it, with the same rule
 * for the body.
 */
bool segmentFlyable(const mapping::ExplorationMap& map, const Eigen::Vector3d& a,
                    const Eigen::Vector3d& b, double radius, double halfHeight,
                    bool leavingBlockedRoot);

/**
 * The largest radius up to `radius` (to about radius / 64) whose ball around p touches no
 * occupied cell (grazed surfaces count, as in the clearance checks); -1 when p's own cell does.
 */
double clearanceFromOccupied(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                             double radius);

/** The box shrunk by margin on every side (collapsing to its centre along too-thin axes). */
Aabb shrink(const Aabb& box, double margin);

/** A uniform point in the box. */
Eigen::Vector3d sampleInBox(const Aabb& box, std::mt19937_64& rng);

/** A uniform yaw in [-pi, pi). */
double sampleYaw(std::mt19937_64& rng);

}  // namespace daep::planning
