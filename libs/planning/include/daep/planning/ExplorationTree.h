#pragma once

#include <Eigen/Core>
#include <vector>

#include "daep/common/Types.h"
#include "daep/planning/Tree.h"
#include "daep/planning/TreeParts.h"

namespace daep::planning {

/**
 * The exploration RRT* of AEP and DAEP (the paper's time-aware tree when its parts know the
 * people): nodes steered towards samples, each given the cheapest valid parent within the
 * rewire radius, its view on arrival and its branch score; neighbours rewired through it when
 * that shortens their way and everything the rewire re-times stays valid; a previous best
 * branch re-added below a new root.
 *
 * Every node carries its arrival time, computed by the flight model along the branch. The
 * parts decide the rest: which moves are valid (statically, and timed against people), what a
 * node sees when it arrives, and how a branch is scored. The sampling (where, how many) is
 * the planner's.
 */
class ExplorationTree {
public:
    ExplorationTree(double extensionRange, double rewireRadius);

    /** What a tree is grown for: views to score (local), or only ways to a goal (global). */
    enum class Growth { Views, Ways };

    /**
     * Starts over from `root` at `time`. `rootFree`: the drone's own ball is clear (else the
     * first move out of it only has to leave, see segmentFlyable). Nodes stay in `box`.
     */
    void reset(const FlatPose& root, double time, bool rootFree, const Aabb& box,
               const TreeParts& parts, Growth growth);

    /**
     * One RRT* step towards the sample: steer, pick the cheapest valid parent within the rewire
     * radius, add the node, rewire neighbours through it. Growing views, the node gets its
     * view on arrival; growing ways, it faces along its edge with no gain. Returns the new
     * node or -1.
     */
    int extend(const Eigen::Vector3d& sample);

    /** Re-adds a branch below the root, pose by pose, while each move stays valid. */
    void reuseBranch(const std::vector<FlatPose>& branch);

    /** The straight move from node `parent` to `to` is statically valid. */
    bool edgeValid(int parent, const Eigen::Vector3d& to) const;

    /** Overwrites a node's gain (its score is left as it is). */
    void setGain(int node, double gain) { tree_.node(node).gain = gain; }

    const Tree& tree() const { return tree_; }

private:
    /** The timed move from node `parent`, at its arrival time, to `to` is valid. */
    bool timedValidFrom(int parent, const FlatPose& to) const;
    void setParent(int node, int parent);
    /** Sets a node's cost, arrival time and score from its parent's. */
    void timeFromParent(int node);
    /** timeFromParent for a node and its whole subtree. */
    void propagate(int node);
    /**
     * Moves `node` under `parent` when its whole re-timed subtree stays valid; else leaves the
     * tree as it was. Returns whether it moved.
     */
    bool rewire(int node, int parent);
    /**
     * propagate() that re-checks what it re-times: a view people may stand in (at the old or
     * the new arrival) is seen again at the new arrival, and every re-timed move is checked
     * against the people. False at the first move that is no longer valid.
     */
    bool retime(int node);
    void saveSubtree(int node, std::vector<std::pair<int, TreeNode>>& saved) const;
    /** Appends a node under parent and sets its cost, time and score from the parent's. */
    int addNode(int parent, const Eigen::Vector3d& p, const YawGain& view);
    void rewireThrough(int added, const std::vector<std::pair<double, int>>& neighbours,
                       int parent);

    double extensionRange_;
    double rewireRadius_;
    Tree tree_;
    std::vector<std::vector<int>> children_;
    Aabb box_;
    bool rootFree_ = true;
    TreeParts parts_;
    Growth growth_ = Growth::Views;
};

}  // namespace daep::planning
