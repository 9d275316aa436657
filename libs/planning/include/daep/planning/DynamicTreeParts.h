#pragma once

#include <Eigen/Core>
#include <vector>

#include "daep/planning/TreeParts.h"

namespace daep::planning {

class DynamicObstacles;
class DynamicFrequencyMap;

// DAEP's parts of the exploration tree: with them the tree is the paper's time-aware tree.

/** The form of the dynamic score ([daep] score). */
enum class DynamicScore {
    Paper,      ///< s = parent + d exp(-lambda c) (1 + zeta DFM)
    Reference,  ///< the reference code's: the DFM boost in the exponent
};

/**
 * The time-aware move check: the static path space, plus the move flown as the flight model
 * flies it (turns included) over its time interval, clear of every predicted body.
 */
class TimeAwareValidator final : public MoveValidator {
public:
    TimeAwareValidator(const MoveValidator& pathSpace, const DynamicObstacles& bodies,
                       const FlightModel& flight);
    bool staticValid(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                     bool leavingBlocked) const override;
    bool timedValid(const FlatPose& from, double start, const FlatPose& to) const override;
    bool checksPeople() const override;

private:
    const MoveValidator& pathSpace_;
    const DynamicObstacles& bodies_;
    const FlightModel& flight_;
};

/** The dynamic score s(p, t): AEP's, boosted where the dynamic frequency map saw people. */
class DynamicScoreObjective final : public BranchObjective {
public:
    DynamicScoreObjective(DynamicScore form, double lambda, double zeta,
                          const DynamicFrequencyMap& dfm);
    double score(double parentScore, double gain, double edge,
                 const Eigen::Vector3d& p) const override;

private:
    DynamicScore form_;
    double lambda_;
    double zeta_;
    const DynamicFrequencyMap& dfm_;
};

/**
 * The dynamic information gain d(p, t): the cubature gain with rays stopped by the bodies
 * predicted at the arrival time. Where no body is in range it is AEP's cached view (the
 * reference DAEP ray casts every node). A view people hide for now is also cached as if
 * nobody stood in it: such a frontier stays a frontier. With the flight model's faceTravel
 * the view at p is the one along the leg that reaches it (no turn at the end).
 */
class DynamicInformationGain final : public ViewModel {
public:
    DynamicInformationGain(CachedView& staticView, const DynamicObstacles& bodies,
                           const FlightModel& flight);
    YawGain viewOnArrival(const Eigen::Vector3d& from, const Eigen::Vector3d& p, double arrival,
                          bool rayCast) override;
    bool peopleInView(const Eigen::Vector3d& p, double t) const override;
    /** The predicted bodies at time t within the view's range of p. */
    std::vector<BodyOccluder> bodiesInView(const Eigen::Vector3d& p, double t) const;

private:
    CachedView& staticView_;
    const DynamicObstacles& bodies_;
    const FlightModel& flight_;
};

}  // namespace daep::planning
