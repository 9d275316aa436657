#pragma once

#include <Eigen/Core>
#include <vector>

#include "daep/planning/Planner.h"

namespace daep::mapping {
class ExplorationMap;
}

namespace daep::planning {

/** Where a path may be taken over the people's heads. */
struct OverHeadsSpace {
    const mapping::ExplorationMap* map = nullptr;
    double radius = 0.3;          ///< the drone's, as in segmentFlyable
    double halfHeight = 0.05;     ///< its body's, as in segmentFlyable
    double height = 0.0;          ///< a drone centre this high clears every body
    bool leavingBlocked = false;  ///< the drone's own ball is not known free (segmentFlyable)
};

/**
 * Raises the stops to space.height where both their legs stay flyable: from the stop before
 * (as raised) and to the next stop as planned, so a stop left low stays reachable. The drone
 * is at `start`. Returns whether any stop was raised; arrival times are left as they were.
 */
bool raiseStops(const OverHeadsSpace& space, const Eigen::Vector3d& start,
                std::vector<Waypoint>& stops);

/**
 * The stops with the drone kept at space.height as long as it can between a stop there and
 * one below it: it climbs at the start of a leg going up and drops at the end of a leg going
 * down (else a quarter or half of the leg later or earlier) where both parts are flyable. An
 * added waypoint keeps the heading of its leg; arrival times are left to the caller.
 */
std::vector<Waypoint> stayHigh(const OverHeadsSpace& space, const Eigen::Vector3d& start,
                               const std::vector<Waypoint>& stops);

/**
 * The stops with every climb on the spot from below space.height to over it flown before the
 * turn it comes with: the drone leaves the people's reach at once and turns up there (a move
 * turns first, then flies). The drone is at `start`; arrival times are left to the caller.
 */
std::vector<Waypoint> climbBeforeTurning(const OverHeadsSpace& space, const FlatPose& start,
                                         const std::vector<Waypoint>& stops);

/**
 * Where to end a way flown over the heads before it goes down among the people again: the
 * index of the first stop below space.height that follows at least 2 m (across) flown over
 * the heads from `start`, or stops.size() when there is none. There the drone stops over the
 * heads and plans again, so that the blind guard judges the walkways where it goes down
 * afresh (after a shorter flight they were judged when the plan was made).
 */
std::size_t beforeDescent(const OverHeadsSpace& space, const Eigen::Vector3d& start,
                          const std::vector<Waypoint>& stops);

}  // namespace daep::planning
