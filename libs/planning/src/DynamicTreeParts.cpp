#include "daep/planning/DynamicTreeParts.h"

#include <cmath>

#include "daep/planning/DynamicFrequencyMap.h"
#include "daep/planning/DynamicObstacles.h"
#include "daep/planning/FlightModel.h"

namespace daep::planning {

TimeAwareValidator::TimeAwareValidator(const MoveValidator& pathSpace,
                                       const DynamicObstacles& bodies, const FlightModel& flight)
    : pathSpace_(pathSpace), bodies_(bodies), flight_(flight) {}

bool TimeAwareValidator::staticValid(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                     bool leavingBlocked) const {
    return pathSpace_.staticValid(a, b, leavingBlocked);
}

bool TimeAwareValidator::timedValid(const FlatPose& from, double start, const FlatPose& to) const {
    if (bodies_.empty())
        return true;
    FlatPose at = from;
    for (const FlatPose& next : flight_.movePoses(from, to)) {
        const TimedSegment move =
            timedSegment(at, next, start, flight_.motion.speed, flight_.motion.yawRate);
        if (!bodies_.isSafe(move))
            return false;
        start = move.end();
        at = next;
    }
    return true;
}

bool TimeAwareValidator::checksPeople() const {
    return !bodies_.empty();
}

DynamicScoreObjective::DynamicScoreObjective(DynamicScore form, double lambda, double zeta,
                                             const DynamicFrequencyMap& dfm)
    : form_(form), lambda_(lambda), zeta_(zeta), dfm_(dfm) {}

double DynamicScoreObjective::score(double parentScore, double gain, double edge,
                                    const Eigen::Vector3d& p) const {
    const double boost = zeta_ * dfm_.value(p.head<2>());
    if (form_ == DynamicScore::Reference)
        return parentScore + gain * std::exp(-lambda_ * edge * (1.0 + boost));
    return parentScore + gain * std::exp(-lambda_ * edge) * (1.0 + boost);
}

DynamicInformationGain::DynamicInformationGain(CachedView& staticView,
                                               const DynamicObstacles& bodies,
                                               const FlightModel& flight)
    : staticView_(staticView), bodies_(bodies), flight_(flight) {}

std::vector<BodyOccluder> DynamicInformationGain::bodiesInView(const Eigen::Vector3d& p,
                                                               double t) const {
    std::vector<BodyOccluder> inRange;
    const double range = staticView_.evaluator().params().range;
    for (const BodyOccluder& b : bodies_.bodiesAt(t))
        if ((b.center - p.head<2>()).norm() <= range + b.radius)
            inRange.push_back(b);
    return inRange;
}

bool DynamicInformationGain::peopleInView(const Eigen::Vector3d& p, double t) const {
    return !bodiesInView(p, t).empty();
}

YawGain DynamicInformationGain::viewOnArrival(const Eigen::Vector3d& from, const Eigen::Vector3d& p,
                                              double arrival, bool rayCast) {
    const std::vector<BodyOccluder> inRange = bodiesInView(p, arrival);
    const GainEvaluator& g = staticView_.evaluator();
    const Eigen::Vector2d leg = (p - from).head<2>();
    const bool facingTravel = flight_.faceTravel && leg.norm() > 0.05;
    const auto facingTravelView = [&](const std::vector<double>& columns) {
        const double heading = std::atan2(leg.y(), leg.x());
        return YawGain{heading, g.windowGain(columns, heading)};
    };
    if (inRange.empty()) {
        if (!facingTravel)
            return staticView_.viewOnArrival(from, p, arrival, rayCast);
        const std::vector<double> columns = staticView_.rayCastColumns(p, nullptr);
        staticView_.remember(p, g.bestYaw(columns));
        return facingTravelView(columns);
    }
    // The cache keeps the view without people, who will have walked on.
    const GainEvaluator::ColumnViews views = staticView_.rayCastColumnsOpenAndOccluded(p, inRange);
    staticView_.remember(p, g.bestYaw(views.open));
    return facingTravel ? facingTravelView(views.occluded) : g.bestYaw(views.occluded);
}

}  // namespace daep::planning
