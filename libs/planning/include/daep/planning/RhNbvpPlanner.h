#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "daep/planning/GainEvaluator.h"
#include "daep/planning/Planner.h"
#include "daep/planning/Tree.h"
#include "daep/planning/TreeParts.h"

namespace daep::planning {

/** Sections [rhnbvp] and [planning]. */
struct RhNbvpParams {
    double extensionRange = 1.0;
    int initialIterations = 15;
    int cutoffIterations = 200;
    double lambda = 0.5;
    double zeroGain = 2.0;
    int maxSamples = 10000;
    double robotRadius = 0.3;
    double bodyHalfHeight = 0.05;  ///< half the drone's height ([drone] box_z)

    /** Reads and validates the keys; throws InputError naming the bad key. */
    static RhNbvpParams fromConfig(const mrpt::config::CConfigFileBase& config);
};

/**
 * Receding-horizon next-best-view planner (Bircher et al. 2016). Each call grows an RRT from the
 * current pose in known free space; a node's value is its parent's plus its gain discounted by
 * exp(-lambda * path length). Only the first edge of the best branch is returned; the rest of
 * that branch seeds the next tree.
 *
 * When the root's own neighbourhood is not known free (cells around the drone never seen, or an
 * obstacle closer than the robot radius), the root is accepted as is: the drone is physically
 * there. Edges leaving it are then checked from one robot radius out along the edge, must not
 * touch occupied cells, and must end in known free space.
 */
class RhNbvpPlanner : public ExplorationPlanner {
public:
    RhNbvpPlanner(const RhNbvpParams& params, const GainParams& gain, std::uint64_t seed);

    std::string name() const override { return "rhnbvp"; }
    Plan plan(const PlanningContext& context) override;

    /** The tree grown by the last plan() call. */
    const Tree& tree() const { return tree_; }
    const RhNbvpParams& params() const { return params_; }

private:
    bool edgeValid(int parent, const Eigen::Vector3d& to) const;
    int addNode(const PlanningContext& context, int parent, const Eigen::Vector3d& position,
                double yaw);
    void reinsertPreviousBranch(const PlanningContext& context);
    void grow(const PlanningContext& context);
    bool goodEnough() const;
    Plan makePlan(const PlanningContext& context);

    RhNbvpParams params_;
    GainEvaluator gain_;
    std::mt19937_64 rng_;
    PathSpaceValidator pathSpace_;  ///< known free space, as AEP's default
    Tree tree_;
    Aabb samplingBox_;
    bool rootFree_ = true;
    int best_ = -1;
    int samples_ = 0;
    std::vector<FlatPose> previousBranch_;
};

}  // namespace daep::planning
