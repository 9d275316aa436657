#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "daep/common/Types.h"
#include "daep/planning/Planner.h"

namespace daep::mapping {
class ExplorationMap;
}

namespace daep::planning {

class DynamicObstacles;

/** Where the way-out search looks: a lattice around the drone. */
struct WayOutParams {
    double spacing = 0.4;  ///< lattice step, m (also the vertical step)
    double radius = 3.2;   ///< horizontal reach from the drone, m
    double robotRadius = 0.3;
    double bodyHalfHeight = 0.05;  ///< as in segmentFlyable
};

/** A way out: the lattice points flown through (the start excluded) and how exposed it is. */
struct WayOut {
    std::vector<Eigen::Vector3d> path;
    double length = 0.0;
    /** Time (s) the drone is inside a predicted body (gap <= 0), hovering at the end included. */
    double exposure = 0.0;
    /** The least gap (m) to the predicted bodies while outside them. */
    double gap = 0.0;
    /** The least gap (m), negative inside a body, once under way (after the first 0.4 s). */
    double deepest = 0.0;
};

/**
 * The exposure and gap of flying `path` from `from` at `time`, then hovering at its end until
 * `hoverUntil` (at least 0.4 s).
 */
WayOut judgeWay(const DynamicObstacles& bodies, const Eigen::Vector3d& from, double time,
                std::vector<Eigen::Vector3d> path, const MotionLimits& motion, double hoverUntil);

/**
 * The way out of a corner: when no short straight escape keeps clear of the people coming,
 * the path through the known free space around the drone, flown at its heading, that spends
 * the least time inside the predicted bodies (as judgeWay judges it); of equal ones the one with
 * the larger least gap outside them, then the shorter. A label-setting search over a lattice of
 * `spacing` within `radius` (three layers: the drone's height and one step above and below), each
 * move timed as flown from `time`, judged in 0.4 s pieces, and checked in free space with the robot
 * radius.
 */
std::optional<WayOut> findWayOut(const mapping::ExplorationMap& map, const Aabb& box,
                                 const DynamicObstacles& bodies, const FlatPose& from, double time,
                                 const MotionLimits& motion, double hoverUntil,
                                 const WayOutParams& params);

}  // namespace daep::planning
