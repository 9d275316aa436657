#include "daep/planning/Planner.h"

#include <cmath>
#include <utility>

namespace daep::planning {

double MotionLimits::travelTime(const FlatPose& a, const FlatPose& b) const {
    const double turn = std::abs(wrapAngle(b.yaw - a.yaw)) / yawRate;
    const double fly = (b.position - a.position).norm() / speed;
    return turn + fly;
}

const char* unseenWatchName(UnseenWatch watch) {
    switch (watch) {
        case UnseenWatch::Open:
            return "open";
        case UnseenWatch::Cleared:
            return "cleared";
        case UnseenWatch::NoWalkway:
            return "no_walkway";
        case UnseenWatch::Lost:
            return "lost";
        case UnseenWatch::None:
            break;
    }
    return "-";
}

void Plan::cutTo(std::size_t n) {
    if (n >= waypoints.size())
        return;
    waypoints.resize(n);
    if (n == 0 && status == Status::Path)
        status = Status::NoPath;
}

void Plan::waitFor(double seconds) {
    waypoints.clear();
    waitSeconds = seconds;
    status = seconds > 0.0 ? Status::Wait : Status::NoPath;
}

bool Plan::wellFormed() const {
    switch (status) {
        case Status::Path:
            return !waypoints.empty();
        case Status::Wait:
            return waypoints.empty() && waitSeconds > 0.0;
        case Status::NoPath:
        case Status::Finished:
            return waypoints.empty();
    }
    return false;
}

const char* statusName(Plan::Status status) {
    switch (status) {
        case Plan::Status::Path:
            return "path";
        case Plan::Status::Wait:
            return "wait";
        case Plan::Status::NoPath:
            return "no_path";
        case Plan::Status::Finished:
            return "finished";
    }
    return "?";
}

}  // namespace daep::planning
