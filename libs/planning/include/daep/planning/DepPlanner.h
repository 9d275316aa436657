#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "daep/planning/GainEvaluator.h"
#include "daep/planning/Planner.h"
#include "daep/planning/Roadmap.h"
#include "daep/planning/YawBinnedGain.h"

namespace daep::planning {

/** Section [dep] (plus robot_radius from [planning]); see share/daep/config/dep.ini. */
struct DepParams {
    bool replan = true;
    bool smooth = true;
    double edgeLength = 1.5;
    int neighbours = 15;
    double nodeSpacing = 0.8;
    double localExtent = 3.0;
    int samplesPerPlan = 400;
    int maxNewNodes = 40;
    int globalAfter = 3;
    int yawBins = 32;
    CellWeights weights;
    double candidateFraction = 0.1;
    double minGain = 1.0;
    int finishPlans = 10;
    int finishMinNodes = 2;
    double refreshStep = 1.0;
    double spentRatio = 0.8;
    int spentResetCells = 250;
    double replanLookahead = 3.0;
    double smoothMargin = 0.1;
    double robotRadius = 0.3;

    /** Reads and validates the keys; throws InputError naming the bad key. */
    static DepParams fromConfig(const mrpt::config::CConfigFileBase& config);
};

/**
 * DEP (Xu et al., IROS 2021): one probabilistic roadmap kept for the whole mission and grown
 * around the drone at every call; every node carries a gain per heading bin. The planner flies
 * to the candidate node (gain >= candidate_fraction of the best) with the best ratio of path
 * gain to flight plus turn time, along the roadmap's shortest path (lazily collision checked).
 * With replan = true the rest of the path is re-checked at every map update in flight and the
 * flight is aborted when it became blocked; the next call starts from where the drone stopped.
 */
class DepPlanner : public ExplorationPlanner {
public:
    DepPlanner(const DepParams& params, const GainParams& gain, std::uint64_t seed);

    std::string name() const override { return "dep"; }
    Plan plan(const PlanningContext& context) override;
    bool keepFlying(const PlanningContext& context, const Plan& plan,
                    std::size_t nextWaypoint) override;

    const Roadmap& roadmap() const { return roadmap_; }
    const DepParams& params() const { return params_; }
    /** Nodes added by the last plan() call (the start anchor included). */
    int lastNewNodes() const { return lastNewNodes_; }
    /** Nodes whose gains the last plan() call recomputed. */
    int lastRefreshed() const { return lastRefreshed_; }

    /** True when the capsule a-b stays in known free space and the climb fits the camera. */
    bool edgeValid(const mapping::ExplorationMap& map, const Eigen::Vector3d& a,
                   const Eigen::Vector3d& b) const;
    bool insideCone(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;

private:
    struct Choice {
        int goal = -1;
        std::vector<int> path;
        double gain = 0.0;
        double score = 0.0;
        bool unreachable = false;  ///< candidates exist but no safe path reaches one now
        double finalYaw = 0.0;     ///< heading at the goal when unreachable (facing the block)
    };

    int startNode(const PlanningContext& context);
    bool startSegmentSafe(const mapping::ExplorationMap& map, const Eigen::Vector3d& from,
                          const Eigen::Vector3d& to) const;
    /** Collision check of edge a-b; an anchor end is exempt within its own ball. */
    bool linkSafe(const mapping::ExplorationMap& map, int a, int b) const;
    /** When no edge out of `start` is safe now, links it to safe nodes up to 2 edges away. */
    void ensureExit(const mapping::ExplorationMap& map, int start);
    void evaluateGain(const mapping::ExplorationMap& map, int node);
    void refreshGains(const PlanningContext& context);
    int grow(const PlanningContext& context);
    void markSpentGoal(const PlanningContext& context, int start);
    void expireSpent(const mapping::ExplorationMap& map);
    bool tryAddSample(const mapping::ExplorationMap& map, const Eigen::Vector3d& sample);
    Choice choose(const PlanningContext& context, int start);
    Choice approach(const mapping::ExplorationMap& map, const Choice& blocked);
    Choice bestCandidate(const PlanningContext& context, int start,
                         const Roadmap::Paths& paths) const;
    double pathGain(const std::vector<int>& path) const;
    double pathTime(const PlanningContext& context, const std::vector<int>& path) const;
    std::vector<Eigen::Vector3d> smoothed(const mapping::ExplorationMap& map,
                                          std::vector<Eigen::Vector3d> points) const;
    Plan pathPlan(const PlanningContext& context, const Choice& choice);
    Plan waitPlan(const PlanningContext& context) const;

    DepParams params_;
    GainParams gainParams_;
    YawBinnedGain gain_;
    std::mt19937_64 rng_;
    Roadmap roadmap_;
    Aabb samplingBox_;
    std::vector<Eigen::Vector3d> lastPath_;  ///< positions of the last plan, for gain refresh
    int lastGoal_ = -1;  ///< goal node of the last path plan, its bin and gain when chosen
    int lastGoalBin_ = 0;
    double lastGoalGain_ = 0.0;
    int failedGrowth_ = 0;
    int idlePlans_ = 0;
    bool noCandidateLast_ = false;
    int lastNewNodes_ = 0;
    int lastRefreshed_ = 0;
};

}  // namespace daep::planning
