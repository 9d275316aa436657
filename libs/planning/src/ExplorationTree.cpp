#include "daep/planning/ExplorationTree.h"

#include <algorithm>
#include <utility>

#include "daep/planning/FlightModel.h"
#include "daep/planning/FlightSpace.h"

namespace daep::planning {

ExplorationTree::ExplorationTree(double extensionRange, double rewireRadius)
    : extensionRange_(extensionRange), rewireRadius_(rewireRadius) {}

void ExplorationTree::reset(const FlatPose& root, double time, bool rootFree, const Aabb& box,
                            const TreeParts& parts, Growth growth) {
    growth_ = growth;
    tree_.reset(root);
    tree_.node(0).time = time;
    children_.assign(1, {});
    box_ = box;
    rootFree_ = rootFree;
    parts_ = parts;
}

bool ExplorationTree::edgeValid(int parent, const Eigen::Vector3d& to) const {
    return parts_.moves->staticValid(tree_.node(parent).position, to, parent == 0 && !rootFree_);
}

bool ExplorationTree::timedValidFrom(int parent, const FlatPose& to) const {
    const TreeNode& n = tree_.node(parent);
    return parts_.moves->timedValid({n.position, n.yaw}, n.time, to);
}

void ExplorationTree::setParent(int node, int parent) {
    std::vector<int>& old = children_[static_cast<std::size_t>(tree_.node(node).parent)];
    old.erase(std::find(old.begin(), old.end(), node));
    children_[static_cast<std::size_t>(parent)].push_back(node);
    tree_.node(node).parent = parent;
}

void ExplorationTree::timeFromParent(int node) {
    TreeNode& n = tree_.node(node);
    const TreeNode& parent = tree_.node(n.parent);
    const double edge = (n.position - parent.position).norm();
    n.cost = parent.cost + edge;
    n.time =
        parent.time + parts_.flight->moveTime({parent.position, parent.yaw}, {n.position, n.yaw});
    n.score = parts_.objective->score(parent.score, n.gain, edge, n.position);
}

void ExplorationTree::propagate(int node) {
    timeFromParent(node);
    for (int child : children_[static_cast<std::size_t>(node)])
        propagate(child);
}

int ExplorationTree::addNode(int parent, const Eigen::Vector3d& p, const YawGain& view) {
    const int i = tree_.add(parent, p, view.yaw);
    children_.emplace_back();
    children_[static_cast<std::size_t>(parent)].push_back(i);
    tree_.node(i).gain = view.gain;
    propagate(i);
    return i;
}

int ExplorationTree::extend(const Eigen::Vector3d& sample) {
    const int nearest = tree_.nearest(sample);
    const Eigen::Vector3d p = steer(tree_.node(nearest).position, sample, extensionRange_);
    if (!box_.contains(p) || !parts_.moves->staticValid(p, p, false))
        return -1;
    std::vector<std::pair<double, int>> candidates;  // (cost through it, node)
    tree_.forEachNear(p, rewireRadius_, nearest,
                      [&](int i, double d) { candidates.emplace_back(tree_.node(i).cost + d, i); });
    std::sort(candidates.begin(), candidates.end());
    std::size_t first = 0;
    while (first < candidates.size() && !edgeValid(candidates[first].second, p))
        ++first;
    if (first == candidates.size())
        return -1;
    // The view depends on the arrival time (people may stand in the way then); the cheapest
    // statically valid parent gives the estimate, the turn to the view's yaw comes after.
    const TreeNode& cheapest = tree_.node(candidates[first].second);
    const FlatPose from{cheapest.position, cheapest.yaw};
    const YawGain view =
        growth_ == Growth::Views
            ? parts_.view->viewOnArrival(cheapest.position, p,
                                         parts_.flight->reachTime(from, cheapest.time, p), false)
            : YawGain{headingTowards(cheapest.position, p, cheapest.yaw), 0.0};
    // Both checks are pure, so the cheap one with people goes first: where walkers block a
    // tree, nearly every move fails it.
    int parent = -1;
    for (std::size_t k = first; k < candidates.size() && parent < 0; ++k) {
        const int i = candidates[k].second;
        if (timedValidFrom(i, {p, view.yaw}) && (k == first || edgeValid(i, p)))
            parent = i;
    }
    if (parent < 0)
        return -1;
    const int added = addNode(parent, p, view);
    rewireThrough(added, candidates, parent);
    return added;
}

void ExplorationTree::rewireThrough(int added,
                                    const std::vector<std::pair<double, int>>& neighbours,
                                    int parent) {
    const Eigen::Vector3d p = tree_.node(added).position;
    for (const auto& neighbour : neighbours) {
        const int q = neighbour.second;
        if (q == 0 || q == parent)
            continue;
        const TreeNode& other = tree_.node(q);
        const double through = tree_.node(added).cost + (other.position - p).norm();
        if (through < other.cost - 1e-9 && timedValidFrom(added, {other.position, other.yaw}) &&
            edgeValid(added, other.position))
            rewire(q, added);
    }
}

bool ExplorationTree::rewire(int node, int parent) {
    const int oldParent = tree_.node(node).parent;
    std::vector<std::pair<int, TreeNode>> saved;
    if (parts_.moves->checksPeople())  // else no re-timed move can fail
        saveSubtree(node, saved);
    setParent(node, parent);
    if (retime(node))
        return true;
    setParent(node, oldParent);
    for (const auto& [i, n] : saved)
        tree_.node(i) = n;
    return false;
}

void ExplorationTree::saveSubtree(int node, std::vector<std::pair<int, TreeNode>>& saved) const {
    saved.emplace_back(node, tree_.node(node));
    for (int child : children_[static_cast<std::size_t>(node)])
        saveSubtree(child, saved);
}

bool ExplorationTree::retime(int node) {
    TreeNode& n = tree_.node(node);
    const TreeNode& parent = tree_.node(n.parent);
    const FlatPose from{parent.position, parent.yaw};
    if (growth_ == Growth::Views) {
        const double reach = parts_.flight->reachTime(from, parent.time, n.position);
        if (parts_.view->peopleInView(n.position, n.time) ||
            parts_.view->peopleInView(n.position, reach)) {
            const YawGain view =
                parts_.view->viewOnArrival(parent.position, n.position, reach, false);
            n.yaw = view.yaw;
            n.gain = view.gain;
        }
    }
    if (!parts_.moves->timedValid(from, parent.time, {n.position, n.yaw}))
        return false;
    timeFromParent(node);
    for (int child : children_[static_cast<std::size_t>(node)])
        if (!retime(child))
            return false;
    return true;
}

void ExplorationTree::reuseBranch(const std::vector<FlatPose>& branch) {
    int parent = 0;
    for (const FlatPose& pose : branch) {
        if (!box_.contains(pose.position) || !edgeValid(parent, pose.position))
            break;
        const TreeNode& from = tree_.node(parent);
        const double arrival =
            parts_.flight->reachTime({from.position, from.yaw}, from.time, pose.position);
        const YawGain view =
            parts_.view->viewOnArrival(from.position, pose.position, arrival, true);
        if (!timedValidFrom(parent, {pose.position, view.yaw}))
            break;
        parent = addNode(parent, pose.position, view);
    }
}

}  // namespace daep::planning
