#include "daep/planning/DepPlanner.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "daep/common/Config.h"
#include "daep/common/ConfigChecks.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/planning/FlightSpace.h"
#include "daep/planning/Tree.h"

namespace daep::planning {
namespace {

/** The drone counts as standing on a node this close to it. */
constexpr double kOnNode = 0.01;
/** Floor of a candidate's travel time, so that the score stays finite. */
constexpr double kMinTime = 0.1;
/** Bound on candidate re-ranking rounds (gain refreshes and lazily blocked edges). */
constexpr int kMaxRounds = 64;

double headingOf(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double fallback) {
    const Eigen::Vector2d d = (b - a).head<2>();
    return d.norm() < 1e-6 ? fallback : std::atan2(d.y(), d.x());
}

}  // namespace

DepParams DepParams::fromConfig(const mrpt::config::CConfigFileBase& config) {
    const ConfigReader r(config, "dep");
    DepParams p;
    p.replan = r.requireBool("replan");
    p.smooth = r.requireBool("smooth");
    p.edgeLength = requirePositive(r, "edge_length");
    p.neighbours = requireIntAtLeast(r, "neighbours", 1);
    p.nodeSpacing = requirePositive(r, "node_spacing");
    p.localExtent = requirePositive(r, "local_extent");
    p.samplesPerPlan = requireIntAtLeast(r, "samples_per_plan", 1);
    p.maxNewNodes = requireIntAtLeast(r, "max_new_nodes", 1);
    p.globalAfter = requireIntAtLeast(r, "global_after", 1);
    p.yawBins = requireIntAtLeast(r, "yaw_bins", 1);
    if (p.yawBins > 64)
        failRange(r, "yaw_bins", p.yawBins, "must be <= 64");
    p.weights.unknown = requireNonNegative(r, "unknown_weight");
    p.weights.frontier = requireNonNegative(r, "frontier_weight");
    p.weights.surface = requireNonNegative(r, "surface_weight");
    p.candidateFraction = requireInRange(r, "candidate_fraction", 0.0, 1.0);
    p.minGain = requireNonNegative(r, "min_gain");
    p.finishPlans = requireIntAtLeast(r, "finish_plans", 0);
    p.finishMinNodes = requireIntAtLeast(r, "finish_min_nodes", 0);
    p.refreshStep = requirePositive(r, "refresh_step");
    p.spentRatio = requireInRange(r, "spent_ratio", 0.0, 1.0);
    p.spentResetCells = requireIntAtLeast(r, "spent_reset_cells", 0);
    p.replanLookahead = requirePositive(r, "replan_lookahead");
    p.smoothMargin = requireNonNegative(r, "smooth_margin");
    p.robotRadius = requireNonNegative(ConfigReader(config, "planning"), "robot_radius");
    if (p.nodeSpacing >= p.edgeLength)
        failRange(r, "node_spacing", p.nodeSpacing, "must be < edge_length");
    return p;
}

DepPlanner::DepPlanner(const DepParams& params, const GainParams& gain, std::uint64_t seed)
    : params_(params),
      gainParams_(gain),
      gain_(gain, params.yawBins, params.weights),
      rng_(seed),
      roadmap_(params.edgeLength) {}

bool DepPlanner::insideCone(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    const Eigen::Vector3d d = b - a;
    const double elevation = std::atan2(std::abs(d.z()), d.head<2>().norm());
    return elevation <= 0.5 * gainParams_.vfov;
}

bool DepPlanner::edgeValid(const mapping::ExplorationMap& map, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b) const {
    return insideCone(a, b) && map.isSegmentFree(a, b, params_.robotRadius);
}

bool DepPlanner::startSegmentSafe(const mapping::ExplorationMap& map, const Eigen::Vector3d& from,
                                  const Eigen::Vector3d& to) const {
    const double r = params_.robotRadius;
    if (map.isSegmentFree(from, from, r))
        return map.isSegmentFree(from, to, r);
    // The drone is physically at `from`: skip its own ball (cells there may be unseen).
    const double length = (to - from).norm();
    const Eigen::Vector3d start = length > r ? from + (to - from) * (r / length) : to;
    return map.isSegmentFreeOrUnknown(start, to, r) && map.isSegmentFree(to, to, r);
}

bool DepPlanner::linkSafe(const mapping::ExplorationMap& map, int a, int b) const {
    const RoadmapNode& na = roadmap_.node(a);
    const RoadmapNode& nb = roadmap_.node(b);
    if (na.anchor)
        return startSegmentSafe(map, na.position, nb.position);
    if (nb.anchor)
        return startSegmentSafe(map, nb.position, na.position);
    return map.isSegmentFree(na.position, nb.position, params_.robotRadius);
}

void DepPlanner::evaluateGain(const mapping::ExplorationMap& map, int node) {
    RoadmapNode& n = roadmap_.node(node);
    n.binGains = gain_.evaluate(map, n.position, n.spentColumns);
    const auto best = std::max_element(n.binGains.begin(), n.binGains.end());
    n.bestBin = static_cast<int>(best - n.binGains.begin());
    n.bestGain = *best;
    n.gainRevision = map.revision();
    n.hasGain = true;
}

int DepPlanner::startNode(const PlanningContext& context) {
    const mapping::ExplorationMap& map = *context.map;
    const Eigen::Vector3d& p = context.pose.position;
    const int nearest = roadmap_.nearest(p);
    if (nearest >= 0 && (roadmap_.node(nearest).position - p).norm() <= kOnNode)
        return nearest;
    // The drone is off the roadmap (first call, or stopped mid-edge): anchor it there.
    const int anchor = roadmap_.addNode(p);
    roadmap_.node(anchor).anchor = true;
    ++lastNewNodes_;
    int linked = 0;
    for (int q : roadmap_.within(p, params_.edgeLength)) {
        if (q == anchor || linked >= params_.neighbours)
            continue;
        if (startSegmentSafe(map, p, roadmap_.node(q).position)) {
            roadmap_.addEdge(anchor, q, map.revision());
            ++linked;
        }
    }
    evaluateGain(map, anchor);
    return anchor;
}

void DepPlanner::ensureExit(const mapping::ExplorationMap& map, int start) {
    const std::uint64_t revision = map.revision();
    for (const RoadmapLink& l : roadmap_.links(start)) {
        RoadmapEdge& e = roadmap_.edge(l.edge);
        if (e.checkedRevision != revision) {
            e.checkedRevision = revision;
            e.blocked = !linkSafe(map, start, l.to);
        }
        if (!e.blocked)
            return;
    }
    // Every edge out of here is blocked by what was seen since it was made: reach further.
    int linked = 0;
    for (int q : roadmap_.within(roadmap_.node(start).position, 2.0 * params_.edgeLength)) {
        if (linked >= params_.neighbours)
            break;
        if (q != start && roadmap_.findEdge(start, q) < 0 && linkSafe(map, start, q)) {
            roadmap_.addEdge(start, q, revision);
            ++linked;
        }
    }
}

void DepPlanner::refreshGains(const PlanningContext& context) {
    const mapping::ExplorationMap& map = *context.map;
    std::vector<Eigen::Vector3d> points = lastPath_;
    points.push_back(context.pose.position);
    std::vector<char> due(roadmap_.size(), 0);
    const auto mark = [&](const Eigen::Vector3d& q) {
        for (int i : roadmap_.within(q, gainParams_.range))
            due[i] = 1;
    };
    mark(points.front());
    for (std::size_t s = 0; s + 1 < points.size(); ++s) {
        const double length = (points[s + 1] - points[s]).norm();
        const int steps = static_cast<int>(std::ceil(length / params_.refreshStep));
        for (int k = 1; k <= steps; ++k)
            mark(points[s] + (points[s + 1] - points[s]) * (double(k) / steps));
    }
    lastRefreshed_ = 0;
    for (int i = 0; i < roadmap_.size(); ++i) {
        const RoadmapNode& n = roadmap_.node(i);
        // Weighted unknown volume never comes back once a node sees none: skip those.
        if (due[i] && n.gainRevision != map.revision() && n.bestGain > 0.0) {
            evaluateGain(map, i);
            ++lastRefreshed_;
        }
    }
}

bool DepPlanner::tryAddSample(const mapping::ExplorationMap& map, const Eigen::Vector3d& sample) {
    if (!roadmap_.within(sample, params_.nodeSpacing).empty())
        return false;
    if (!map.isSegmentFree(sample, sample, params_.robotRadius))
        return false;
    const std::vector<int> near = roadmap_.within(sample, params_.edgeLength);
    const int node = roadmap_.addNode(sample);
    int linked = 0;
    for (int q : near) {
        if (linked >= params_.neighbours)
            break;
        if (insideCone(sample, roadmap_.node(q).position) && linkSafe(map, node, q)) {
            roadmap_.addEdge(node, q, map.revision());
            ++linked;
        }
    }
    if (linked == 0) {
        roadmap_.removeLastNode();
        return false;
    }
    evaluateGain(map, node);
    return true;
}

void DepPlanner::markSpentGoal(const PlanningContext& context, int start) {
    // Unknown cells the camera cannot see (inside solid objects, reached by rays slipping
    // between voxel corners) would attract the drone forever: a heading that was looked along
    // without the gain dropping has the sectors it looked at ignored from then on.
    if (start != lastGoal_ || gain_.binOf(context.pose.yaw) != lastGoalBin_)
        return;
    RoadmapNode& n = roadmap_.node(start);
    if (n.binGains[lastGoalBin_] >= params_.spentRatio * lastGoalGain_) {
        n.spentColumns |= gain_.columnsSeenFrom(lastGoalBin_);
        n.spentKnown = context.map->knownCellsInBox();
        evaluateGain(*context.map, start);
    }
}

void DepPlanner::expireSpent(const mapping::ExplorationMap& map) {
    // A person standing in the view also keeps the gain from dropping; once the map has grown
    // elsewhere, such sectors are tried again.
    const std::size_t known = map.knownCellsInBox();
    for (int i = 0; i < roadmap_.size(); ++i) {
        RoadmapNode& n = roadmap_.node(i);
        if (n.spentColumns != 0 &&
            known >= n.spentKnown + static_cast<std::size_t>(params_.spentResetCells)) {
            n.spentColumns = 0;
            evaluateGain(map, i);
        }
    }
}

int DepPlanner::grow(const PlanningContext& context) {
    Aabb box = samplingBox_;
    if (failedGrowth_ < params_.globalAfter && !noCandidateLast_) {
        const Eigen::Vector3d e = Eigen::Vector3d::Constant(params_.localExtent);
        box.min = box.min.cwiseMax(context.pose.position - e);
        box.max = box.max.cwiseMin(context.pose.position + e);
        box.max = box.max.cwiseMax(box.min);  // the drone may be outside the shrunk box
    }
    int added = 0;
    for (int s = 0; s < params_.samplesPerPlan && added < params_.maxNewNodes; ++s) {
        if (context.deadline.passed())
            return added;  // cut short: says nothing about what is left to explore
        if (tryAddSample(*context.map, sampleInBox(box, rng_)))
            ++added;
    }
    failedGrowth_ = added < params_.finishMinNodes ? failedGrowth_ + 1 : 0;
    return added;
}

double DepPlanner::pathGain(const std::vector<int>& path) const {
    double gain = roadmap_.node(path.back()).bestGain;
    // On the way the camera faces the next node: count what each intermediate node sees so.
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
        const RoadmapNode& n = roadmap_.node(path[i]);
        const double heading = headingOf(n.position, roadmap_.node(path[i + 1]).position, 0.0);
        gain += n.binGains[gain_.binOf(heading)];
    }
    return gain;
}

double DepPlanner::pathTime(const PlanningContext& context, const std::vector<int>& path) const {
    double yaw = context.pose.yaw;
    double turn = 0.0;
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
        const double h =
            headingOf(roadmap_.node(path[i]).position, roadmap_.node(path[i + 1]).position, yaw);
        turn += std::abs(wrapAngle(h - yaw));
        yaw = h;
    }
    const RoadmapNode& goal = roadmap_.node(path.back());
    turn += std::abs(wrapAngle(gain_.binYaw(goal.bestBin) - yaw));
    const double time =
        roadmap_.pathLength(path) / context.motion.speed + turn / context.motion.yawRate;
    return std::max(time, kMinTime);
}

DepPlanner::Choice DepPlanner::bestCandidate(const PlanningContext& context, int start,
                                             const Roadmap::Paths& paths) const {
    double top = 0.0;
    for (int i = 0; i < roadmap_.size(); ++i)
        if (std::isfinite(paths.cost[i]))
            top = std::max(top, roadmap_.node(i).bestGain);
    const double threshold = std::max(params_.minGain, params_.candidateFraction * top);
    Choice best;
    for (int i = 0; i < roadmap_.size(); ++i) {
        const RoadmapNode& n = roadmap_.node(i);
        if (!std::isfinite(paths.cost[i]) || n.bestGain < threshold || n.bestGain <= 0.0)
            continue;
        // Already here and facing its best heading: its gain is what the camera sees now.
        if (i == start && gain_.binOf(context.pose.yaw) == n.bestBin)
            continue;
        std::vector<int> path = Roadmap::pathTo(paths, start, i);
        const double gain = pathGain(path);
        const double score = gain / pathTime(context, path);
        if (best.goal < 0 || score > best.score)
            best = {i, std::move(path), gain, score, false};
    }
    return best;
}

DepPlanner::Choice DepPlanner::choose(const PlanningContext& context, int start) {
    const mapping::ExplorationMap& map = *context.map;
    const std::uint64_t revision = map.revision();
    const auto check = [&](int a, int b) { return linkSafe(map, a, b); };
    Choice first;  // the best candidate before any edge was found blocked
    for (int round = 0; round < kMaxRounds;) {
        const Roadmap::Paths paths = roadmap_.shortestPaths(start, revision);
        Choice c = bestCandidate(context, start, paths);
        if (c.goal < 0)
            return first.goal < 0 ? c : approach(map, first);
        if (roadmap_.node(c.goal).gainRevision != revision) {
            evaluateGain(map, c.goal);  // stale gain: refresh and rank again
            continue;
        }
        if (first.goal < 0)
            first = c;
        const std::vector<int> path = roadmap_.lazyPath(start, c.goal, revision, check);
        if (!path.empty() && roadmap_.pathLength(path) <= paths.cost[c.goal] + 1e-9) {
            c.path = path;
            return c;
        }
        ++round;  // lazily found blocked edges: rank again without them
    }
    return approach(map, first);
}

DepPlanner::Choice DepPlanner::approach(const mapping::ExplorationMap& map, const Choice& blocked) {
    // No safe path to any candidate: fly the safe part of the best one and look at what blocks
    // it, so that cells a person left marked occupied are seen free again.
    Choice c;
    c.unreachable = true;
    c.path = {blocked.path.front()};
    for (std::size_t i = 0; i + 1 < blocked.path.size(); ++i) {
        const int a = blocked.path[i], b = blocked.path[i + 1];
        RoadmapEdge& e = roadmap_.edge(roadmap_.findEdge(a, b));
        if (e.checkedRevision != map.revision()) {
            e.checkedRevision = map.revision();
            e.blocked = !linkSafe(map, a, b);
        }
        c.finalYaw = headingOf(roadmap_.node(a).position, roadmap_.node(b).position, 0.0);
        if (e.blocked)
            break;
        c.path.push_back(b);
    }
    c.goal = c.path.back();
    return c;
}

std::vector<Eigen::Vector3d> DepPlanner::smoothed(const mapping::ExplorationMap& map,
                                                  std::vector<Eigen::Vector3d> points) const {
    // Greedy shortcutting; a shortcut needs the wider capsule so it keeps clear of obstacles.
    if (!params_.smooth || points.size() < 3)
        return points;
    const double r = params_.robotRadius + params_.smoothMargin;
    std::vector<Eigen::Vector3d> out{points.front()};
    std::size_t i = 0;
    while (i + 1 < points.size()) {
        std::size_t j = points.size() - 1;
        while (j > i + 1 &&
               !(insideCone(points[i], points[j]) && map.isSegmentFree(points[i], points[j], r)))
            --j;
        out.push_back(points[j]);
        i = j;
    }
    return out;
}

Plan DepPlanner::pathPlan(const PlanningContext& context, const Choice& choice) {
    std::vector<Eigen::Vector3d> points;
    for (int v : choice.path)
        points.push_back(roadmap_.node(v).position);
    points.front() = context.pose.position;
    points = smoothed(*context.map, points);
    Plan plan;
    plan.status = Plan::Status::Path;
    FlatPose at = context.pose;
    double time = context.time;
    const auto append = [&](const FlatPose& pose) {
        time += context.motion.travelTime(at, pose);
        plan.waypoints.push_back({pose, time});
        at = pose;
    };
    for (std::size_t i = 1; i < points.size(); ++i)
        append({points[i], headingOf(points[i - 1], points[i], at.yaw)});
    const RoadmapNode& goal = roadmap_.node(choice.goal);
    const double finalYaw = choice.unreachable ? choice.finalYaw : gain_.binYaw(goal.bestBin);
    if (plan.waypoints.empty() || std::abs(wrapAngle(finalYaw - at.yaw)) > 1e-9)
        append({at.position, finalYaw});
    plan.gain = goal.bestGain;
    lastGoal_ = choice.unreachable ? -1 : choice.goal;
    lastGoalBin_ = goal.bestBin;
    lastGoalGain_ = goal.bestGain;
    plan.score = choice.score;
    lastPath_ = points;
    return plan;
}

Plan DepPlanner::waitPlan(const PlanningContext& context) const {
    // Turning in place lets time pass (people move on) and looks at another side.
    Plan plan;
    plan.status = Plan::Status::Path;
    FlatPose turned = context.pose;
    turned.yaw = wrapAngle(turned.yaw + 0.5 * M_PI);
    plan.waypoints.push_back(
        {turned, context.time + context.motion.travelTime(context.pose, turned)});
    return plan;
}

Plan DepPlanner::plan(const PlanningContext& context) {
    if (context.map == nullptr)
        throw std::invalid_argument("DepPlanner::plan: no map");
    samplingBox_ = shrink(context.explorationBox, params_.robotRadius);
    lastNewNodes_ = 0;
    const int start = startNode(context);
    ensureExit(*context.map, start);
    refreshGains(context);
    expireSpent(*context.map);
    markSpentGoal(context, start);
    lastGoal_ = -1;
    lastNewNodes_ += grow(context);
    const Choice choice = choose(context, start);
    noCandidateLast_ = choice.goal < 0;
    const bool idle = (choice.goal < 0 || choice.unreachable) &&
                      lastNewNodes_ < params_.finishMinNodes && !context.deadline.passed();
    idlePlans_ = idle ? idlePlans_ + 1 : 0;
    std::ostringstream why;
    why << roadmap_.size() << " nodes (+" << lastNewNodes_ << "), " << lastRefreshed_
        << " gains refreshed";
    Plan result;
    if (params_.finishPlans > 0 && idlePlans_ >= params_.finishPlans) {
        why << "; " << idlePlans_ << " plans in a row added almost nothing and reached no gain";
        result.status = Plan::Status::Finished;
    } else if (choice.goal >= 0) {
        result = pathPlan(context, choice);
        if (choice.unreachable)
            why << "; every candidate is blocked now: approaching the blockage";
        else
            why << "; goal gain " << result.gain << ", score " << result.score;
    } else {
        // Turning lets people walk on and looks around; finish_plans such turns in a row end
        // the mission.
        result = waitPlan(context);
        why << "; no candidate with gain >= " << params_.minGain << ": turning in place";
    }
    if (choice.goal < 0)
        lastPath_.clear();
    result.reason = why.str();
    result.tree = roadmap_.treeEdges();
    return result;
}

bool DepPlanner::keepFlying(const PlanningContext& context, const Plan& plan,
                            std::size_t nextWaypoint) {
    if (!params_.replan || context.map == nullptr)
        return true;
    // Unknown cells do not block: the path was planned in known free space and cells never
    // return to unknown, so only what has become occupied since (people) is a new danger. The
    // drone's own ball is not checked (the plan's first edge was not either): what is already
    // that close cannot be avoided by stopping, only by flying on.
    const double r = params_.robotRadius;
    Eigen::Vector3d from = context.pose.position;
    double checked = 0.0;
    for (std::size_t i = nextWaypoint; i < plan.waypoints.size(); ++i) {
        const Eigen::Vector3d& to = plan.waypoints[i].pose.position;
        const double length = (to - from).norm();
        const Eigen::Vector3d begin = (i == nextWaypoint && length > r)
                                          ? Eigen::Vector3d(from + (to - from) * (r / length))
                                          : from;
        if ((i > nextWaypoint || length > r) && !context.map->isSegmentFreeOrUnknown(begin, to, r))
            return false;
        checked += (to - from).norm();
        if (checked >= params_.replanLookahead)
            break;
        from = to;
    }
    return true;
}

}  // namespace daep::planning
