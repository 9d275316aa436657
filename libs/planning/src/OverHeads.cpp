#include "daep/planning/OverHeads.h"

#include <cmath>

#include "daep/planning/FlightModel.h"
#include "daep/planning/FlightSpace.h"

namespace daep::planning {
namespace {

/** Heights within this (m) count as the same. */
constexpr double kLevel = 1e-9;
/** Legs shorter than this (m) across are flown as they are: climbs and drops on the spot. */
constexpr double kShortLeg = 0.1;
/**
 * After this far (m) over the heads the drone stops before it goes down again, so that the
 * walkways around where it goes down are judged afresh (a shorter flight: as planned).
 */
constexpr double kLongFlightOverHeads = 2.0;

bool isHigh(const OverHeadsSpace& space, const Eigen::Vector3d& p) {
    return p.z() >= space.height - kLevel;
}

bool flyable(const OverHeadsSpace& space, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
             bool fromStart) {
    return segmentFlyable(*space.map, a, b, space.radius, space.halfHeight,
                          fromStart && space.leavingBlocked);
}

}  // namespace

bool raiseStops(const OverHeadsSpace& space, const Eigen::Vector3d& start,
                std::vector<Waypoint>& stops) {
    bool any = false;
    Eigen::Vector3d at = start;
    bool fromStart = true;
    for (std::size_t k = 0; k < stops.size(); ++k) {
        Eigen::Vector3d& stop = stops[k].pose.position;
        const Eigen::Vector3d up(stop.x(), stop.y(), space.height);
        const bool last = k + 1 == stops.size();
        if (!isHigh(space, stop) && flyable(space, at, up, fromStart) &&
            (last || flyable(space, up, stops[k + 1].pose.position, false))) {
            stop = up;
            any = true;
        }
        fromStart = fromStart && stop == start;
        at = stop;
    }
    return any;
}

std::vector<Waypoint> stayHigh(const OverHeadsSpace& space, const Eigen::Vector3d& start,
                               const std::vector<Waypoint>& stops) {
    std::vector<Waypoint> out;
    Eigen::Vector3d a = start;
    bool fromStart = true;
    for (const Waypoint& next : stops) {
        const Eigen::Vector3d& b = next.pose.position;
        const bool aHigh = isHigh(space, a), bHigh = isHigh(space, b);
        const Eigen::Vector2d across = (b - a).head<2>();
        if (aHigh != bHigh && across.norm() > kShortLeg) {
            for (const double late : {1.0, 0.75, 0.5}) {
                const Eigen::Vector2d xy = a.head<2>() + (bHigh ? 1.0 - late : late) * across;
                const Eigen::Vector3d turn(xy.x(), xy.y(), space.height);
                if (flyable(space, a, turn, fromStart) && flyable(space, turn, b, false)) {
                    out.push_back({{turn, next.pose.yaw}, 0.0});
                    break;
                }
            }
        }
        out.push_back(next);
        fromStart = fromStart && b == start;
        a = b;
    }
    return out;
}

std::vector<Waypoint> climbBeforeTurning(const OverHeadsSpace& space, const FlatPose& start,
                                         const std::vector<Waypoint>& stops) {
    constexpr double kSameHeading = 1e-9;
    std::vector<Waypoint> out;
    FlatPose at = start;
    for (const Waypoint& next : stops) {
        const FlatPose& to = next.pose;
        const bool climbsOnTheSpot =
            !isHigh(space, at.position) && isHigh(space, to.position) &&
            (to.position - at.position).head<2>().norm() < FlightModel::kOnTheSpot;
        if (climbsOnTheSpot && std::abs(wrapAngle(to.yaw - at.yaw)) > kSameHeading)
            out.push_back({{to.position, at.yaw}, 0.0});
        out.push_back(next);
        at = to;
    }
    return out;
}

std::size_t beforeDescent(const OverHeadsSpace& space, const Eigen::Vector3d& start,
                          const std::vector<Waypoint>& stops) {
    double flown = 0.0;  // across, over the heads, since the drone was last below them
    Eigen::Vector3d at = start;
    for (std::size_t k = 0; k < stops.size(); ++k) {
        const Eigen::Vector3d& p = stops[k].pose.position;
        const bool high = isHigh(space, p);
        if (!high && flown >= kLongFlightOverHeads)
            return k;
        flown = high && isHigh(space, at) ? flown + (p - at).head<2>().norm() : 0.0;
        at = p;
    }
    return stops.size();
}

}  // namespace daep::planning
