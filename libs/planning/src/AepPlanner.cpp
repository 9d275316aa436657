#include "daep/planning/AepPlanner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "daep/common/Config.h"
#include "daep/common/ConfigChecks.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/planning/FlightSpace.h"

namespace daep::planning {
namespace {

constexpr double kTrailSpacing = 0.5;

}  // namespace

AepParams AepParams::fromConfig(const mrpt::config::CConfigFileBase& config,
                                const std::string& section) {
    const ConfigReader r(config, section);
    AepParams p;
    p.extensionRange = requirePositive(r, "extension_range");
    p.samplingRadius = requirePositive(r, "max_sampling_radius");
    p.rewireRadius = requirePositive(r, "rewire_radius");
    p.initialIterations = requireIntAtLeast(r, "initial_iterations", 1);
    p.cutoffIterations = requireIntAtLeast(r, "cutoff_iterations", p.initialIterations);
    p.maxSamples = requireIntAtLeast(r, "max_samples", 1);
    p.lambda = requireNonNegative(r, "lambda");
    p.zeroGain = requireNonNegative(r, "zero_gain");
    p.view.sigmaThreshold = requireNonNegative(r, "sigma_thresh");
    p.gp.lengthScale = requirePositive(r, "gp_length_scale");
    p.gp.signalSigma = requirePositive(r, "gp_sigma_f");
    p.gp.noiseSigma = requirePositive(r, "gp_sigma_n");
    p.view.gpRadius = requirePositive(r, "gp_radius");
    p.view.gpMaxNeighbours = requireIntAtLeast(r, "gp_max_neighbours", 1);
    p.view.cacheThreshold = requireNonNegative(r, "cache_node_threshold");
    p.cacheUpdateRadius = requireNonNegative(r, "cache_update_radius");
    p.globalMinNodes = requireIntAtLeast(r, "global_min_nodes", 1);
    p.globalMaxNodes = requireIntAtLeast(r, "global_max_nodes", p.globalMinNodes);
    p.globalMaxSamples = requireIntAtLeast(r, "global_max_samples", 1);
    p.globalGoalBias = requireNonNegative(r, "global_goal_bias");
    if (p.globalGoalBias > 1.0)
        failRange(r, "global_goal_bias", p.globalGoalBias, "must be <= 1");
    p.goalRadius = requirePositive(r, "goal_radius");
    p.globalPlannerCounter = requireIntAtLeast(r, "global_planner_counter", 0);
    p.globalRetryWait = requireNonNegative(r, "global_retry_wait_s");
    p.mapFrontiers = r.requireBool("map_frontiers");
    p.mapPaths = r.requireBool("map_paths");
    const ConfigReader planning(config, "planning");
    p.robotRadius = requireNonNegative(planning, "robot_radius");
    p.bodyHalfHeight = 0.5 * requirePositiveXyz(ConfigReader(config, "drone"), "box").z();
    p.crossUnknown =
        requireEnum<bool>(planning, "path_space", {{"known_free", false}, {"not_occupied", true}});
    return p;
}

AepPlanner::AepPlanner(const AepParams& params, const GainParams& gain, std::uint64_t seed)
    : params_(params),
      gain_(gain),
      gp_(params.gp),
      cache_(1.0),
      aepScore_(params.lambda),
      cachedView_(params.view, gain_, cache_, gp_, stats_),
      parts_{&pathSpace_, &aepScore_, &cachedView_, &flight_},
      rng_(seed),
      tree_(params.extensionRange, params.rewireRadius) {}

void AepPlanner::compose(const MoveValidator& moves, const BranchObjective& objective,
                         ViewModel& view) {
    parts_ = {&moves, &objective, &view, &flight_};
}

YawGain AepPlanner::evaluateGain(const mapping::ExplorationMap& map, const Eigen::Vector3d& p) {
    return cachedView_.estimate(map, p);
}

void AepPlanner::refreshCache(const mapping::ExplorationMap& map, const Eigen::Vector3d& pose) {
    trail_.push_back(pose);
    std::set<int> dirty;
    for (const Eigen::Vector3d& t : trail_)
        for (int id : cache_.near(t, params_.cacheUpdateRadius))
            dirty.insert(id);
    trail_.clear();
    for (int id : dirty) {
        const YawGain view = gain_.bestYaw(map, cache_.entry(id).position);
        ++stats_.cacheRefreshed;
        if (view.gain > params_.view.cacheThreshold) {
            cache_.update(id, view.yaw, view.gain);
        } else {
            cache_.remove(id);
            ++stats_.cacheDropped;
        }
    }
}

Eigen::Vector3d AepPlanner::sampleLocal(const Eigen::Vector3d& center) {
    Aabb window;
    for (int a = 0; a < 3; ++a) {
        window.min[a] = std::max(center[a] - params_.samplingRadius, samplingBox_.min[a]);
        window.max[a] = std::min(center[a] + params_.samplingRadius, samplingBox_.max[a]);
        if (window.min[a] > window.max[a])
            window.min[a] = window.max[a] =
                std::clamp(center[a], samplingBox_.min[a], samplingBox_.max[a]);
    }
    Eigen::Vector3d s = sampleInBox(window, rng_);
    for (int attempt = 0; attempt < 16 && (s - center).norm() > params_.samplingRadius; ++attempt)
        s = sampleInBox(window, rng_);
    return s;
}

void AepPlanner::resetTree(const PlanningContext& context, ExplorationTree::Growth growth) {
    tree_.reset(context.pose, context.time, rootFree_, samplingBox_, parts_, growth);
    best_ = -1;
}

void AepPlanner::growLocal(const PlanningContext& context) {
    best_ = tree().bestByScore();
    auto goodEnough = [&] { return best_ >= 0 && tree().node(best_).score > params_.zeroGain; };
    while (stats_.samples < params_.maxSamples && !context.deadline.passed() &&
           (tree().size() - 1 < params_.initialIterations ||
            (!goodEnough() && tree().size() - 1 < params_.cutoffIterations))) {
        ++stats_.samples;
        if (tree_.extend(sampleLocal(context.pose.position)) >= 0)
            best_ = tree().bestByScore();
    }
}

Plan AepPlanner::localPlan(const PlanningContext& context) {
    Plan plan;
    plan.tree = tree().edges();
    const TreeNode& best = tree().node(best_);
    const std::vector<int> branch = tree().branch(best_);
    const TreeNode& first = tree().node(branch.front());
    plan.status = Plan::Status::Path;
    plan.waypoints =
        flight_.flown(context.pose, context.time, {{{first.position, first.yaw}, 0.0}});
    plan.gain = first.gain;
    plan.score = best.score;
    for (std::size_t i = 1; i < branch.size(); ++i) {
        const TreeNode& n = tree().node(branch[i]);
        previousBranch_.push_back({n.position, n.yaw});
    }
    std::ostringstream why;
    why << "local: best branch value " << best.score << ", " << branch.size() << " deep, "
        << tree().size() - 1 << " nodes";
    plan.reason = why.str();
    return plan;
}

Plan AepPlanner::plan(const PlanningContext& context) {
    if (context.map == nullptr)
        throw std::invalid_argument("AepPlanner::plan: no map");
    stats_ = {};
    flight_.motion = context.motion;
    pathSpace_.bind(*context.map, params_.robotRadius, params_.bodyHalfHeight,
                    params_.crossUnknown);
    cachedView_.bind(*context.map);
    samplingBox_ = shrink(context.explorationBox, params_.robotRadius);
    if (params_.crossUnknown)
        samplingBox_.max.z() = context.explorationBox.max.z() - 0.5 * context.droneSize.z();
    rootFree_ = context.map->isSegmentFree(context.pose.position, context.pose.position,
                                           params_.robotRadius);
    refreshCache(*context.map, context.pose.position);
    resetTree(context, ExplorationTree::Growth::Views);
    tree_.reuseBranch(previousBranch_);
    previousBranch_.clear();
    growLocal(context);
    if (best_ >= 0 && tree().node(best_).score > params_.zeroGain) {
        globalFailures_ = 0;
        return localPlan(context);
    }
    if (context.deadline.passed())
        return planAtDeadline(context);
    return globalPlan(context, best_ >= 0 ? tree().node(best_).score : 0.0);
}

Plan AepPlanner::planAtDeadline(const PlanningContext& context) {
    if (best_ > 0 && tree().node(best_).score > 0.0) {
        Plan plan = localPlan(context);
        plan.reason = "deadline: " + plan.reason;
        return plan;
    }
    previousBranch_.clear();
    Plan plan;
    plan.status = Plan::Status::NoPath;
    plan.tree = tree().edges();
    plan.reason =
        "deadline: no branch with gain after " + std::to_string(tree().size() - 1) + " nodes";
    return plan;
}

bool AepPlanner::hasClearance(const Eigen::Vector3d& p) const {
    return samplingBox_.contains(p) && pathSpace_.staticValid(p, p, false);
}

void AepPlanner::cacheMapFrontiers(const PlanningContext& context) {
    // Viewpoints where the drone has its clearance in the path space and reaches them so,
    // within 1 m of the unknown; 1 m apart, and at most kMaxViews ray casts.
    constexpr int kReach = 5;
    constexpr double kSpacing = 1.0;
    constexpr std::size_t kMaxViews = 40;
    const auto usable = [this](const Eigen::Vector3d& p) { return hasClearance(p); };
    for (const Eigen::Vector3d& p : context.map->frontierViewpoints(context.pose.position, usable,
                                                                    kReach, kSpacing, kMaxViews)) {
        if (context.deadline.passed())
            return;
        if (!cache_.near(p, kSpacing, 1).empty())
            continue;  // a frontier there is cached already
        cachedView_.remember(p, cachedView_.rayCast(*context.map, p));
    }
}

bool AepPlanner::verifyFrontier(const mapping::ExplorationMap& map, int id) {
    const YawGain view = cachedView_.rayCast(map, cache_.entry(id).position);
    if (view.gain <= params_.view.cacheThreshold) {
        cache_.remove(id);
        return false;
    }
    cache_.update(id, view.yaw, view.gain);
    return true;
}

bool AepPlanner::growGlobal(const PlanningContext& context, const std::vector<int>& frontiers) {
    resetTree(context, ExplorationTree::Growth::Ways);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_int_distribution<std::size_t> pick(0,
                                                    frontiers.empty() ? 0 : frontiers.size() - 1);
    const Eigen::Vector3d& root = context.pose.position;
    bool reached = false;
    std::set<int> verified;  // cached gains may be stale far from where the drone flew
    while (
        stats_.samples < params_.globalMaxSamples && tree().size() - 1 < params_.globalMaxNodes &&
        !(reached && tree().size() - 1 >= params_.globalMinNodes) && !context.deadline.passed()) {
        ++stats_.samples;
        const bool towardsGoal = !frontiers.empty() && unit(rng_) < params_.globalGoalBias;
        const Eigen::Vector3d sample = towardsGoal ? cache_.entry(frontiers[pick(rng_)]).position
                                                   : sampleInBox(samplingBox_, rng_);
        const int added = tree_.extend(sample);
        if (added < 0)
            continue;
        const Eigen::Vector3d p = tree().node(added).position;
        if ((p - root).norm() <= params_.goalRadius)
            continue;
        // The global tree also surveys the known free space for viewpoints the local trees
        // never reached: their gains enter the cache like any other.
        tree_.setGain(added, evaluateGain(*context.map, p).gain);
        for (int id : cache_.near(p, params_.goalRadius)) {
            if (verified.insert(id).second && !verifyFrontier(*context.map, id))
                continue;
            reached = reached || cache_.entry(id).alive;
        }
    }
    return reached;
}

bool AepPlanner::peopleBlockFrontiers(const PlanningContext& context) {
    if (!parts_.moves->checksPeople())
        return false;
    const TreeParts composed = parts_;
    parts_.moves = &pathSpace_;
    const bool reached = growGlobal(context, cache_.liveIds());
    parts_ = composed;
    return reached ||
           (tree().size() <= 1 && parts_.view->peopleInView(context.pose.position, context.time));
}

Plan AepPlanner::globalPlan(const PlanningContext& context, double localScore) {
    stats_.global = true;
    previousBranch_.clear();
    // The local planner just judged the drone's surroundings: frontiers there are done.
    for (int id : cache_.near(context.pose.position, params_.goalRadius))
        cache_.remove(id);
    if (params_.mapFrontiers && cache_.size() == 0)
        cacheMapFrontiers(context);
    const std::vector<int> frontiers = cache_.liveIds();
    Plan plan;
    plan.score = localScore;
    std::ostringstream why;
    growGlobal(context, frontiers);
    plan.tree = tree().edges();
    // Cheapest way to each frontier: a tree node within goal_radius, then straight to it.
    std::vector<std::pair<double, std::pair<int, int>>> options;  // (cost, (frontier, node))
    for (int i = 0; i < tree().size(); ++i) {
        const TreeNode& n = tree().node(i);
        for (int f : cache_.near(n.position, params_.goalRadius))
            options.push_back({n.cost + (cache_.entry(f).position - n.position).norm(), {f, i}});
    }
    std::sort(options.begin(), options.end());
    std::set<int> tried;
    for (const auto& [cost, choice] : options) {
        const auto [f, node] = choice;
        if (!tried.insert(f).second || !cache_.entry(f).alive ||
            (cache_.entry(f).position - context.pose.position).norm() <= params_.goalRadius)
            continue;
        if (!verifyFrontier(*context.map, f))
            continue;
        std::vector<Eigen::Vector3d> path{context.pose.position};
        for (int i : tree().branch(node))
            path.push_back(tree().node(i).position);
        Plan out = frontierPlan(context, shortcut(context, withFrontier(path, f)), f);
        out.tree = std::move(plan.tree);
        out.score = localScore;
        why << "global: frontier gain " << out.gain << " at path cost " << cost << ", "
            << cache_.size() << " frontiers, " << tree().size() - 1 << " nodes";
        out.reason = why.str();
        return out;
    }
    if (context.deadline.passed()) {  // cut short: no judgement on the frontiers
        plan.status = Plan::Status::NoPath;
        why << "deadline: global tree cut at " << tree().size() - 1 << " nodes, no path yet";
        plan.reason = why.str();
        return plan;
    }
    if (peopleBlockFrontiers(context)) {
        plan.status = Plan::Status::NoPath;
        why << "global: people block the way to " << cache_.size() << " frontiers";
        plan.reason = why.str();
        return plan;
    }
    if (mayBeHemmedByPeople() && tree().size() <= 1 && !rootFree_) {
        // Nothing flyable around the drone, which came here through free space: what hems it
        // in was mapped since, and among people that is someone's imprint (a head passing
        // under it). The camera clears it; it says nothing of the frontiers.
        plan.status = Plan::Status::NoPath;
        why << "global: hemmed in where it hovers, by what was mapped since it came";
        plan.reason = why.str();
        return plan;
    }
    if (params_.mapPaths) {
        Plan out = mapPathPlan(context);
        if (out.status == Plan::Status::Path) {
            out.tree = std::move(plan.tree);
            out.score = localScore;
            why << "global, through the map's free cells: frontier gain " << out.gain << ", "
                << cache_.size() << " frontiers, " << out.waypoints.size() << " waypoints; "
                << tree().size() - 1 << " nodes reached none";
            out.reason = why.str();
            return out;
        }
    }
    ++globalFailures_;
    // Frontiers a tree sample saw may all lie out of reach now (the map around them filled
    // in); the map's own frontier is looked for from the drone through space it can fly.
    if (params_.mapFrontiers)
        cacheMapFrontiers(context);
    const bool givingUp =
        params_.globalPlannerCounter > 0 && globalFailures_ >= params_.globalPlannerCounter;
    if (givingUp || cache_.size() == 0) {
        plan.status = Plan::Status::Finished;
        why << (cache_.size() == 0 ? "no frontiers left" : "no frontier reachable") << " after "
            << globalFailures_ << " global plans";
    } else {
        plan.waitFor(params_.globalRetryWait);
        why << "global: no path to any of " << cache_.size() << " frontiers (" << tree().size() - 1
            << " nodes)";
    }
    plan.reason = why.str();
    return plan;
}

std::vector<Eigen::Vector3d> AepPlanner::withFrontier(std::vector<Eigen::Vector3d> path,
                                                      int f) const {
    const Eigen::Vector3d& frontier = cache_.entry(f).position;
    if (samplingBox_.contains(frontier) && pathSpace_.staticValid(path.back(), frontier, false))
        path.push_back(frontier);
    return path;
}

Plan AepPlanner::frontierPlan(const PlanningContext& context,
                              const std::vector<Eigen::Vector3d>& path, int f) {
    globalFailures_ = 0;
    Plan out = pathPlan(context, path, cache_.entry(f).yaw);
    out.gain = cache_.entry(f).gain;
    return out;
}

Plan AepPlanner::mapPathPlan(const PlanningContext& context) {
    // A found frontier whose gain is gone (re-cast) is dropped, and the search runs again.
    constexpr int kMaxSearches = 3;
    const Eigen::Vector3d& root = context.pose.position;
    const auto usable = [this](const Eigen::Vector3d& p) { return hasClearance(p); };
    Plan none;
    none.status = Plan::Status::NoPath;
    for (int search = 0; search < kMaxSearches && !context.deadline.passed(); ++search) {
        int goal = -1;
        const auto nearFrontier = [&](const Eigen::Vector3d& p) {
            for (int f : cache_.near(p, params_.goalRadius))
                if (cache_.entry(f).alive &&
                    (cache_.entry(f).position - root).norm() > params_.goalRadius) {
                    goal = f;
                    return true;
                }
            return false;
        };
        const std::vector<Eigen::Vector3d> cells =
            context.map->freeCellPath(root, usable, nearFrontier);
        if (cells.empty())
            return none;
        if (!verifyFrontier(*context.map, goal))
            continue;
        const std::vector<Eigen::Vector3d> path = shortcut(context, withFrontier(cells, goal));
        for (std::size_t k = 1; k < path.size(); ++k)
            if (!pathSpace_.staticValid(path[k - 1], path[k], k == 1 && !rootFree_))
                return none;
        return frontierPlan(context, path, goal);
    }
    return none;
}

std::vector<Eigen::Vector3d> AepPlanner::shortcut(const PlanningContext& context,
                                                  const std::vector<Eigen::Vector3d>& path) const {
    FlatPose at = context.pose;
    double time = context.time;
    auto headingTo = [&](std::size_t b) {
        return FlatPose{path[b], headingTowards(at.position, path[b], at.yaw)};
    };
    auto clear = [&](std::size_t a, std::size_t b) {
        return pathSpace_.staticValid(path[a], path[b], a == 0 && !rootFree_) &&
               parts_.moves->timedValid(at, time, headingTo(b));
    };
    std::vector<Eigen::Vector3d> out{path.front()};
    std::size_t a = 0;
    while (a + 1 < path.size()) {
        std::size_t b = path.size() - 1;
        while (b > a + 1 && !clear(a, b))
            --b;
        out.push_back(path[b]);
        const FlatPose next = headingTo(b);
        time += flight_.moveTime(at, next);
        at = next;
        a = b;
    }
    return out;
}

Plan AepPlanner::pathPlan(const PlanningContext& context, const std::vector<Eigen::Vector3d>& path,
                          double finalYaw) const {
    std::vector<Waypoint> legs;  // each leg flown facing along it, then the turn to the view
    FlatPose at = context.pose;
    for (std::size_t k = 1; k < path.size(); ++k) {
        at = {path[k], headingTowards(path[k - 1], path[k], at.yaw)};
        legs.push_back({at, 0.0});
    }
    if (legs.empty() || std::abs(wrapAngle(finalYaw - at.yaw)) > 1e-9)
        legs.push_back({{at.position, finalYaw}, 0.0});
    Plan plan;
    plan.status = Plan::Status::Path;
    plan.waypoints = flight_.flown(context.pose, context.time, legs);
    return plan;
}

bool AepPlanner::keepFlying(const PlanningContext& context, const Plan& plan,
                            std::size_t nextWaypoint) {
    const Eigen::Vector3d& p = context.pose.position;
    if (trail_.empty() || (trail_.back() - p).norm() >= kTrailSpacing)
        trail_.push_back(p);
    const mapping::ExplorationMap& map = *context.map;
    const double r = params_.robotRadius;
    const auto& w = plan.waypoints;
    if (nextWaypoint >= w.size())
        return true;
    if (!map.isSegmentFreeOrUnknown(w[nextWaypoint].pose.position, w[nextWaypoint].pose.position,
                                    r))
        return false;
    for (std::size_t k = nextWaypoint; k + 1 < w.size(); ++k)
        if (!map.isSegmentFreeOrUnknown(w[k].pose.position, w[k + 1].pose.position, r))
            return false;
    return true;
}

}  // namespace daep::planning
