#pragma once

#include <Eigen/Core>
#include <vector>

#include "daep/common/Types.h"
#include "daep/planning/GainEvaluator.h"

namespace daep::mapping {
class ExplorationMap;
}

namespace daep::planning {

class GainCache;
class GaussianProcess;
struct FlightModel;

// The parts an exploration tree is composed of, as OMPL composes a planner of a motion
// validator and an optimization objective: AEP and DAEP grow the same tree over different
// parts (DynamicTreeParts.h holds DAEP's).

/** Counters of the last plan() call, for tests and benchmarks. */
struct AepStats {
    int rayCasts = 0;
    int gpPredictions = 0;
    int cacheRefreshed = 0;
    int cacheDropped = 0;
    int samples = 0;
    bool global = false;
};

/** Which moves the tree may make (OMPL's MotionValidator, split in its static and timed half). */
class MoveValidator {
public:
    virtual ~MoveValidator() = default;
    /**
     * The straight move a -> b keeps the drone's clearance from the map. `leavingBlocked`: the
     * drone is at a but its own ball is not clear (see segmentFlyable); it must be able to leave.
     */
    virtual bool staticValid(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             bool leavingBlocked) const = 0;
    /** The move from `from` at time `start` to `to`, flown as the drone flies, meets nobody. */
    virtual bool timedValid(const FlatPose& from, double start, const FlatPose& to) const = 0;
    /** Whether timedValid can refuse a move: there are people to meet. */
    virtual bool checksPeople() const = 0;
};

/** The value of a branch, node by node (OMPL's OptimizationObjective, maximised). */
class BranchObjective {
public:
    virtual ~BranchObjective() = default;
    /** A node's score from its parent's, its gain and the edge (m) that reaches it at p. */
    virtual double score(double parentScore, double gain, double edge,
                         const Eigen::Vector3d& p) const = 0;
};

/** What a node sees: its information gain and the yaw it is best seen at. */
class ViewModel {
public:
    virtual ~ViewModel() = default;
    /**
     * The view at p for a drone arriving at `arrival` from `from`; `rayCast` asks for a ray
     * cast even where an estimate would do (a reused branch is judged afresh).
     */
    virtual YawGain viewOnArrival(const Eigen::Vector3d& from, const Eigen::Vector3d& p,
                                  double arrival, bool rayCast) = 0;
    /** Whether someone may stand in the view from p at time t (so the view may change). */
    virtual bool peopleInView(const Eigen::Vector3d& p, double t) const = 0;
};

/**
 * The static path space: known free space with the robot radius clear (segmentFlyable), or,
 * crossing unknown space, everything not occupied. Moves are never refused for people.
 */
class PathSpaceValidator final : public MoveValidator {
public:
    void bind(const mapping::ExplorationMap& map, double robotRadius, double bodyHalfHeight,
              bool crossUnknown);
    bool staticValid(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                     bool leavingBlocked) const override;
    bool timedValid(const FlatPose&, double, const FlatPose&) const override { return true; }
    bool checksPeople() const override { return false; }

private:
    const mapping::ExplorationMap* map_ = nullptr;
    double robotRadius_ = 0.0;
    double bodyHalfHeight_ = 0.0;
    bool crossUnknown_ = false;
};

/** AEP's score: s = s(parent) + gain exp(-lambda edge). */
class AepScore final : public BranchObjective {
public:
    explicit AepScore(double lambda) : lambda_(lambda) {}
    double score(double parentScore, double gain, double edge,
                 const Eigen::Vector3d& p) const override;

private:
    double lambda_;
};

/** Section [aep]'s keys of the cached view. */
struct CachedViewParams {
    double gpRadius = 2.0;
    int gpMaxNeighbours = 10;
    double sigmaThreshold = 0.2;
    double cacheThreshold = 15.0;
};

/**
 * AEP's view: the cubature gain at the best yaw, ray cast and cached when above the cache
 * threshold, or estimated by a Gaussian process over the cached gains nearby where it is
 * confident. Time plays no part.
 */
class CachedView final : public ViewModel {
public:
    CachedView(const CachedViewParams& params, const GainEvaluator& gain, GainCache& cache,
               GaussianProcess& gp, AepStats& stats);
    void bind(const mapping::ExplorationMap& map) { map_ = &map; }

    /** The GP's estimate where it is confident, else a ray cast (cached when high). */
    YawGain estimate(const mapping::ExplorationMap& map, const Eigen::Vector3d& p);
    /** The ray-cast view at p, rays stopped by `occluders` when given; counted. */
    YawGain rayCast(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                    const std::vector<BodyOccluder>* occluders = nullptr);
    /** The unknown volume per azimuth column at p (GainEvaluator::columns); counted. */
    std::vector<double> rayCastColumns(const Eigen::Vector3d& p,
                                       const std::vector<BodyOccluder>* occluders);
    /** The columns at p without and with `occluders`, from one march; counted as two. */
    GainEvaluator::ColumnViews rayCastColumnsOpenAndOccluded(
        const Eigen::Vector3d& p, const std::vector<BodyOccluder>& occluders);
    /** Caches the view at p when its gain passes the cache threshold. */
    void remember(const Eigen::Vector3d& p, const YawGain& view);
    const GainEvaluator& evaluator() const { return gain_; }
    /** The map of the current plan() call. */
    const mapping::ExplorationMap& map() const { return *map_; }

    YawGain viewOnArrival(const Eigen::Vector3d& from, const Eigen::Vector3d& p, double arrival,
                          bool rayCast) override;
    bool peopleInView(const Eigen::Vector3d&, double) const override { return false; }

private:
    CachedViewParams params_;
    const GainEvaluator& gain_;
    GainCache& cache_;
    GaussianProcess& gp_;
    AepStats& stats_;
    const mapping::ExplorationMap* map_ = nullptr;
};

/** The parts a tree is grown with. */
struct TreeParts {
    const MoveValidator* moves = nullptr;
    const BranchObjective* objective = nullptr;
    ViewModel* view = nullptr;
    const FlightModel* flight = nullptr;
};

}  // namespace daep::planning
