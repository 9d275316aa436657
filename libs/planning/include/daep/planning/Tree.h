#pragma once

#include <Eigen/Core>
#include <vector>

#include "daep/common/Types.h"
#include "daep/planning/Planner.h"

namespace daep::planning {

/** A node of an exploration RRT. Node 0 is the root (the current pose). */
struct TreeNode {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    double yaw = 0.0;
    int parent = -1;     ///< -1 for the root
    double gain = 0.0;   ///< unknown volume seen from this node (m^3)
    double score = 0.0;  ///< planner-specific value
    double cost = 0.0;   ///< path length from the root (m)
    double time = 0.0;   ///< expected arrival time (absolute, s): turn then fly from the parent
};

/** A rooted tree of viewpoints; nodes are only appended, so indices stay valid. */
class Tree {
public:
    /** Drops all nodes and starts over from `root`. */
    void reset(const FlatPose& root);

    /** Appends a child of `parent`; its cost is the parent's plus the edge length. */
    int add(int parent, const Eigen::Vector3d& position, double yaw);

    /** Index of the node closest to p (lowest index on ties). */
    int nearest(const Eigen::Vector3d& p) const;

    /** Non-root node with the highest score, or -1 when the tree is only its root. */
    int bestByScore() const;

    /** Node indices from the root's child down to `node` (empty for the root). */
    std::vector<int> branch(int node) const;

    std::vector<TreeEdge> edges() const;

    const TreeNode& node(int i) const { return nodes_[i]; }
    TreeNode& node(int i) { return nodes_[i]; }
    const std::vector<TreeNode>& nodes() const { return nodes_; }
    int size() const { return static_cast<int>(nodes_.size()); }

private:
    std::vector<TreeNode> nodes_;
};

}  // namespace daep::planning
