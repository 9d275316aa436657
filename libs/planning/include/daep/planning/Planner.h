#pragma once

#include <Eigen/Core>
#include <chrono>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "daep/common/Types.h"

namespace mrpt::config {
class CConfigFileBase;
}
namespace daep::mapping {
class ExplorationMap;
}
namespace daep::perception {
struct PersonForecast;
}

namespace daep::planning {

/** How the drone moves between waypoints: turn on the spot to the yaw, then fly straight. */
struct MotionLimits {
    double speed = 0.5;    ///< m/s
    double yawRate = 1.0;  ///< rad/s

    /** Turn time + flight time from a to b. */
    double travelTime(const FlatPose& a, const FlatPose& b) const;
};

struct Waypoint {
    FlatPose pose;
    double arrivalTime = 0.0;  ///< absolute simulated time the drone is expected to reach it
};

/** An edge of a planning tree, kept for display and debugging. */
struct TreeEdge {
    Eigen::Vector3d from;
    Eigen::Vector3d to;
};

struct Plan {
    enum class Status {
        Path,      ///< fly `waypoints` (at least one) in order, then plan again
        Wait,      ///< hover `waitSeconds` (> 0), then plan again (people to pass, a retry)
        NoPath,    ///< nothing to fly now: plan again at once (max_failed_plans in a row end)
        Finished,  ///< the planner considers the exploration complete
    };
    Status status = Status::Finished;
    std::vector<Waypoint> waypoints;  ///< empty unless the status is Path
    double waitSeconds = 0.0;         ///< how long a Wait hovers
    /**
     * An escape from a person: the best move there is. Flown on while it stays the best; a
     * planner's keepFlying drops it only for a fresh escape that is clearly better.
     */
    bool escape = false;
    double gain = 0.0;   ///< gain of the chosen goal (m^3 of unknown volume)
    double score = 0.0;  ///< planner-specific value of the chosen branch
    std::string reason;  ///< short human-readable note (why finished, local/global, ...)
    std::vector<TreeEdge> tree;

    /** Keeps the first n waypoints; a path cut to none becomes NoPath. */
    void cutTo(std::size_t n);
    /** Hover `seconds` before planning again: Wait, or NoPath when that is no time at all. */
    void waitFor(double seconds);
    /** Whether the status agrees with the waypoints and the wait (see Status). */
    bool wellFormed() const;
};

/** The status as plans.csv writes it: path, wait, no_path, finished. */
const char* statusName(Plan::Status status);

/**
 * When a plan call must return (anytime planning): trees stop growing once it has passed and
 * the planner hands out the best it has, or no path. Wall-clock time, so runs that must be
 * reproducible (planning_time = fixed) leave it unset: it never passes.
 */
struct PlanningDeadline {
    using Clock = std::chrono::steady_clock;
    Clock::time_point at = Clock::time_point::max();

    static PlanningDeadline in(double seconds) {
        return {Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                   std::chrono::duration<double>(seconds))};
    }
    bool passed() const { return at != Clock::time_point::max() && Clock::now() >= at; }
};

/** What a planner may look at when it plans. */
struct PlanningContext {
    double time = 0.0;  ///< simulated time now
    FlatPose pose;      ///< current drone pose
    const mapping::ExplorationMap* map = nullptr;
    Aabb explorationBox;
    MotionLimits motion;
    /** People as tracked now (planners that usePeople()); null when there are none. */
    const std::vector<perception::PersonForecast>* people = nullptr;
    /** The people come from the drone's own camera: nobody is known where it does not look. */
    bool peopleFromCamera = false;
    /** How far (m) the camera finds people (peopleFromCamera): nobody farther is seen. */
    double peopleRange = std::numeric_limits<double>::infinity();
    Eigen::Vector3d droneSize{0.4, 0.4, 0.1};
    Eigen::Vector3d personSize{1.0, 1.0, 1.8};
    PlanningDeadline deadline;
};

/** What a planner's watch over the people its camera has not seen holds at a place. */
enum class UnseenWatch {
    None,       ///< the planner keeps no such watch (other planners; people from ground truth)
    Open,       ///< a walkway someone unseen may be on by now
    Cleared,    ///< a walkway the camera swept that nobody unseen can have reached yet
    NoWalkway,  ///< a place where the watch expects nobody unseen
    Lost,       ///< off the walkways, where a person the camera lost may have walked by now
};

/** The name collisions.csv gives it: "-", "open", "cleared", "no_walkway" or "lost". */
const char* unseenWatchName(UnseenWatch watch);

/** One interface for RH-NBVP, AEP, DEP and DAEP. */
class ExplorationPlanner {
public:
    virtual ~ExplorationPlanner() = default;
    virtual std::string name() const = 0;
    /** Plans from the context's state. Deterministic for a given seed and input sequence. */
    virtual Plan plan(const PlanningContext& context) = 0;

    /**
     * Whether the planner looks at people (context.people). The mission then tracks them and
     * asks keepFlying at every camera frame, not only when the map changed.
     */
    virtual bool usesPeople() const { return false; }

    /**
     * Asked while `plan` is flown, after every map update, with the index of the waypoint the
     * drone is flying to. Returning false makes the mission stop the drone where it is and
     * call plan() again (re-planning when the path became unsafe). Default: keep flying.
     */
    virtual bool keepFlying(const PlanningContext& context, const Plan& plan,
                            std::size_t nextWaypoint) {
        (void)context;
        (void)plan;
        (void)nextWaypoint;
        return true;
    }

    /**
     * Asked at every camera frame while the drone hovers (planning, waiting) for planners that
     * usePeople(): the escape to fly at once when hovering where the drone is would not stay
     * clear of the predicted people until `until` (the planner may cap it), whatever plan is
     * being made; nullopt while hovering is safe (and then nothing in the planner changes).
     * Default: nullopt.
     */
    virtual std::optional<Plan> evasion(const PlanningContext& context, double until) {
        (void)context;
        (void)until;
        return std::nullopt;
    }

    /**
     * Whether a plan made from an earlier context can still be started now: its moves, timed
     * from context.time, clear of the context's people. Asked (for planners that usePeople())
     * when frames came in while the plan was made; changes nothing in the planner. Default:
     * true.
     */
    virtual bool startsSafely(const PlanningContext& context, const Plan& plan) const {
        (void)context;
        (void)plan;
        return true;
    }

    /**
     * What the planner's watch over unseen people held at xy (x, y) at `time`, as of the last
     * context it was given: why a walker it did not track could, or could not, be there.
     * Changes nothing in the planner. Default: UnseenWatch::None.
     */
    virtual UnseenWatch unseenWatchAt(const Eigen::Vector2d& xy, double time) const {
        (void)xy;
        (void)time;
        return UnseenWatch::None;
    }
};

}  // namespace daep::planning
