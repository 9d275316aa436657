#pragma once

#include <Eigen/Core>
#include <cmath>
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

/**
 * A rooted tree of viewpoints; nodes are only appended, so indices stay valid. A node's
 * position never changes once added: the tree keeps a copy of the positions, axis by axis, for
 * its distance scans.
 */
class Tree {
public:
    /** Drops all nodes and starts over from `root`. */
    void reset(const FlatPose& root);

    /** Appends a child of `parent`; its cost is the parent's plus the edge length. */
    int add(int parent, const Eigen::Vector3d& position, double yaw);

    /** Index of the node closest to p (lowest index on ties). */
    int nearest(const Eigen::Vector3d& p) const;

    /**
     * Calls near(i, distance) in index order for node `always` and every node within `radius`
     * of p; distance is (position - p).norm(), bit for bit.
     */
    template <class Near>
    void forEachNear(const Eigen::Vector3d& p, double radius, int always, const Near& near) const {
        // The squared test with a margin, then the exact one on the distance itself.
        const double loose = radius * radius * (1.0 + 1e-9);
        for (int i = 0; i < size(); ++i) {
            const double d2 = squaredDistance(i, p);
            if (i != always && !(d2 <= loose))
                continue;
            const double d = std::sqrt(d2);
            if (i == always || d <= radius)
                near(i, d);
        }
    }

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
    /** (position - p).squaredNorm() of node i, in Eigen's order: (x^2 + y^2) + z^2. */
    double squaredDistance(int i, const Eigen::Vector3d& p) const {
        const double dx = xs_[std::size_t(i)] - p.x(), dy = ys_[std::size_t(i)] - p.y(),
                     dz = zs_[std::size_t(i)] - p.z();
        return (dx * dx + dy * dy) + dz * dz;
    }
    void append(const TreeNode& node);

    std::vector<TreeNode> nodes_;
    std::vector<double> xs_, ys_, zs_;  ///< node positions, contiguous per axis
};

}  // namespace daep::planning
