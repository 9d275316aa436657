#pragma once

#include <Eigen/Core>
#include <vector>

#include "daep/planning/Planner.h"

namespace daep::planning {

/** The heading from `from` to `to`, or `fallback` when they are (nearly) above each other. */
double headingTowards(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double fallback);

/**
 * How the drone flies from pose to pose, and so when it gets there: the one place arrival
 * times are computed for trees, plans and their safety checks.
 *
 * A move turns on the spot, then flies straight (MotionLimits). With faceTravel the drone
 * first turns to the heading of travel, flies, then turns to the pose's yaw, so that the
 * camera looks where it goes.
 */
struct FlightModel {
    /** Moves shorter than this (m) across are flown on the spot: no turn to face them. */
    static constexpr double kOnTheSpot = 0.05;

    MotionLimits motion;
    bool faceTravel = false;

    /** The poses flown through from a to b (b last): with faceTravel, b's heading first. */
    std::vector<FlatPose> movePoses(const FlatPose& a, const FlatPose& b) const;
    /** The time the move from a to b takes. */
    double moveTime(const FlatPose& a, const FlatPose& b) const;
    /**
     * When the drone leaving `from` at `start` reaches `to`, before it turns to a view chosen
     * there. With faceTravel: after the turn to the heading of travel and the flight (the view
     * there is the one along the leg). Without: the flight alone, since the drone turns to the
     * view first and the view is not chosen yet.
     */
    double reachTime(const FlatPose& from, double start, const Eigen::Vector3d& to) const;
    /** The waypoints with the turns movePoses adds, timed from `pose` at `time`. */
    std::vector<Waypoint> flown(const FlatPose& pose, double time,
                                const std::vector<Waypoint>& waypoints) const;
};

}  // namespace daep::planning
