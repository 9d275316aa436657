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

double headingOf(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double fallback) {
    const Eigen::Vector3d d = to - from;
    if (d.head<2>().norm() < 1e-3)
        return fallback;
    return std::atan2(d.y(), d.x());
}

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
    p.sigmaThreshold = requireNonNegative(r, "sigma_thresh");
    p.gp.lengthScale = requirePositive(r, "gp_length_scale");
    p.gp.signalSigma = requirePositive(r, "gp_sigma_f");
    p.gp.noiseSigma = requirePositive(r, "gp_sigma_n");
    p.gpRadius = requirePositive(r, "gp_radius");
    p.gpMaxNeighbours = requireIntAtLeast(r, "gp_max_neighbours", 1);
    p.cacheThreshold = requireNonNegative(r, "cache_node_threshold");
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
    const ConfigReader planning(config, "planning");
    p.robotRadius = requireNonNegative(planning, "robot_radius");
    p.crossUnknown =
        requireOneOf(planning, "path_space", {"known_free", "not_occupied"}) == "not_occupied";
    return p;
}

AepPlanner::AepPlanner(const AepParams& params, const GainParams& gain, std::uint64_t seed)
    : params_(params), gain_(gain), gp_(params.gp), cache_(1.0), rng_(seed) {}

YawGain AepPlanner::evaluateGain(const mapping::ExplorationMap& map, const Eigen::Vector3d& p) {
    const std::vector<int> ids =
        cache_.near(p, params_.gpRadius, static_cast<std::size_t>(params_.gpMaxNeighbours));
    if (!ids.empty()) {
        std::vector<Eigen::Vector3d> x;
        std::vector<double> y;
        for (int id : ids) {
            x.push_back(cache_.entry(id).position);
            y.push_back(cache_.entry(id).gain);
        }
        gp_.fit(x, y);
        const GpPrediction g = gp_.predict(p);
        if (g.sigma < params_.sigmaThreshold) {
            ++stats_.gpPredictions;
            return {cache_.entry(ids.front()).yaw, std::max(0.0, g.mean)};
        }
    }
    ++stats_.rayCasts;
    const YawGain view = gain_.bestYaw(map, p);
    if (view.gain > params_.cacheThreshold)
        cache_.insert(p, view.yaw, view.gain);
    return view;
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
        if (view.gain > params_.cacheThreshold) {
            cache_.update(id, view.yaw, view.gain);
        } else {
            cache_.remove(id);
            ++stats_.cacheDropped;
        }
    }
}

bool AepPlanner::moveInPathSpace(const PlanningContext& context, const Eigen::Vector3d& a,
                                 const Eigen::Vector3d& b, bool leavingBlocked) const {
    if (params_.crossUnknown)
        return context.map->isSegmentFreeOrUnknown(a, b, params_.robotRadius);
    return segmentFlyable(*context.map, a, b, params_.robotRadius, leavingBlocked);
}

bool AepPlanner::edgeValid(const PlanningContext& context, int parent,
                           const Eigen::Vector3d& to) const {
    return moveInPathSpace(context, tree_.node(parent).position, to, parent == 0 && !rootFree_);
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

void AepPlanner::setParent(int node, int parent) {
    std::vector<int>& old = children_[static_cast<std::size_t>(tree_.node(node).parent)];
    old.erase(std::find(old.begin(), old.end(), node));
    children_[static_cast<std::size_t>(parent)].push_back(node);
    tree_.node(node).parent = parent;
}

YawGain AepPlanner::gainOnArrival(const PlanningContext& context, const Eigen::Vector3d& from,
                                  const Eigen::Vector3d& p, double arrival, bool rayCast) {
    (void)arrival;
    (void)from;
    if (!rayCast)
        return evaluateGain(*context.map, p);
    ++stats_.rayCasts;
    return gain_.bestYaw(*context.map, p);
}

bool AepPlanner::moveSafe(const FlatPose& from, double start, const FlatPose& to) const {
    (void)from;
    (void)start;
    (void)to;
    return true;
}

double AepPlanner::moveTime(const FlatPose& a, const FlatPose& b) const {
    return motion_.travelTime(a, b);
}

bool AepPlanner::moveSafeFrom(int parent, const FlatPose& to) const {
    const TreeNode& n = tree_.node(parent);
    return moveSafe({n.position, n.yaw}, n.time, to);
}

double AepPlanner::branchScore(double parentValue, double gain, double edge,
                               const Eigen::Vector3d& p) const {
    (void)p;
    return parentValue + gain * std::exp(-params_.lambda * edge);
}

void AepPlanner::propagate(int node) {
    TreeNode& n = tree_.node(node);
    const TreeNode& parent = tree_.node(n.parent);
    const double edge = (n.position - parent.position).norm();
    n.cost = parent.cost + edge;
    n.time = parent.time + moveTime({parent.position, parent.yaw}, {n.position, n.yaw});
    n.score = branchScore(parent.score, n.gain, edge, n.position);
    for (int child : children_[static_cast<std::size_t>(node)])
        propagate(child);
}

int AepPlanner::addNode(int parent, const Eigen::Vector3d& p, const YawGain& view) {
    const int i = tree_.add(parent, p, view.yaw);
    children_.emplace_back();
    children_[static_cast<std::size_t>(parent)].push_back(i);
    tree_.node(i).gain = view.gain;
    propagate(i);
    return i;
}

int AepPlanner::extend(const PlanningContext& context, const Eigen::Vector3d& sample) {
    const int nearest = tree_.nearest(sample);
    const Eigen::Vector3d p = steer(tree_.node(nearest).position, sample, params_.extensionRange);
    if (!samplingBox_.contains(p) || !moveInPathSpace(context, p, p, false))
        return -1;
    std::vector<std::pair<double, int>> candidates;  // (cost through it, node)
    for (int i = 0; i < tree_.size(); ++i) {
        const double d = (tree_.node(i).position - p).norm();
        if (i == nearest || d <= params_.rewireRadius)
            candidates.emplace_back(tree_.node(i).cost + d, i);
    }
    std::sort(candidates.begin(), candidates.end());
    std::size_t first = 0;
    while (first < candidates.size() && !edgeValid(context, candidates[first].second, p))
        ++first;
    if (first == candidates.size())
        return -1;
    // The view depends on the arrival time (people may stand in the way then); the cheapest
    // statically valid parent gives the estimate, the turn to the view's yaw comes after.
    const TreeNode& cheapest = tree_.node(candidates[first].second);
    const YawGain view =
        globalTree_
            ? YawGain{headingOf(cheapest.position, p, cheapest.yaw), 0.0}
            : gainOnArrival(context, cheapest.position, p,
                            cheapest.time + (p - cheapest.position).norm() / motion_.speed, false);
    int parent = -1;
    for (std::size_t k = first; k < candidates.size() && parent < 0; ++k) {
        const int i = candidates[k].second;
        if ((k == first || edgeValid(context, i, p)) && moveSafeFrom(i, {p, view.yaw}))
            parent = i;
    }
    if (parent < 0)
        return -1;
    const int added = addNode(parent, p, view);
    for (const auto& [cost, q] : candidates) {
        (void)cost;
        if (q == 0 || q == parent)
            continue;
        const TreeNode& other = tree_.node(q);
        const double through = tree_.node(added).cost + (other.position - p).norm();
        if (through < other.cost - 1e-9 && edgeValid(context, added, other.position) &&
            moveSafeFrom(added, {other.position, other.yaw})) {
            setParent(q, added);
            propagate(q);
        }
    }
    return added;
}

void AepPlanner::resetTree(const PlanningContext& context) {
    tree_.reset(context.pose);
    tree_.node(0).time = context.time;
    children_.assign(1, {});
    best_ = -1;
}

void AepPlanner::reinsertPreviousBranch(const PlanningContext& context) {
    int parent = 0;
    for (const FlatPose& pose : previousBranch_) {
        if (!samplingBox_.contains(pose.position) || !edgeValid(context, parent, pose.position))
            break;
        const TreeNode& from = tree_.node(parent);
        const double arrival = from.time + (pose.position - from.position).norm() / motion_.speed;
        const YawGain view = gainOnArrival(context, from.position, pose.position, arrival, true);
        if (!moveSafeFrom(parent, {pose.position, view.yaw}))
            break;
        parent = addNode(parent, pose.position, view);
    }
    previousBranch_.clear();
}

void AepPlanner::growLocal(const PlanningContext& context) {
    best_ = tree_.bestByScore();
    auto goodEnough = [&] { return best_ >= 0 && tree_.node(best_).score > params_.zeroGain; };
    while (stats_.samples < params_.maxSamples && !context.deadline.passed() &&
           (tree_.size() - 1 < params_.initialIterations ||
            (!goodEnough() && tree_.size() - 1 < params_.cutoffIterations))) {
        ++stats_.samples;
        if (extend(context, sampleLocal(context.pose.position)) >= 0)
            best_ = tree_.bestByScore();
    }
}

Plan AepPlanner::localPlan(const PlanningContext& context) {
    Plan plan;
    plan.tree = tree_.edges();
    const TreeNode& best = tree_.node(best_);
    const std::vector<int> branch = tree_.branch(best_);
    const TreeNode& first = tree_.node(branch.front());
    Waypoint w;
    w.pose = {first.position, first.yaw};
    w.arrivalTime = context.time + context.motion.travelTime(context.pose, w.pose);
    plan.status = Plan::Status::Path;
    plan.waypoints.push_back(w);
    plan.gain = first.gain;
    plan.score = best.score;
    for (std::size_t i = 1; i < branch.size(); ++i) {
        const TreeNode& n = tree_.node(branch[i]);
        previousBranch_.push_back({n.position, n.yaw});
    }
    std::ostringstream why;
    why << "local: best branch value " << best.score << ", " << branch.size() << " deep, "
        << tree_.size() - 1 << " nodes";
    plan.reason = why.str();
    return plan;
}

Plan AepPlanner::plan(const PlanningContext& context) {
    if (context.map == nullptr)
        throw std::invalid_argument("AepPlanner::plan: no map");
    stats_ = {};
    motion_ = context.motion;
    samplingBox_ = shrink(context.explorationBox, params_.robotRadius);
    if (params_.crossUnknown)
        samplingBox_.max.z() = context.explorationBox.max.z() - 0.5 * context.droneSize.z();
    rootFree_ = context.map->isSegmentFree(context.pose.position, context.pose.position,
                                           params_.robotRadius);
    refreshCache(*context.map, context.pose.position);
    globalTree_ = false;
    resetTree(context);
    reinsertPreviousBranch(context);
    growLocal(context);
    if (best_ >= 0 && tree_.node(best_).score > params_.zeroGain) {
        globalFailures_ = 0;
        return localPlan(context);
    }
    if (context.deadline.passed())
        return planAtDeadline(context);
    return globalPlan(context, best_ >= 0 ? tree_.node(best_).score : 0.0);
}

Plan AepPlanner::planAtDeadline(const PlanningContext& context) {
    if (best_ > 0 && tree_.node(best_).score > 0.0) {
        Plan plan = localPlan(context);
        plan.reason = "deadline: " + plan.reason;
        return plan;
    }
    previousBranch_.clear();
    Plan plan;
    plan.status = Plan::Status::NoPath;
    plan.tree = tree_.edges();
    plan.reason =
        "deadline: no branch with gain after " + std::to_string(tree_.size() - 1) + " nodes";
    return plan;
}

void AepPlanner::cacheMapFrontiers(const PlanningContext& context) {
    // Viewpoints where the drone has its clearance in the path space and reaches them so,
    // within 1 m of the unknown; 1 m apart, and at most kMaxViews ray casts.
    constexpr int kReach = 5;
    constexpr double kSpacing = 1.0;
    constexpr std::size_t kMaxViews = 40;
    const auto usable = [&](const Eigen::Vector3d& p) {
        return samplingBox_.contains(p) && moveInPathSpace(context, p, p, false);
    };
    for (const Eigen::Vector3d& p : context.map->frontierViewpoints(context.pose.position, usable,
                                                                    kReach, kSpacing, kMaxViews)) {
        ++stats_.rayCasts;
        const YawGain view = gain_.bestYaw(*context.map, p);
        if (view.gain > params_.cacheThreshold)
            cache_.insert(p, view.yaw, view.gain);
    }
}

bool AepPlanner::verifyFrontier(const mapping::ExplorationMap& map, int id) {
    ++stats_.rayCasts;
    const YawGain view = gain_.bestYaw(map, cache_.entry(id).position);
    if (view.gain <= params_.cacheThreshold) {
        cache_.remove(id);
        return false;
    }
    cache_.update(id, view.yaw, view.gain);
    return true;
}

bool AepPlanner::growGlobal(const PlanningContext& context, const std::vector<int>& frontiers) {
    globalTree_ = true;
    resetTree(context);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::uniform_int_distribution<std::size_t> pick(0,
                                                    frontiers.empty() ? 0 : frontiers.size() - 1);
    const Eigen::Vector3d& root = context.pose.position;
    bool reached = false;
    std::set<int> verified;  // cached gains may be stale far from where the drone flew
    while (stats_.samples < params_.globalMaxSamples && tree_.size() - 1 < params_.globalMaxNodes &&
           !(reached && tree_.size() - 1 >= params_.globalMinNodes) && !context.deadline.passed()) {
        ++stats_.samples;
        const bool towardsGoal = !frontiers.empty() && unit(rng_) < params_.globalGoalBias;
        const Eigen::Vector3d sample = towardsGoal ? cache_.entry(frontiers[pick(rng_)]).position
                                                   : sampleInBox(samplingBox_, rng_);
        const int added = extend(context, sample);
        if (added < 0)
            continue;
        const Eigen::Vector3d p = tree_.node(added).position;
        if ((p - root).norm() <= params_.goalRadius)
            continue;
        // The global tree also surveys the known free space for viewpoints the local trees
        // never reached: their gains enter the cache like any other.
        tree_.node(added).gain = evaluateGain(*context.map, p).gain;
        for (int id : cache_.near(p, params_.goalRadius)) {
            if (verified.insert(id).second && !verifyFrontier(*context.map, id))
                continue;
            reached = reached || cache_.entry(id).alive;
        }
    }
    return reached;
}

bool AepPlanner::peopleBlockFrontiers(const PlanningContext& context) {
    (void)context;
    return false;
}

bool AepPlanner::globalTreeReachesFrontier(const PlanningContext& context) {
    return growGlobal(context, cache_.liveIds());
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
    plan.tree = tree_.edges();
    // Cheapest way to each frontier: a tree node within goal_radius, then straight to it.
    std::vector<std::pair<double, std::pair<int, int>>> options;  // (cost, (frontier, node))
    for (int i = 0; i < tree_.size(); ++i) {
        const TreeNode& n = tree_.node(i);
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
        const CachedGain& frontier = cache_.entry(f);
        const YawGain view{frontier.yaw, frontier.gain};
        std::vector<Eigen::Vector3d> path{context.pose.position};
        for (int i : tree_.branch(node))
            path.push_back(tree_.node(i).position);
        const Eigen::Vector3d& last = path.back();
        if (samplingBox_.contains(frontier.position) &&
            moveInPathSpace(context, last, frontier.position, false))
            path.push_back(frontier.position);
        globalFailures_ = 0;
        Plan out = pathPlan(context, shortcut(context, path), view.yaw);
        out.tree = std::move(plan.tree);
        out.gain = view.gain;
        out.score = localScore;
        why << "global: frontier gain " << view.gain << " at path cost " << cost << ", "
            << cache_.size() << " frontiers, " << tree_.size() - 1 << " nodes";
        out.reason = why.str();
        return out;
    }
    if (context.deadline.passed()) {  // cut short: no judgement on the frontiers
        plan.status = Plan::Status::NoPath;
        why << "deadline: global tree cut at " << tree_.size() - 1 << " nodes, no path yet";
        plan.reason = why.str();
        return plan;
    }
    if (peopleBlockFrontiers(context)) {
        plan.status = Plan::Status::NoPath;
        why << "global: people block the way to " << cache_.size() << " frontiers";
        plan.reason = why.str();
        return plan;
    }
    ++globalFailures_;
    const bool givingUp =
        params_.globalPlannerCounter > 0 && globalFailures_ >= params_.globalPlannerCounter;
    if (givingUp || cache_.size() == 0) {
        plan.status = Plan::Status::Finished;
        why << (cache_.size() == 0 ? "no frontiers left" : "no frontier reachable") << " after "
            << globalFailures_ << " global plans";
    } else {
        plan.waitFor(params_.globalRetryWait);
        why << "global: no path to any of " << cache_.size() << " frontiers (" << tree_.size() - 1
            << " nodes)";
    }
    plan.reason = why.str();
    return plan;
}

std::vector<Eigen::Vector3d> AepPlanner::shortcut(const PlanningContext& context,
                                                  const std::vector<Eigen::Vector3d>& path) const {
    FlatPose at = context.pose;
    double time = context.time;
    auto headingTo = [&](std::size_t b) {
        return FlatPose{path[b], headingOf(at.position, path[b], at.yaw)};
    };
    auto clear = [&](std::size_t a, std::size_t b) {
        return moveInPathSpace(context, path[a], path[b], a == 0 && !rootFree_) &&
               moveSafe(at, time, headingTo(b));
    };
    std::vector<Eigen::Vector3d> out{path.front()};
    std::size_t a = 0;
    while (a + 1 < path.size()) {
        std::size_t b = path.size() - 1;
        while (b > a + 1 && !clear(a, b))
            --b;
        out.push_back(path[b]);
        const FlatPose next = headingTo(b);
        time += motion_.travelTime(at, next);
        at = next;
        a = b;
    }
    return out;
}

Plan AepPlanner::pathPlan(const PlanningContext& context, const std::vector<Eigen::Vector3d>& path,
                          double finalYaw) const {
    Plan plan;
    plan.status = Plan::Status::Path;
    FlatPose at = context.pose;
    double time = context.time;
    auto append = [&](const FlatPose& pose) {
        time += context.motion.travelTime(at, pose);
        plan.waypoints.push_back({pose, time});
        at = pose;
    };
    for (std::size_t k = 1; k < path.size(); ++k)
        append({path[k], headingOf(path[k - 1], path[k], at.yaw)});
    if (plan.waypoints.empty() || std::abs(wrapAngle(finalYaw - at.yaw)) > 1e-9)
        append({at.position, finalYaw});
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
