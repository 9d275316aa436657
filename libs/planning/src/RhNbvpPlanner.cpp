#include "daep/planning/RhNbvpPlanner.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "daep/common/Config.h"
#include "daep/common/ConfigChecks.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/planning/FlightSpace.h"

namespace daep::planning {

RhNbvpParams RhNbvpParams::fromConfig(const mrpt::config::CConfigFileBase& config) {
    const ConfigReader r(config, "rhnbvp");
    RhNbvpParams p;
    p.extensionRange = requirePositive(r, "extension_range");
    p.initialIterations = requireIntAtLeast(r, "initial_iterations", 1);
    p.cutoffIterations = requireIntAtLeast(r, "cutoff_iterations", p.initialIterations);
    p.lambda = requireNonNegative(r, "lambda");
    p.zeroGain = requireNonNegative(r, "zero_gain");
    p.maxSamples = requireIntAtLeast(r, "max_samples", 1);
    p.robotRadius = requireNonNegative(ConfigReader(config, "planning"), "robot_radius");
    p.bodyHalfHeight = 0.5 * requirePositiveXyz(ConfigReader(config, "drone"), "box").z();
    return p;
}

RhNbvpPlanner::RhNbvpPlanner(const RhNbvpParams& params, const GainParams& gain, std::uint64_t seed)
    : params_(params), gain_(gain), rng_(seed) {}

bool RhNbvpPlanner::edgeValid(int parent, const Eigen::Vector3d& to) const {
    return pathSpace_.staticValid(tree_.node(parent).position, to, parent == 0 && !rootFree_);
}

int RhNbvpPlanner::addNode(const PlanningContext& context, int parent,
                           const Eigen::Vector3d& position, double yaw) {
    const int i = tree_.add(parent, position, yaw);
    TreeNode& n = tree_.node(i);
    n.gain = gain_.gainAtYaw(*context.map, position, yaw);
    n.score = tree_.node(parent).score + n.gain * std::exp(-params_.lambda * n.cost);
    if (best_ < 0 || n.score > tree_.node(best_).score)
        best_ = i;
    return i;
}

void RhNbvpPlanner::reinsertPreviousBranch(const PlanningContext& context) {
    int parent = 0;
    for (const FlatPose& pose : previousBranch_) {
        if (!samplingBox_.contains(pose.position) || !edgeValid(parent, pose.position)) {
            break;
        }
        parent = addNode(context, parent, pose.position, pose.yaw);
    }
}

bool RhNbvpPlanner::goodEnough() const {
    return tree_.size() - 1 >= params_.initialIterations && best_ >= 0 &&
           tree_.node(best_).score > params_.zeroGain;
}

void RhNbvpPlanner::grow(const PlanningContext& context) {
    while (tree_.size() - 1 < params_.cutoffIterations && samples_ < params_.maxSamples &&
           !goodEnough() && !context.deadline.passed()) {
        ++samples_;
        const Eigen::Vector3d sample = sampleInBox(samplingBox_, rng_);
        const double yaw = sampleYaw(rng_);
        const int parent = tree_.nearest(sample);
        const Eigen::Vector3d p =
            steer(tree_.node(parent).position, sample, params_.extensionRange);
        if (!samplingBox_.contains(p) || !edgeValid(parent, p))
            continue;
        addNode(context, parent, p, yaw);
    }
}

Plan RhNbvpPlanner::plan(const PlanningContext& context) {
    if (context.map == nullptr)
        throw std::invalid_argument("RhNbvpPlanner::plan: no map");
    tree_.reset(context.pose);
    pathSpace_.bind(*context.map, params_.robotRadius, params_.bodyHalfHeight, false);
    best_ = -1;
    samples_ = 0;
    samplingBox_ = shrink(context.explorationBox, params_.robotRadius);
    rootFree_ = context.map->isSegmentFree(context.pose.position, context.pose.position,
                                           params_.robotRadius);
    reinsertPreviousBranch(context);
    grow(context);
    return makePlan(context);
}

Plan RhNbvpPlanner::makePlan(const PlanningContext& context) {
    Plan plan;
    plan.tree = tree_.edges();
    previousBranch_.clear();
    const int nodes = tree_.size() - 1;
    std::ostringstream why;
    if (best_ < 0 ||
        (tree_.node(best_).score <= params_.zeroGain && nodes < params_.initialIterations)) {
        why << "tree stalled: " << nodes << " nodes after " << samples_ << " samples";
        plan.status = Plan::Status::NoPath;
        plan.reason = why.str();
        return plan;
    }
    const TreeNode& best = tree_.node(best_);
    plan.score = best.score;
    if (best.score <= params_.zeroGain) {
        why << "no gain (best value " << best.score << " over " << nodes << " nodes)";
        plan.status = Plan::Status::Finished;
        plan.reason = why.str();
        return plan;
    }
    const std::vector<int> branch = tree_.branch(best_);
    const TreeNode& first = tree_.node(branch.front());
    Waypoint w;
    w.pose.position = first.position;
    w.pose.yaw = first.yaw;
    w.arrivalTime = context.time + context.motion.travelTime(context.pose, w.pose);
    plan.status = Plan::Status::Path;
    plan.waypoints.push_back(w);
    plan.gain = first.gain;
    for (std::size_t i = 1; i < branch.size(); ++i) {
        const TreeNode& n = tree_.node(branch[i]);
        previousBranch_.push_back({n.position, n.yaw});
    }
    why << "best branch value " << best.score << ", " << branch.size() << " nodes deep, " << nodes
        << " nodes";
    plan.reason = why.str();
    return plan;
}

}  // namespace daep::planning
