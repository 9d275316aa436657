#pragma once

#include <Eigen/Core>
#include <random>
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

/** `to`, moved towards `from` so that it lies at most maxStep away. */
Eigen::Vector3d steer(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double maxStep);

/**
 * Whether the drone can fly a -> b with its capsule of `radius` in known free space. With
 * `leavingBlockedRoot` (the drone is at a, but its own ball is not known free: cells around it
 * unseen, or an obstacle nearer than the radius) the first radius is skipped, the rest must not
 * touch occupied cells and b must be known free: the drone is physically at a and must be able
 * to leave.
 */
bool segmentFlyable(const mapping::ExplorationMap& map, const Eigen::Vector3d& a,
                    const Eigen::Vector3d& b, double radius, bool leavingBlockedRoot);

/** The box shrunk by margin on every side (collapsing to its centre along too-thin axes). */
Aabb shrink(const Aabb& box, double margin);

/** A uniform point in the box. */
Eigen::Vector3d sampleInBox(const Aabb& box, std::mt19937_64& rng);

/** A uniform yaw in [-pi, pi). */
double sampleYaw(std::mt19937_64& rng);

}  // namespace daep::planning
