#include "daep/planning/Tree.h"

#include "daep/mapping/ExplorationMap.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace daep::planning {

void Tree::reset(const FlatPose& root) {
    nodes_.clear();
    TreeNode node;
    node.position = root.position;
    node.yaw = root.yaw;
    nodes_.push_back(node);
}

int Tree::add(int parent, const Eigen::Vector3d& position, double yaw) {
    TreeNode node;
    node.position = position;
    node.yaw = yaw;
    node.parent = parent;
    node.cost = nodes_[parent].cost + (position - nodes_[parent].position).norm();
    nodes_.push_back(node);
    return size() - 1;
}

int Tree::nearest(const Eigen::Vector3d& p) const {
    int best = -1;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (int i = 0; i < size(); ++i) {
        const double d = (nodes_[i].position - p).squaredNorm();
        if (d < bestDistance) {
            bestDistance = d;
            best = i;
        }
    }
    return best;
}

int Tree::bestByScore() const {
    int best = -1;
    for (int i = 1; i < size(); ++i) {
        if (best < 0 || nodes_[i].score > nodes_[best].score)
            best = i;
    }
    return best;
}

std::vector<int> Tree::branch(int node) const {
    std::vector<int> path;
    for (int i = node; i > 0; i = nodes_[i].parent)
        path.push_back(i);
    std::reverse(path.begin(), path.end());
    return path;
}

std::vector<TreeEdge> Tree::edges() const {
    std::vector<TreeEdge> result;
    result.reserve(nodes_.size());
    for (const TreeNode& n : nodes_) {
        if (n.parent >= 0)
            result.push_back({nodes_[n.parent].position, n.position});
    }
    return result;
}

Eigen::Vector3d steer(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double maxStep) {
    const Eigen::Vector3d d = to - from;
    const double length = d.norm();
    if (length <= maxStep)
        return to;
    return from + d * (maxStep / length);
}

Aabb shrink(const Aabb& box, double margin) {
    Aabb out;
    for (int a = 0; a < 3; ++a) {
        const double lo = box.min[a] + margin;
        const double hi = box.max[a] - margin;
        const double mid = 0.5 * (box.min[a] + box.max[a]);
        out.min[a] = lo <= hi ? lo : mid;
        out.max[a] = lo <= hi ? hi : mid;
    }
    return out;
}

Eigen::Vector3d sampleInBox(const Aabb& box, std::mt19937_64& rng) {
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a) {
        p[a] = std::uniform_real_distribution<double>(box.min[a], box.max[a])(rng);
    }
    return p;
}

double sampleYaw(std::mt19937_64& rng) {
    return std::uniform_real_distribution<double>(-M_PI, M_PI)(rng);
}

bool segmentFlyable(const mapping::ExplorationMap& map, const Eigen::Vector3d& a,
                    const Eigen::Vector3d& b, double radius, bool leavingBlockedRoot) {
    if (!leavingBlockedRoot)
        return map.isSegmentFree(a, b, radius);
    const double length = (b - a).norm();
    const Eigen::Vector3d start =
        length > radius ? Eigen::Vector3d(a + (b - a) * (radius / length)) : b;
    return map.isSegmentFreeOrUnknown(start, b, radius) && map.isSegmentFree(b, b, radius);
}

}  // namespace daep::planning
