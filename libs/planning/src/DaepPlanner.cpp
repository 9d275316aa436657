#include "daep/planning/DaepPlanner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>

#include "daep/common/Config.h"
#include "daep/common/ConfigChecks.h"
#include "daep/common/Geometry.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/planning/FlightModel.h"
#include "daep/planning/FlightSpace.h"
#include "daep/planning/OverHeads.h"
#include "daep/planning/WayOut.h"

namespace daep::planning {
namespace {

/** People are counted into the frequency map at most this often (s)... */
constexpr double kDfmPeriod = 0.2;
/** ...and only while measured recently (s): a prediction is not an observation. */
constexpr double kDfmFreshness = 0.5;
/** How far (m) over the height that clears every body a stop over the heads is put. */
constexpr double kOverHeads = 0.05;
/** Heights (m) closer than this compare equal: a stop at the ceiling is under it. */
constexpr double kHeightTolerance = 1e-9;
/** Headings a look before a stop may take, evenly around (besides the worst walkway's). */
constexpr int kLookDirections = 16;

bool samePositions(const std::vector<Waypoint>& a, const std::vector<Waypoint>& b) {
    return std::equal(
        a.begin(), a.end(), b.begin(), b.end(),
        [](const Waypoint& p, const Waypoint& q) { return p.pose.position == q.pose.position; });
}

}  // namespace

DaepParams DaepParams::fromConfig(const mrpt::config::CConfigFileBase& config) {
    const ConfigReader r(config, "daep");
    DaepParams p;
    p.aep = AepParams::fromConfig(config, "daep");
    p.safety.clearance = requireNonNegative(r, "clearance");
    p.safety.sigmaInflation = requireNonNegative(r, "sigma_inflation");
    p.safety.maxInflation = requireNonNegative(r, "max_inflation");
    p.safety.horizon = requirePositive(r, "prediction_horizon_s");
    p.safety.timeStep = requirePositive(r, "safety_time_step_s");
    p.recheckClearanceScale = requireNonNegative(r, "recheck_clearance_scale");
    p.dfmCellSize = requirePositive(r, "dfm_cell_size");
    p.zeta = requireNonNegative(r, "zeta");
    p.score = requireEnum<DynamicScore>(
        r, "score", {{"paper", DynamicScore::Paper}, {"reference", DynamicScore::Reference}});
    p.borderBoost = requirePositive(r, "border_boost");
    p.borderDistance = requireNonNegative(r, "border_distance");
    p.useGp = r.requireBool("use_gp");
    p.evasionHorizon = requirePositive(r, "evasion_horizon_s");
    p.trapHorizon = requireNonNegative(r, "trap_horizon_s");
    p.waitTime = requirePositive(r, "wait_s");
    const std::vector<std::pair<std::string, AutoSwitch>> autoSwitch = {
        {"auto", AutoSwitch::Auto}, {"true", AutoSwitch::On}, {"false", AutoSwitch::Off}};
    p.faceTravel = requireEnum(r, "face_travel_direction", autoSwitch);
    p.blindGuard = requireEnum(r, "blind_guard", autoSwitch);
    p.blind.walkSpeed = requireNonNegative(r, "blind_walk_speed");
    p.blind.busyThreshold = requireInRange(r, "blind_busy_threshold", 0.0, 1.0);
    p.blind.stopTime = requireNonNegative(r, "blind_stop_s");
    p.blind.range = requirePositive(r, "blind_watch_range");
    p.blind.maxLooks = requireIntAtLeast(r, "blind_max_looks", 0);
    p.blind.lostTime = requireNonNegative(r, "blind_lost_s");
    p.flyOverHeads = requireEnum(r, "fly_over_heads", autoSwitch);
    p.overHeadsMinClearance = requireNonNegative(r, "over_heads_min_clearance");
    return p;
}

namespace {

AepParams withoutGpWhenOff(const DaepParams& p) {
    AepParams a = p.aep;
    if (!p.useGp)
        a.view.sigmaThreshold = 0.0;  // the GP's sigma is never below 0: every node is ray cast
    return a;
}

}  // namespace

DaepPlanner::DaepPlanner(const DaepParams& params, const GainParams& gain, std::uint64_t seed)
    : AepPlanner(withoutGpWhenOff(params), gain, seed),
      params_(params),
      timeAware_(pathSpace(), obstacles_, flight()),
      dynamicScore_(params.score, params.aep.lambda, params.zeta, dfm_),
      dynamicGain_(cachedView(), obstacles_, flight()) {
    gainEvaluator().setYawAngleBooster(params.borderBoost, params.borderDistance);
    compose(timeAware_, dynamicScore_, dynamicGain_);
}

DynamicObstacles DaepPlanner::obstaclesOf(const PlanningContext& context) const {
    SafetyParams safety = params_.safety;
    safety.droneSize = context.droneSize;
    safety.personSize = context.personSize;
    safety.ceiling = shrink(context.explorationBox, params().robotRadius).max.z();
    if (isOn(params_.flyOverHeads, context.peopleFromCamera))
        fitOverHeads(context, safety);
    return DynamicObstacles(
        safety, context.people ? *context.people : std::vector<perception::PersonForecast>{});
}

void DaepPlanner::fitOverHeads(const PlanningContext& context, SafetyParams& safety) const {
    const double top = context.explorationBox.max.z() - 0.5 * safety.droneSize.z();
    const double room = top - kOverHeads - safety.bodyTop();
    if (room < params_.overHeadsMinClearance - kHeightTolerance)
        return;  // no room over the heads: the flight space's ceiling stands
    // Up there the map, not the box shrunk by the robot radius, says what is flyable.
    safety.ceiling = std::max(safety.ceiling, top);
    safety.overheadClearance = std::min(safety.clearance, room);
}

void DaepPlanner::observePeople(const PlanningContext& context) {
    flight().faceTravel = isOn(params_.faceTravel, context.peopleFromCamera);
    obstacles_ = obstaclesOf(context);
    peopleSeen_ = peopleSeen_ || !obstacles_.people().empty();
    if (dfm_.width() == 0) {
        dfm_ = DynamicFrequencyMap(context.explorationBox, params_.dfmCellSize);
        BlindWatchParams blind = params_.blind;
        blind.range = std::min(blind.range, context.peopleRange);  // unseen beyond the camera's
        watch_ = BlindWatch(dfm_, blind);
    }
    guardingBlind_ = isOn(params_.blindGuard, context.peopleFromCamera);
    flyingOverHeads_ = isOn(params_.flyOverHeads, context.peopleFromCamera);
    const bool dfmDue = context.time >= lastObservation_ + kDfmPeriod;
    if (!guardingBlind_ && !dfmDue)
        return;  // nobody needs where people were measured now
    std::vector<Eigen::Vector2d> seen;
    for (const perception::PersonForecast& f : obstacles_.people())
        if (context.time - f.time <= kDfmFreshness)
            seen.push_back(f.at(context.time).mean);
    if (guardingBlind_)
        watch_.see(context.pose, gainEvaluator().params().hfov, context.time, dfm_, seen,
                   context.map);
    if (!dfmDue)
        return;
    lastObservation_ = context.time;
    for (const Eigen::Vector2d& xy : seen)
        dfm_.add(xy);
}

std::vector<TimedSegment> DaepPlanner::timedMoves(const PlanningContext& context, const Plan& plan,
                                                  std::size_t fromWaypoint) const {
    std::vector<TimedSegment> moves;
    FlatPose at = context.pose;
    double t = context.time;
    for (std::size_t k = fromWaypoint; k < plan.waypoints.size(); ++k) {
        const FlatPose& next = plan.waypoints[k].pose;
        moves.push_back(timedSegment(at, next, t, context.motion.speed, context.motion.yawRate));
        t = moves.back().end();
        at = next;
    }
    return moves;
}

Plan DaepPlanner::cutAtFirstUnsafe(const PlanningContext& context, Plan plan) const {
    const std::vector<TimedSegment> moves = timedMoves(context, plan, 0);
    std::size_t safe = 0;
    while (safe < moves.size() && obstacles_.isSafe(moves[safe]))
        ++safe;
    if (safe < plan.waypoints.size()) {
        plan.cutTo(safe);
        plan.reason += safe == 0 ? "; first move unsafe" : "; cut before an unsafe move";
    }
    return plan;
}

Plan DaepPlanner::wait(const PlanningContext& context, const std::string& why) const {
    Plan plan;
    plan.status = Plan::Status::Path;
    // Waiting, the drone turns on the spot a quarter at a time: the camera sweeps around, so
    // people coming from where it was not looking are seen (and the turn is checked as a move).
    const FlatPose look{context.pose.position, wrapAngle(context.pose.yaw + M_PI / 2)};
    if (timeAware_.timedValid(context.pose, context.time, look)) {
        plan.waypoints.push_back(
            {look, context.time + context.motion.travelTime(context.pose, look)});
        plan.reason = "wait, looking around: " + why;
        return plan;
    }
    plan.waitFor(params_.waitTime);
    plan.reason = "wait: " + why;
    return plan;
}

std::optional<BlindThreat> DaepPlanner::blindThreat(const PlanningContext& context,
                                                    const Eigen::Vector3d& stop,
                                                    double until) const {
    if (!guardingBlind_ || stop.z() >= obstacles_.clearedHeight())
        return std::nullopt;  // nobody reaches a drone over their head
    const BlindThreat threat =
        watch_.worstThreat(dfm_, stop.head<2>(), context.time, until, obstacles_.bodyKeepOut());
    if (threat.excess <= 0.0)
        return std::nullopt;
    return threat;
}

const Waypoint* DaepPlanner::guardedStop(const Plan& plan) const {
    if (!overHeadsHeight())
        return &plan.waypoints.front();
    // Flying over the heads, the first stop among the people is where they may come.
    for (const Waypoint& w : plan.waypoints)
        if (w.pose.position.z() < obstacles_.clearedHeight())
            return &w;
    return nullptr;
}

std::optional<DaepPlanner::Look> DaepPlanner::bestLook(const PlanningContext& context,
                                                       const Waypoint& stop,
                                                       const BlindThreat& threat) const {
    // At the worst walkway first, then all around, the smaller turns first.
    const Eigen::Vector2d d = threat.cell - context.pose.position.head<2>();
    std::vector<double> yaws{std::atan2(d.y(), d.x())};
    for (int k = 1; k < kLookDirections; ++k)
        yaws.push_back(context.pose.yaw + 2.0 * M_PI * k / kLookDirections);
    std::stable_sort(yaws.begin() + 1, yaws.end(), [&](double a, double b) {
        return std::abs(wrapAngle(a - context.pose.yaw)) <
               std::abs(wrapAngle(b - context.pose.yaw));
    });
    const double hfov = gainEvaluator().params().hfov;
    const double stay = stop.arrivalTime - context.time + params_.blind.stopTime;
    std::optional<Look> best;
    for (const double yaw : yaws) {
        const FlatPose pose{context.pose.position, wrapAngle(yaw)};
        if (!timeAware_.timedValid(context.pose, context.time, pose))
            continue;
        const double end = context.time + context.motion.travelTime(context.pose, pose);
        // Re-planned after the look, the drone reaches the stop as much later.
        const BlindThreat left = watch_.afterLook(pose, hfov, end, dfm_, context.map)
                                     .worstThreat(dfm_, stop.pose.position.head<2>(), end,
                                                  end + stay, obstacles_.bodyKeepOut());
        const double threatLeft = std::max(0.0, left.excess);
        if (!best || threatLeft < best->threatLeft - 1e-9)
            best = Look{pose, end, threatLeft};
    }
    return best;
}

bool DaepPlanner::lookBeforeStop(const PlanningContext& context, Plan& plan) {
    const Waypoint* stop = guardedStop(plan);
    const std::optional<BlindThreat> threat =
        looks_ < params_.blind.maxLooks && stop != nullptr
            ? blindThreat(context, stop->pose.position, stop->arrivalTime + params_.blind.stopTime)
            : std::nullopt;
    if (!threat) {
        looks_ = 0;
        return false;
    }
    const std::optional<Look> look = bestLook(context, *stop, *threat);
    if (!look) {
        looks_ = 0;
        return false;
    }
    ++looks_;
    std::ostringstream why;
    why << "look: a person unseen could reach the next stop (by " << threat->excess << " m) from "
        << (threat->lost ? "where a person lost may be, at " : "the walkway at ")
        << threat->cell.x() << ", " << threat->cell.y() << "; the look leaves " << look->threatLeft
        << " m";
    Plan out;
    out.status = Plan::Status::Path;
    out.waypoints.push_back({look->pose, look->end});
    out.tree = std::move(plan.tree);
    out.reason = why.str();
    plan = std::move(out);
    return true;
}

Plan DaepPlanner::escape(const PlanningContext& context) {
    observePeople(context);
    return bestEscape(context);
}

std::optional<Plan> DaepPlanner::evasion(const PlanningContext& context, double until) {
    const Eigen::Vector3d& here = context.pose.position;
    const double end = std::min(until, context.time + params_.evasionHorizon);
    if (obstaclesOf(context).isSafeToHover(here, context.time, end))
        return std::nullopt;
    Plan plan = escape(context);
    if (!plan.escape)
        return std::nullopt;  // no move is free of static obstacles: go on with what it does
    return plan;
}

namespace {

/** Clearance (m) an unsafe escape may give up to stay off walkways unseen people may use. */
constexpr double kWalkwayMargin = 0.2;
/** A way out replaces the straight escapes when it spends this much less time in a body (s)... */
constexpr double kWayOutMargin = 0.4;
/** ...and its first this many metres are flown before the next judgement. */
constexpr double kWayOutLeg = 0.8;

/** One candidate escape: where to, how much clearance it keeps, and whether it is in view. */
struct Escape {
    FlatPose goal;
    double gap = -std::numeric_limits<double>::infinity();
    /**
     * The gap once the move is under way: from where the drone starts every escape shares
     * the gap, so unsafe escapes are told apart by where they lead.
     */
    double gapUnderWay = -std::numeric_limits<double>::infinity();
    double distance = 0.0;
    bool seen = false;
    bool offWalkways = true;  ///< no unseen person could walk in while the drone is there

    /**
     * Any safe escape beats an unsafe one. Among safe ones, one no unseen walker threatens
     * beats one they do, then one the camera looks along beats a blind one (people not
     * tracked may stand there), then the shorter, then the clearer; among unsafe ones, the
     * clearer under way, off walkways unless that costs more than kWalkwayMargin.
     */
    bool betterThan(const Escape& o) const {
        const bool safe = gap > 0.0, otherSafe = o.gap > 0.0;
        if (safe != otherSafe)
            return safe;
        if (!safe) {
            // An unseen walker is as real as a tracked one: off the walkways is worth a
            // little of the clearance from the people tracked.
            if (offWalkways != o.offWalkways)
                return offWalkways ? gapUnderWay > o.gapUnderWay - kWalkwayMargin
                                   : gapUnderWay > o.gapUnderWay + kWalkwayMargin;
            return gapUnderWay > o.gapUnderWay + 1e-9;
        }
        if (offWalkways != o.offWalkways)
            return offWalkways;
        if (seen != o.seen)
            return seen;
        if (std::abs(distance - o.distance) > 1e-9)
            return distance < o.distance;
        return gap > o.gap + 1e-9;
    }
};

}  // namespace

std::optional<double> DaepPlanner::overHeadsHeight() const {
    return flyingOverHeads_ ? escapeUpHeight() : std::nullopt;
}

std::optional<double> DaepPlanner::escapeUpHeight() const {
    const double height = obstacles_.clearedHeight() + kOverHeads;
    if (height > obstacles_.params().ceiling + kHeightTolerance)
        return std::nullopt;
    return height;
}

namespace {

/**
 * The point straight above `from` at `height`: when there is a height, it is above `from`, and
 * the climb is `flyable`.
 */
template <typename Flyable>
std::optional<Eigen::Vector3d> straightUp(const Eigen::Vector3d& from, std::optional<double> height,
                                          const Flyable& flyable) {
    if (!height || !(*height > from.z()))
        return std::nullopt;
    const Eigen::Vector3d up(from.x(), from.y(), *height);
    if (!flyable(up))
        return std::nullopt;
    return up;
}

}  // namespace

template <typename Visit>
void DaepPlanner::forEachEscapeGoal(const PlanningContext& context, const Eigen::Vector3d& from,
                                    Visit&& visit, bool throughImprints) const {
    const mapping::ExplorationMap& map = *context.map;
    const double r = params().robotRadius, h = params().bodyHalfHeight;
    const Aabb box = shrink(context.explorationBox, r);
    const bool leavingBlocked = !map.isSegmentFree(from, from, r);
    const bool leavingStatic = throughImprints && !map.isSegmentFreeThroughImprints(from, from, r);
    // Through imprints: what the drone's own ball touches that is not an imprint must fall
    // behind, so the move starts a radius out.
    const auto flyableThroughImprints = [&](const Eigen::Vector3d& to) {
        const double length = (to - from).norm();
        const Eigen::Vector3d start =
            leavingStatic ? Eigen::Vector3d(from + (to - from) * std::min(1.0, r / length)) : from;
        return map.isSegmentFreeThroughImprints(to, to, r) &&
               map.isSegmentFreeThroughImprints(start, to, r);
    };
    const auto flyable = [&](const Eigen::Vector3d& to) {
        return throughImprints ? flyableThroughImprints(to)
                               : segmentFlyable(map, from, to, r, h, leavingBlocked);
    };
    // Straight up, over the heads: there nobody, seen or not, can reach the drone.
    if (const std::optional<Eigen::Vector3d> up = straightUp(from, overHeadsHeight(), flyable);
        up && !visit(*up, context.pose.yaw, 0.0))
        return;
    for (const double distance : {0.4, 0.8, 1.2, 1.6}) {
        for (int k = 0; k < 16; ++k) {
            for (const double dz : {0.0, 0.4, -0.4}) {
                const double a = 2.0 * M_PI * k / 16.0;
                const Eigen::Vector3d to =
                    from + Eigen::Vector3d(distance * std::cos(a), distance * std::sin(a), dz);
                if (!box.contains(to) || !flyable(to))
                    continue;
                if (!visit(to, a, distance))
                    return;
            }
        }
    }
}

std::optional<Eigen::Vector3d> DaepPlanner::escapeUpGoal(const PlanningContext& context) const {
    const Eigen::Vector3d& from = context.pose.position;
    const mapping::ExplorationMap& map = *context.map;
    const double r = params().robotRadius;
    return straightUp(from, escapeUpHeight(), [&](const Eigen::Vector3d& up) {
        return segmentFlyable(map, from, up, r, params().bodyHalfHeight,
                              !map.isSegmentFree(from, from, r));
    });
}

bool DaepPlanner::isTrap(const PlanningContext& context, const Eigen::Vector3d& stop,
                         double arrival) const {
    if (obstacles_.empty() || params_.trapHorizon <= 0.0)
        return false;
    const double keepOut = obstacles_.bodyKeepOut();
    const Eigen::Vector2d at = stop.head<2>();
    // Where each person who could walk up to the stop within trap_horizon_s of the drone's
    // arrival will be then; they may turn towards the drone at any moment.
    std::vector<Eigen::Vector2d> walkers;
    for (const perception::PersonForecast& f : obstacles_.people()) {
        const Eigen::Vector2d q = f.at(std::min(arrival, f.time + params_.safety.horizon)).mean;
        const double speed = std::max(params_.blind.walkSpeed, f.velocity().norm());
        if (speed > 0.0 && ((q - at).norm() - keepOut) / speed <= params_.trapHorizon)
            walkers.push_back(q);
    }
    // Each needs an escape out of their way: a goal farther than the keep-out from their
    // straight walk to the stop.
    std::vector<bool> escaped(walkers.size(), false);
    std::size_t left = walkers.size();
    if (left > 0)
        forEachEscapeGoal(context, stop, [&](const Eigen::Vector3d& to, double, double) {
            for (std::size_t i = 0; i < walkers.size(); ++i)
                if (!escaped[i] &&
                    distanceToSegment<Eigen::Vector2d>(to.head<2>(), walkers[i], at) > keepOut) {
                    escaped[i] = true;
                    --left;
                }
            return left > 0;
        });
    return left > 0;
}

Plan DaepPlanner::cutBeforeTrap(const PlanningContext& context, Plan plan) const {
    for (std::size_t k = 0; k < plan.waypoints.size(); ++k) {
        const Waypoint& stop = plan.waypoints[k];
        if (!isTrap(context, stop.pose.position, stop.arrivalTime))
            continue;
        plan.cutTo(k);
        plan.reason += k == 0 ? "; first stop a trap" : "; cut before a trap";
        break;
    }
    return plan;
}

Plan DaepPlanner::bestEscape(const PlanningContext& context) const {
    const Eigen::Vector3d& from = context.pose.position;
    const double halfFov = 0.5 * gainEvaluator().params().hfov;
    bool any = false;
    Escape best;
    const auto consider = [&](const Eigen::Vector3d& to, double a, double distance) {
        Escape e;
        e.distance = distance;
        e.seen = std::abs(wrapAngle(a - context.pose.yaw)) <= halfFov;
        // Keep the heading: no turn, the drone moves at once.
        e.goal = {to, context.pose.yaw};
        const TimedSegment move = timedSegment(context.pose, e.goal, context.time,
                                               context.motion.speed, context.motion.yawRate);
        TimedSegment hover;
        hover.from = hover.to = to;
        hover.start = move.end();
        hover.turnTime = std::max(0.0, context.time + params_.evasionHorizon - move.end());
        const double hoverGap = obstacles_.clearance(hover);
        e.gap = std::min(obstacles_.clearance(move), hoverGap);
        e.gapUnderWay = std::min(
            obstacles_.clearance(move.after(move.start + params_.safety.timeStep)), hoverGap);
        e.offWalkways = !blindThreat(context, to, hover.end()).has_value();
        if (!any || e.betterThan(best))
            best = e;
        any = true;
        return true;
    };
    forEachEscapeGoal(context, from, consider);
    // Not cruising over the heads, the drone still climbs over them when nothing on its own
    // level keeps clear: cornered where a walker turns back, it is the way that needs no room.
    if (!flyingOverHeads_ && (!any || best.gap <= 0.0))
        if (const std::optional<Eigen::Vector3d> up = escapeUpGoal(context))
            consider(*up, context.pose.yaw, 0.0);
    // Walled in by the imprints of people the camera missed (a queue walking past a corner):
    // they walk on, walls do not.
    bool throughImprints = false;
    if (!any) {
        forEachEscapeGoal(context, from, consider, true);
        throughImprints = any;
    }
    if (!any)
        return wait(context, "a person is coming and no escape is free of static obstacles");
    if (best.gap <= 0.0)
        if (std::optional<Plan> out = wayOut(context, best.goal.position))
            return std::move(*out);
    Plan plan;
    plan.status = Plan::Status::Path;
    plan.escape = true;
    plan.waypoints.push_back(
        {best.goal, context.time + context.motion.travelTime(context.pose, best.goal)});
    std::ostringstream why;
    why << "evasion: " << (best.seen ? "" : "blind ") << "escape of " << best.distance
        << " m with clearance " << best.gap << " m" << (throughImprints ? " through imprints" : "");
    plan.reason = why.str();
    return plan;
}

std::optional<Plan> DaepPlanner::wayOut(const PlanningContext& context,
                                        const Eigen::Vector3d& straight) const {
    WayOutParams search;
    search.robotRadius = params().robotRadius;
    search.bodyHalfHeight = params().bodyHalfHeight;
    const double hoverUntil = context.time + params_.evasionHorizon;
    const std::optional<WayOut> way =
        findWayOut(*context.map, context.explorationBox, obstacles_, context.pose, context.time,
                   context.motion, hoverUntil, search);
    const WayOut escape = judgeWay(obstacles_, context.pose.position, context.time, {straight},
                                   context.motion, hoverUntil);
    // Less time inside the bodies, and never deeper in them than the straight escape goes.
    if (!way || way->exposure > escape.exposure - kWayOutMargin ||
        way->deepest < escape.deepest - 1e-9)
        return std::nullopt;
    std::vector<Waypoint> legs;  // at the drone's heading: no turn, it moves at once
    Eigen::Vector3d at = context.pose.position;
    double flown = 0.0;
    for (const Eigen::Vector3d& q : way->path) {
        flown += (q - at).norm();
        legs.push_back({{q, context.pose.yaw}, 0.0});
        at = q;
        if (flown >= kWayOutLeg - 1e-9)
            break;  // then judged again, from there
    }
    Plan plan;
    plan.status = Plan::Status::Path;
    plan.escape = true;
    plan.waypoints = FlightModel{context.motion, false}.flown(context.pose, context.time, legs);
    std::ostringstream why;
    why << "evasion: way out of " << way->length << " m (" << flown << " m now), " << way->exposure
        << " s in a body (the best straight escape " << escape.exposure << " s)";
    plan.reason = why.str();
    return plan;
}

Plan DaepPlanner::plan(const PlanningContext& context) {
    observePeople(context);
    const bool hoverSafe = obstacles_.isSafeToHover(context.pose.position, context.time,
                                                    context.time + params_.evasionHorizon);
    Plan plan = AepPlanner::plan(context);
    if (plan.status == Plan::Status::Finished)
        return hoverSafe ? plan : bestEscape(context);  // get clear first, then judge again
    plan = cutBeforeTrap(context, cutAtFirstUnsafe(context, std::move(plan)));
    if (!plan.waypoints.empty()) {
        plan = overHeads(context, std::move(plan));
        if (lookBeforeStop(context, plan))  // a stop over heads needs no look
            plan = overHeads(context, std::move(plan));
        return plan;
    }
    if (!hoverSafe)
        return bestEscape(context);
    return overHeads(context, wait(context, plan.reason));
}

bool DaepPlanner::keepsViewLow(const PlanningContext& context, const Plan& plan,
                               const Eigen::Vector3d& raisedGoal) const {
    // The goal's gain was judged where the planner put it. Over the heads the view may miss
    // what it was for: through a doorway, under a lintel the drone cannot see past from above.
    constexpr double kViewKept = 0.5;
    const Eigen::Vector3d& goal = plan.waypoints.back().pose.position;
    return plan.gain > 0.0 && raisedGoal != goal &&
           gainEvaluator().bestYaw(*context.map, raisedGoal).gain < kViewKept * plan.gain;
}

Plan DaepPlanner::overHeads(const PlanningContext& context, Plan plan) const {
    if (plan.status != Plan::Status::Path || plan.escape)
        return plan;
    const std::optional<double> height = overHeadsHeight();
    if (!height)
        return plan;
    OverHeadsSpace space;
    space.map = context.map;
    space.radius = params().robotRadius;
    space.halfHeight = params().bodyHalfHeight;
    space.height = *height;
    const Eigen::Vector3d& start = context.pose.position;
    space.leavingBlocked = !context.map->isSegmentFree(start, start, space.radius);
    std::vector<Waypoint> raised = plan.waypoints;
    bool any = raiseStops(space, start, raised);
    if (any && keepsViewLow(context, plan, raised.back().pose.position)) {
        raised.back() = plan.waypoints.back();
        any = !samePositions(raised, plan.waypoints);
    }
    // Kept high between the stops if that is clear of the people, else the raised stops alone;
    // either way it stops over the heads before going down among the people again.
    for (std::vector<Waypoint> way : {stayHigh(space, start, raised), raised}) {
        way.resize(beforeDescent(space, start, way));
        way = climbBeforeTurning(space, context.pose, way);
        if (!any && samePositions(way, plan.waypoints))
            return plan;  // nothing raised, added or cut
        Plan candidate = plan;
        candidate.waypoints =
            FlightModel{context.motion, false}.flown(context.pose, context.time, way);
        candidate = cutAtFirstUnsafe(context, std::move(candidate));
        if (!way.empty() && candidate.waypoints.size() == way.size()) {
            candidate.reason += "; over heads";
            return candidate;
        }
    }
    return plan;
}

bool DaepPlanner::keepFlying(const PlanningContext& context, const Plan& plan,
                             std::size_t nextWaypoint) {
    observePeople(context);
    if (!AepPlanner::keepFlying(context, plan, nextWaypoint))
        return false;
    if (plan.escape)
        return !freshEscapeBetter(context, plan, nextWaypoint);
    return movesClear(obstacles_, context, plan, nextWaypoint);
}

namespace {

std::vector<Eigen::Vector3d> positionsFrom(const Plan& plan, std::size_t first) {
    std::vector<Eigen::Vector3d> out;
    for (std::size_t i = first; i < plan.waypoints.size(); ++i)
        out.push_back(plan.waypoints[i].pose.position);
    return out;
}

}  // namespace

bool DaepPlanner::freshEscapeBetter(const PlanningContext& context, const Plan& escape,
                                    std::size_t nextWaypoint) const {
    const Eigen::Vector3d& here = context.pose.position;
    const double hoverUntil = context.time + params_.evasionHorizon;
    const WayOut flying = judgeWay(obstacles_, here, context.time,
                                   positionsFrom(escape, nextWaypoint), context.motion, hoverUntil);
    if (flying.exposure <= 0.0)
        return false;
    const Plan fresh = bestEscape(context);
    if (!fresh.escape)
        return false;
    const WayOut instead = judgeWay(obstacles_, here, context.time, positionsFrom(fresh, 0),
                                    context.motion, hoverUntil);
    // The same rule that lets a way out replace the straight escapes.
    return instead.exposure < flying.exposure - kWayOutMargin &&
           instead.deepest >= flying.deepest - 1e-9;
}

bool DaepPlanner::movesClear(const DynamicObstacles& bodies, const PlanningContext& context,
                             const Plan& plan, std::size_t nextWaypoint) const {
    for (const TimedSegment& move : timedMoves(context, plan, nextWaypoint)) {
        if (move.start > context.time + params_.safety.horizon)
            break;
        if (!bodies.isSafe(move, params_.recheckClearanceScale))
            return false;
    }
    return true;
}

UnseenWatch DaepPlanner::unseenWatchAt(const Eigen::Vector2d& xy, double time) const {
    if (!guardingBlind_)
        return UnseenWatch::None;
    const double lost = watch_.lostFrom(xy, time);
    if (!watch_.walkwayAt(dfm_, xy))
        return lost <= time ? UnseenWatch::Lost : UnseenWatch::NoWalkway;
    return std::min(watch_.unseenFrom(xy), lost) <= time ? UnseenWatch::Open : UnseenWatch::Cleared;
}

bool DaepPlanner::startsSafely(const PlanningContext& context, const Plan& plan) const {
    return plan.escape || movesClear(obstaclesOf(context), context, plan, 0);
}

}  // namespace daep::planning
