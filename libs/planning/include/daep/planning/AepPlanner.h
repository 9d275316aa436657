#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "daep/planning/ExplorationTree.h"
#include "daep/planning/FlightModel.h"
#include "daep/planning/GainCache.h"
#include "daep/planning/GainEvaluator.h"
#include "daep/planning/GaussianProcess.h"
#include "daep/planning/Planner.h"
#include "daep/planning/TreeParts.h"

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
    GpParams gp;
    CachedViewParams view;  ///< gp_radius, gp_max_neighbours, sigma_thresh, cache_node_threshold
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
    /**
     * When the global tree reaches no frontier, search the map's known free cells (with the
     * drone's clearance) for a way to one before the plan counts as failed: a sampled tree's
     * budget can miss a narrow passage far off. Off for the reference AEP baseline.
     */
    bool mapPaths = false;
    double robotRadius = 0.3;
    double bodyHalfHeight = 0.05;  ///< half the drone's height ([drone] box_z)
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
 *
 * Both trees are one ExplorationTree over AEP's parts (the static path space, the cached view,
 * AepScore); DAEP composes its own (compose()).
 */
class AepPlanner : public ExplorationPlanner {
public:
    AepPlanner(const AepParams& params, const GainParams& gain, std::uint64_t seed);
    // The tree's parts refer to the planner's own gain cache and counters.
    AepPlanner(const AepPlanner&) = delete;
    AepPlanner& operator=(const AepPlanner&) = delete;

    std::string name() const override { return "aep"; }
    Plan plan(const PlanningContext& context) override;
    bool keepFlying(const PlanningContext& context, const Plan& plan,
                    std::size_t nextWaypoint) override;

    const Tree& tree() const { return tree_.tree(); }
    const GainCache& cache() const { return cache_; }
    GainCache& cache() { return cache_; }
    const AepParams& params() const { return params_; }
    const AepStats& stats() const { return stats_; }
    /** The parts the tree is grown with: AEP's, or those a subclass composed. */
    const TreeParts& parts() const { return parts_; }

    /** Gain and yaw at p: the cache's GP estimate when confident, else ray cast (and cached). */
    YawGain evaluateGain(const mapping::ExplorationMap& map, const Eigen::Vector3d& p);

    /** Re-casts cached viewpoints near the places flown since the last call; drops weak ones. */
    void refreshCache(const mapping::ExplorationMap& map, const Eigen::Vector3d& pose);

protected:
    /**
     * Whether what hems the drone in where it hovers may be a person's imprint, mapped after
     * it came (then a global tree with no node does not count as a failed global plan). AEP
     * maps people as it sees them and counts it.
     */
    virtual bool mayBeHemmedByPeople() const { return false; }
    /**
     * Grows the trees over other parts (DAEP: the time-aware validator, the dynamic score and
     * the dynamic information gain). They must outlive the planner's use of them; the flight
     * model stays the planner's own (flight()).
     */
    void compose(const MoveValidator& moves, const BranchObjective& objective, ViewModel& view);
    /** AEP's static path space, bound to the map of the current plan() call. */
    const PathSpaceValidator& pathSpace() const { return pathSpace_; }
    /** AEP's view: cached cubature gains and their GP estimate. */
    CachedView& cachedView() { return cachedView_; }
    FlightModel& flight() { return flight_; }
    const FlightModel& flight() const { return flight_; }
    GainEvaluator& gainEvaluator() { return gain_; }
    const GainEvaluator& gainEvaluator() const { return gain_; }

private:
    Eigen::Vector3d sampleLocal(const Eigen::Vector3d& center);
    void resetTree(const PlanningContext& context, ExplorationTree::Growth growth);
    void growLocal(const PlanningContext& context);
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
    /** Inside the sampling box, the drone's ball known free: where the map's walks may go. */
    bool hasClearance(const Eigen::Vector3d& p) const;
    /**
     * A path to the nearest live frontier through the map's known free cells
     * (AepParams::mapPaths), shortcut like a tree's; no path (status NoPath) when none is
     * found or a leg of it fails the static path space.
     */
    Plan mapPathPlan(const PlanningContext& context);
    /** The plan flying `path` (from the drone) to cached frontier f, seen from its yaw. */
    Plan frontierPlan(const PlanningContext& context, const std::vector<Eigen::Vector3d>& path,
                      int f);
    /** Re-casts a cached viewpoint; drops it (false) when its gain fell to the threshold. */
    bool verifyFrontier(const mapping::ExplorationMap& map, int id);
    /** Returns whether a node came within goal_radius of a live frontier. */
    bool growGlobal(const PlanningContext& context, const std::vector<int>& frontiers);
    /**
     * Asked when the global tree found no way to any frontier: whether people alone are in
     * the way (a global tree grown over the static path space reaches one: dynamic frontiers),
     * or no tree grows at all while someone is in view of the drone (what they hide is not
     * judged yet). Then the frontiers are kept and tried again as the people move, instead of
     * the failure counting towards the end of the mission.
     */
    bool peopleBlockFrontiers(const PlanningContext& context);
    /** `path` with cached frontier f's position appended when the last leg to it is valid. */
    std::vector<Eigen::Vector3d> withFrontier(std::vector<Eigen::Vector3d> path, int f) const;
    std::vector<Eigen::Vector3d> shortcut(const PlanningContext& context,
                                          const std::vector<Eigen::Vector3d>& path) const;
    Plan pathPlan(const PlanningContext& context, const std::vector<Eigen::Vector3d>& path,
                  double finalYaw) const;

    AepParams params_;
    FlightModel flight_;
    GainEvaluator gain_;
    GaussianProcess gp_;
    GainCache cache_;
    AepStats stats_;
    PathSpaceValidator pathSpace_;
    AepScore aepScore_;
    CachedView cachedView_;
    TreeParts parts_;
    std::mt19937_64 rng_;
    ExplorationTree tree_;
    Aabb samplingBox_;
    bool rootFree_ = true;
    int best_ = -1;
    int globalFailures_ = 0;
    std::vector<FlatPose> previousBranch_;
    std::vector<Eigen::Vector3d> trail_;  ///< where the drone flew since the last plan
};

}  // namespace daep::planning
