#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "daep/planning/GainCache.h"
#include "daep/planning/GainEvaluator.h"
#include "daep/planning/GaussianProcess.h"
#include "daep/planning/Planner.h"
#include "daep/planning/Tree.h"

namespace daep::planning {

/** Sections [aep] and [planning]. */
struct AepParams {
    double extensionRange = 1.0;
    double samplingRadius = 10.0;
    double rewireRadius = 1.5;
    int initialIterations = 15;
    int cutoffIterations = 30;
    int maxSamples = 2000;
    double lambda = 0.75;
    double zeroGain = 25.0;
    double sigmaThreshold = 0.2;
    GpParams gp;
    double gpRadius = 2.0;
    int gpMaxNeighbours = 10;
    double cacheThreshold = 15.0;
    double cacheUpdateRadius = 5.0;
    int globalMinNodes = 100;
    int globalMaxNodes = 1500;
    int globalMaxSamples = 20000;
    double globalGoalBias = 0.2;
    double goalRadius = 1.5;
    /** Failed global plans in a row that finish the mission; 0: never (only no frontier left). */
    int globalPlannerCounter = 25;
    /** After a failed global plan that does not finish the mission, hover this long (s). */
    double globalRetryWait = 0.0;
    /**
     * When no frontier is cached, look for viewpoints on the map's own frontier before saying
     * "finished" (the cache holds only what the trees' samples saw; a region no tree reached
     * can hold most of what is left). Off for the reference AEP baseline.
     */
    bool mapFrontiers = false;
    double robotRadius = 0.3;
    /**
     * [planning] path_space = not_occupied: nodes and moves may lie in unknown space (only
     * occupied cells block, as the reference planners' line check), up to the box's top less
     * the drone's half-height; known_free: known free space only, in the box shrunk by the
     * robot radius.
     */
    bool crossUnknown = false;

    /** Reads and validates the keys of `section`; throws InputError naming the bad key. */
    static AepParams fromConfig(const mrpt::config::CConfigFileBase& config,
                                const std::string& section = "aep");
};

/** Counters of the last plan() call, for tests and benchmarks. */
struct AepStats {
    int rayCasts = 0;
    int gpPredictions = 0;
    int cacheRefreshed = 0;
    int cacheDropped = 0;
    int samples = 0;
    bool global = false;
};

/**
 * Autonomous Exploration Planner (Selin et al. 2019).
 *
 * Local: an RRT* grown from the pose with samples drawn uniformly in the 3D ball of
 * max_sampling_radius clipped to the exploration box (not AEP's x/y-only "dimension reduction";
 * the worlds are 2-2.5 m tall, so the two differ little). Nodes lie in known free space with the
 * robot capsule clear. Node value = parent value + gain * exp(-lambda * edge length); the gain
 * is the best-yaw cubature, or the gain cache's Gaussian-process estimate where it is confident.
 * The first edge of the best branch is flown and the rest of the branch seeds the next tree.
 *
 * Global: when no branch is worth more than zero_gain, the cached viewpoints (gain above
 * cache_node_threshold) are the frontiers. An RRT* through known free space (at least
 * global_min_nodes) gives the cheapest path to one, flown in full and ending at the frontier's
 * best yaw. The global tree's nodes are also gain-evaluated, so viewpoints that no local tree
 * reached become frontiers too. No frontier left after a full global tree: finished.
 */
class AepPlanner : public ExplorationPlanner {
public:
    AepPlanner(const AepParams& params, const GainParams& gain, std::uint64_t seed);

    std::string name() const override { return "aep"; }
    Plan plan(const PlanningContext& context) override;
    bool keepFlying(const PlanningContext& context, const Plan& plan,
                    std::size_t nextWaypoint) override;

    const Tree& tree() const { return tree_; }
    const GainCache& cache() const { return cache_; }
    GainCache& cache() { return cache_; }
    const AepParams& params() const { return params_; }
    const AepStats& stats() const { return stats_; }

    /** Gain and yaw at p: the cache's GP estimate when confident, else ray cast (and cached). */
    YawGain evaluateGain(const mapping::ExplorationMap& map, const Eigen::Vector3d& p);

    /** Re-casts cached viewpoints near the places flown since the last call; drops weak ones. */
    void refreshCache(const mapping::ExplorationMap& map, const Eigen::Vector3d& pose);

protected:
    // Hooks through which DAEP makes the same trees aware of moving people.

    /**
     * The gain at p for a drone arriving at `arrival` from `from` (AEP: the static gain at the
     * best yaw, from the cache's GP where it is confident unless `rayCast`; DAEP: the dynamic
     * information gain d(p, t)).
     */
    virtual YawGain gainOnArrival(const PlanningContext& context, const Eigen::Vector3d& from,
                                  const Eigen::Vector3d& p, double arrival, bool rayCast);
    /** Whether turning then flying from `from` at `start` to `to` is safe (AEP: always). */
    virtual bool moveSafe(const FlatPose& from, double start, const FlatPose& to) const;
    /** moveSafe from tree node `parent` at its arrival time. */
    bool moveSafeFrom(int parent, const FlatPose& to) const;
    /** Time to get from pose a to pose b (AEP: turn to b's yaw, then fly). */
    virtual double moveTime(const FlatPose& a, const FlatPose& b) const;
    /** A node's score from its parent's: AEP adds gain * exp(-lambda * edge); DAEP's is the
     * dynamic score s(p, t). */
    virtual double branchScore(double parentValue, double gain, double edge,
                               const Eigen::Vector3d& p) const;
    /**
     * Asked when the global tree found no way to any frontier: whether people alone are in
     * the way, so the frontiers are kept and tried again as the people move, instead of the
     * failure counting towards the end of the mission (AEP: never, it ignores people).
     */
    virtual bool peopleBlockFrontiers(const PlanningContext& context);
    /**
     * Grows a global tree from the pose towards the live frontiers (its nodes' gains enter
     * the cache, so it also finds new ones); true when it reaches one.
     */
    bool globalTreeReachesFrontier(const PlanningContext& context);
    GainEvaluator& gainEvaluator() { return gain_; }
    const GainEvaluator& gainEvaluator() const { return gain_; }
    const MotionLimits& motion() const { return motion_; }
    AepStats& mutableStats() { return stats_; }

private:
    bool edgeValid(const PlanningContext& context, int parent, const Eigen::Vector3d& to) const;
    /** A straight move from a to b lies in the path space (see AepParams::crossUnknown). */
    bool moveInPathSpace(const PlanningContext& context, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b, bool leavingBlocked) const;
    Eigen::Vector3d sampleLocal(const Eigen::Vector3d& center);
    /**
     * One RRT* step towards the sample: steer, pick the cheapest valid parent within the rewire
     * radius, add the node (with its gain in a local tree), rewire neighbours through it.
     * Returns the new node or -1.
     */
    int extend(const PlanningContext& context, const Eigen::Vector3d& sample);
    void setParent(int node, int parent);
    void propagate(int node);
    /** Appends a node under parent and sets its cost and score from the parent's. */
    int addNode(int parent, const Eigen::Vector3d& p, const YawGain& view);
    void reinsertPreviousBranch(const PlanningContext& context);
    void growLocal(const PlanningContext& context);
    void resetTree(const PlanningContext& context);
    Plan localPlan(const PlanningContext& context);
    /**
     * When the deadline passed during the local growth: the best branch grown so far if it
     * has any gain, else no path (neither counts as a failed global plan).
     */
    Plan planAtDeadline(const PlanningContext& context);
    Plan globalPlan(const PlanningContext& context, double localScore);
    /**
     * Caches the viewpoints on the map's reachable frontier whose ray-cast gain passes the
     * cache threshold (see AepParams::mapFrontiers).
     */
    void cacheMapFrontiers(const PlanningContext& context);
    /** Re-casts a cached viewpoint; drops it (false) when its gain fell to the threshold. */
    bool verifyFrontier(const mapping::ExplorationMap& map, int id);
    /** Returns whether a node came within goal_radius of a live frontier. */
    bool growGlobal(const PlanningContext& context, const std::vector<int>& frontiers);
    std::vector<Eigen::Vector3d> shortcut(const PlanningContext& context,
                                          const std::vector<Eigen::Vector3d>& path) const;
    Plan pathPlan(const PlanningContext& context, const std::vector<Eigen::Vector3d>& path,
                  double finalYaw) const;

    AepParams params_;
    MotionLimits motion_;
    GainEvaluator gain_;
    GaussianProcess gp_;
    GainCache cache_;
    std::mt19937_64 rng_;
    Tree tree_;
    std::vector<std::vector<int>> children_;
    Aabb samplingBox_;
    bool rootFree_ = true;
    bool globalTree_ = false;
    int best_ = -1;
    int globalFailures_ = 0;
    AepStats stats_;
    std::vector<FlatPose> previousBranch_;
    std::vector<Eigen::Vector3d> trail_;  ///< where the drone flew since the last plan
};

}  // namespace daep::planning
