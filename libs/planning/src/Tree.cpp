#include "daep/planning/Tree.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace daep::planning {

void Tree::reset(const FlatPose& root) {
    nodes_.clear();
    xs_.clear();
    ys_.clear();
    zs_.clear();
    TreeNode node;
    node.position = root.position;
    node.yaw = root.yaw;
    append(node);
}

void Tree::append(const TreeNode& node) {
    nodes_.push_back(node);
    xs_.push_back(node.position.x());
    ys_.push_back(node.position.y());
    zs_.push_back(node.position.z());
}

int Tree::add(int parent, const Eigen::Vector3d& position, double yaw) {
    TreeNode node;
    node.position = position;
    node.yaw = yaw;
    node.parent = parent;
    node.cost = nodes_[parent].cost + (position - nodes_[parent].position).norm();
    append(node);
    return size() - 1;
}

int Tree::nearest(const Eigen::Vector3d& p) const {
    int best = -1;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (int i = 0; i < size(); ++i) {
        const double d = squaredDistance(i, p);
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

}  // namespace daep::planning
