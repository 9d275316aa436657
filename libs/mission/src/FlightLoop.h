#pragma once

#include <cstddef>
#include <optional>

#include "MissionCore.h"
#include "SimulatorSource.h"

namespace daep::mission {

/**
 * The simulated drone's closed loop between plans, frame by frame: flying a plan with the
 * planner's re-check after every map update (or every frame, for planners that use people),
 * and hovering (while a plan is made, or waiting) with the safety watch: at every frame a
 * people-aware planner says whether hovering there stays safe, and its escape is flown at once
 * when not. Every frame goes through the mission's per-frame step.
 */
class FlightLoop {
public:
    /** What the mission around the loop decides and records. */
    class Mission {
    public:
        virtual ~Mission() = default;
        virtual bool stopping() const = 0;
        /** The longest step allowed towards `end` (the mission may end sooner). */
        virtual double stepLimit(double end) const = 0;
        /** After every step, before its frame (if any) goes through the per-frame step. */
        virtual void stepped(const SimulatorSource::Step& step, bool flying) = 0;
        /** After the frame of a step, if any: the records due by now. */
        virtual void recordDue() = 0;
        /** After a frame has gone through the per-frame step. */
        virtual void frameProcessed() = 0;
    };

    FlightLoop(SimulatorSource& sim, MissionCore& core, Mission& mission)
        : sim_(sim), core_(core), mission_(mission) {}

    /** The first frame, the climb, and a full turn on the spot in quarters. */
    void takeOffAndLookAround(double climb);

    /**
     * One plan, made from the state when planning began; the world goes on for the time it
     * takes, with the drone hovering and evading as needed. nullopt when the plan is stale by
     * the time it is done: the drone evaded meanwhile, or the path is no longer safe against
     * what the frames taken meanwhile predict, its times counted from now.
     */
    std::optional<planning::Plan> planOnce(double recordTime);

    /** Hovers until `end`, watching; returns whether the drone evaded (it moved). */
    bool hoverUntil(double end);

    /** Flies a path; returns false when the planner aborted it (the drone stops there). */
    bool fly(const planning::Plan& plan);

    planning::PlanningContext context() const {
        return core_.driver.context(sim_.time(), sim_.drone().pose());
    }

    int hoverEvasions() const { return hoverEvasions_; }
    int stalePlans() const { return stalePlans_; }

private:
    bool advanceUntil(double end, bool flying);
    bool flyTo(const FlatPose& goal, const planning::Plan* plan = nullptr, std::size_t index = 0);
    void flyEscape(planning::Plan escape);
    void processFrame();

    SimulatorSource& sim_;
    MissionCore& core_;
    Mission& mission_;
    bool watchingHover_ = false;
    double hoverSafeUntil_ = 0.0;  ///< while watching: how long hovering must stay safe
    std::optional<planning::Plan> pendingEvasion_;
    int hoverEvasions_ = 0;  ///< escapes flown while hovering (planning, waiting)
    int stalePlans_ = 0;     ///< plans unsafe against the frames taken while they were made
};

}  // namespace daep::mission
