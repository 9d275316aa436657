#include "daep/planning/DynamicObstacles.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace daep::planning {

Eigen::Vector3d TimedSegment::positionAt(double t) const {
    const double flying = t - start - turnTime;
    if (flying <= 0.0 || flyTime <= 0.0)
        return flying <= 0.0 ? from : to;
    return from + (to - from) * std::min(1.0, flying / flyTime);
}

TimedSegment TimedSegment::after(double t) const {
    TimedSegment rest = *this;
    const double delay = std::clamp(t - start, 0.0, turnTime + flyTime);
    rest.start = start + delay;
    if (delay <= turnTime) {
        rest.turnTime = turnTime - delay;
        return rest;
    }
    rest.from = positionAt(rest.start);
    rest.turnTime = 0.0;
    rest.flyTime = flyTime - (delay - turnTime);
    return rest;
}

TimedSegment timedSegment(const FlatPose& a, const FlatPose& b, double start, double speed,
                          double yawRate) {
    TimedSegment s;
    s.from = a.position;
    s.to = b.position;
    s.start = start;
    s.turnTime = std::abs(wrapAngle(b.yaw - a.yaw)) / yawRate;
    s.flyTime = (b.position - a.position).norm() / speed;
    return s;
}

DynamicObstacles::DynamicObstacles(const SafetyParams& params,
                                   std::vector<perception::PersonForecast> people)
    : params_(params), people_(std::move(people)) {
    bodyRadius_ =
        0.5 * params.personSize.head<2>().norm() + 0.5 * params.droneSize.head<2>().norm();
    bodyTop_ = params.bodyTop();
}

namespace {

/** Square root of the largest eigenvalue of a 2x2 covariance. */
double largestSigma(const Eigen::Matrix2d& c) {
    const double mean = 0.5 * (c(0, 0) + c(1, 1));
    const double diff = 0.5 * (c(0, 0) - c(1, 1));
    return std::sqrt(std::max(0.0, mean + std::sqrt(diff * diff + c(0, 1) * c(0, 1))));
}

}  // namespace

double DynamicObstacles::keepOutRadius(const perception::PersonForecast& person, double t,
                                       double clearanceScale) const {
    return keepOutRadius(person.at(t), clearanceScale);
}

double DynamicObstacles::keepOutRadius(const perception::PositionPrediction& at,
                                       double clearanceScale) const {
    const double sigma = largestSigma(at.covariance);
    return bodyKeepOut(clearanceScale) +
           std::min(params_.maxInflation, params_.sigmaInflation * sigma);
}

std::optional<DynamicObstacles::Encounter> DynamicObstacles::encounter(
    const perception::PersonForecast& person, const TimedSegment& move) const {
    Encounter e;
    e.t0 = std::max(move.start, person.time);
    e.t1 = std::min(move.end(), person.time + params_.horizon);
    if (e.t1 < e.t0)
        return std::nullopt;
    const double droneSpeed =
        move.flyTime > 0.0 ? (move.to - move.from).norm() / move.flyTime : 0.0;
    e.closing = droneSpeed + person.velocity().norm();
    return e;
}

double DynamicObstacles::gapTo(const perception::PersonForecast& person, const TimedSegment& move,
                               double clearanceScale) const {
    const std::optional<Encounter> e = encounter(person, move);
    return e ? gapDuring(person, move, *e, clearanceScale)
             : std::numeric_limits<double>::infinity();
}

double DynamicObstacles::gapDuring(const perception::PersonForecast& person,
                                   const TimedSegment& move, const Encounter& e,
                                   double clearanceScale) const {
    const double t0 = e.t0, t1 = e.t1, closing = e.closing;
    // Quick reject: even closing at full speed over the whole move cannot reach the body.
    const Eigen::Vector2d startGap = move.positionAt(t0).head<2>() - person.meanAt(t0);
    const double reach = keepOutRadius(person, t1, clearanceScale) + closing * (t1 - t0);
    if (startGap.norm() > reach + 1e-9)
        return startGap.norm() - reach;
    const int steps = std::max(1, static_cast<int>(std::ceil((t1 - t0) / params_.timeStep)));
    const double h = (t1 - t0) / steps;
    const double slack = 0.5 * h * closing;
    const double top = clearedHeight(clearanceScale);
    const bool canClimbOver = params_.ceiling > top;
    double gap = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= steps; ++k) {
        const double t = t0 + k * h;
        const Eigen::Vector3d d = move.positionAt(t);
        const double above = d.z() - top;
        const perception::PositionPrediction body = person.at(t);
        const double horizontal =
            (d.head<2>() - body.mean).norm() - keepOutRadius(body, clearanceScale) - slack;
        gap = std::min(gap, above > 0.0 || canClimbOver ? std::max(horizontal, above) : horizontal);
    }
    return gap;
}

double DynamicObstacles::clearance(const TimedSegment& move, double clearanceScale) const {
    double gap = std::numeric_limits<double>::infinity();
    for (const perception::PersonForecast& p : people_)
        gap = std::min(gap, gapTo(p, move, clearanceScale));
    return gap;
}

bool DynamicObstacles::blocks(const perception::PersonForecast& person, const TimedSegment& move,
                              double clearanceScale) const {
    const std::optional<Encounter> e = encounter(person, move);
    if (!e)
        return false;
    // gapDuring's quick reject with the largest body the person can have: far walkers are
    // passed without their forecast's covariance. Never rejects where gapDuring would not.
    if (std::isfinite(params_.maxInflation) && params_.maxInflation >= 0.0) {
        const double largestReach =
            bodyKeepOut(clearanceScale) + params_.maxInflation + e->closing * (e->t1 - e->t0);
        const Eigen::Vector2d startGap = move.positionAt(e->t0).head<2>() - person.meanAt(e->t0);
        if (startGap.norm() > largestReach + 1e-9)
            return false;
    }
    return gapDuring(person, move, *e, clearanceScale) <= 0.0;
}

/**
 * The walker who blocked the last unsafe move is asked first: a planner's samples that fail
 * mostly fail on the same walker (a tree hemmed in tries thousands). The answer does not
 * depend on the order.
 */
bool DynamicObstacles::isSafe(const TimedSegment& move, double clearanceScale) const {
    const std::size_t first = lastBlocker_ < people_.size() ? lastBlocker_ : 0;
    if (!people_.empty() && blocks(people_[first], move, clearanceScale))
        return false;
    for (std::size_t i = 0; i < people_.size(); ++i) {
        if (i != first && blocks(people_[i], move, clearanceScale)) {
            lastBlocker_ = i;
            return false;
        }
    }
    return true;
}

bool DynamicObstacles::isSafeToHover(const Eigen::Vector3d& p, double t0, double t1) const {
    TimedSegment hover;
    hover.from = hover.to = p;
    hover.start = t0;
    hover.turnTime = std::max(0.0, t1 - t0);
    return isSafe(hover);
}

std::vector<BodyOccluder> DynamicObstacles::bodiesAt(double t) const {
    std::vector<BodyOccluder> out;
    for (const perception::PersonForecast& p : people_) {
        if (t > p.time + params_.horizon)
            continue;
        BodyOccluder b;
        b.center = p.at(t).mean;
        b.radius = 0.5 * std::min(params_.personSize.x(), params_.personSize.y());
        b.height = params_.personSize.z();
        out.push_back(b);
    }
    return out;
}

}  // namespace daep::planning
