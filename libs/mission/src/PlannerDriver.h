#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "daep/common/Types.h"
#include "daep/planning/Planner.h"

namespace daep::eval {
class RunRecorder;
}

namespace daep::mission {

class PeopleInput;
class StageClock;

/**
 * The one planner driver of every mission, simulated or recorded: the context a plan is made
 * in (with the tracked people, for planners that use them), the plan call with its deadline,
 * the time it is charged, and its line in plans.csv.
 */
class PlannerDriver {
public:
    struct Setup {
        const mapping::ExplorationMap* map = nullptr;
        Aabb explorationBox;
        planning::MotionLimits motion;
        Eigen::Vector3d droneSize{0.4, 0.4, 0.1};
        Eigen::Vector3d personSize{1.0, 1.0, 1.8};
        /** Tracked people; given to the planner only if it usesPeople(). */
        const PeopleInput* people = nullptr;
        /** [experiment] planning_time = fixed: each call is charged this; else its wall time. */
        bool fixedTime = true;
        double fixedSeconds = 0.0;
        double deadlineSeconds = 0.0;  ///< with measured time: the call's wall-clock deadline
        eval::RunRecorder* recorder = nullptr;
        StageClock* stages = nullptr;
    };

    /** What one call gave, and what it cost. */
    struct Call {
        planning::Plan plan;
        double wallSec = 0.0;
        double chargedSec = 0.0;
    };

    PlannerDriver(std::unique_ptr<planning::ExplorationPlanner> planner, const Setup& setup);

    planning::ExplorationPlanner& planner() { return *planner_; }
    const planning::ExplorationPlanner& planner() const { return *planner_; }
    bool usesPeople() const { return usesPeople_; }

    /** What the planner may look at, at time t from `pose`. */
    planning::PlanningContext context(double t, const FlatPose& pose) const;

    /**
     * One plan of a flight from `pose` at t: charged to the clock and written to plans.csv
     * (PlansFormat::Flight) at `recordTime` (the exploration time).
     */
    Call planFlight(double t, const FlatPose& pose, double recordTime);

    /**
     * One plan on recorded data (PlansFormat::Replay): nothing is flown, so plans.csv says
     * whether the plan would be safe to start from `pose` (keepFlying: the map, and the
     * tracked people for planners that use them); its wall time is what it costs.
     */
    Call planReplay(double t, const FlatPose& pose);

    int iterations() const { return iterations_; }
    double chargedSeconds() const { return charged_; }
    /** The tree of the last plan that had one, for the scene. */
    const std::vector<planning::TreeEdge>& lastTree() const { return lastTree_; }

private:
    Call call(const planning::PlanningContext& context);

    std::unique_ptr<planning::ExplorationPlanner> planner_;
    Setup setup_;
    bool usesPeople_ = false;
    int iterations_ = 0;
    double charged_ = 0.0;
    std::vector<planning::TreeEdge> lastTree_;
};

}  // namespace daep::mission
