#include "daep/planning/FlightModel.h"

#include <cmath>

namespace daep::planning {

double headingTowards(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double fallback) {
    const Eigen::Vector3d d = to - from;
    if (d.head<2>().norm() < 1e-3)
        return fallback;
    return std::atan2(d.y(), d.x());
}

std::vector<FlatPose> FlightModel::movePoses(const FlatPose& a, const FlatPose& b) const {
    const Eigen::Vector2d d = (b.position - a.position).head<2>();
    if (!faceTravel || d.norm() < kOnTheSpot)
        return {b};
    const FlatPose along{b.position, std::atan2(d.y(), d.x())};
    if (std::abs(wrapAngle(along.yaw - b.yaw)) < 1e-6)
        return {b};
    return {along, b};
}

double FlightModel::moveTime(const FlatPose& a, const FlatPose& b) const {
    double time = 0.0;
    FlatPose at = a;
    for (const FlatPose& next : movePoses(a, b)) {
        time += motion.travelTime(at, next);
        at = next;
    }
    return time;
}

double FlightModel::reachTime(const FlatPose& from, double start, const Eigen::Vector3d& to) const {
    const Eigen::Vector2d d = (to - from.position).head<2>();
    if (faceTravel && d.norm() >= kOnTheSpot)
        return start + moveTime(from, {to, std::atan2(d.y(), d.x())});
    return start + (to - from.position).norm() / motion.speed;
}

std::vector<Waypoint> FlightModel::flown(const FlatPose& pose, double time,
                                         const std::vector<Waypoint>& waypoints) const {
    std::vector<Waypoint> out;
    FlatPose at = pose;
    for (const Waypoint& w : waypoints) {
        for (const FlatPose& next : movePoses(at, w.pose)) {
            time += motion.travelTime(at, next);
            out.push_back({next, time});
            at = next;
        }
    }
    return out;
}

}  // namespace daep::planning
