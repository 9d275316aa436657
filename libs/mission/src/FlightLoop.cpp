#include "FlightLoop.h"

#include <cmath>

namespace daep::mission {
namespace {

constexpr double kEps = 1e-9;

}  // namespace

void FlightLoop::processFrame() {
    const CameraSight sight = sim_.sight();
    core_.step.process(sim_.frame(), &sight);
    mission_.frameProcessed();
}

/**
 * Advances the world to `end`, or until the drone reaches its goal when flying (true), or,
 * while watching the hover, until the planner asks to evade (pendingEvasion_).
 */
bool FlightLoop::advanceUntil(double end, bool flying) {
    while (sim_.time() < end - kEps && !mission_.stopping()) {
        const SimulatorSource::Step step = sim_.step(mission_.stepLimit(end), flying);
        mission_.stepped(step, flying);
        if (step.frameTaken)
            processFrame();
        mission_.recordDue();
        if (step.reached)
            return true;
        if (step.frameTaken && !flying && watchingHover_ && core_.driver.usesPeople()) {
            const auto timed = core_.stages.time(Stage::Checks);
            pendingEvasion_ = core_.driver.planner().evasion(context(), hoverSafeUntil_);
            if (pendingEvasion_)
                return false;
        }
    }
    return false;
}

bool FlightLoop::hoverUntil(double end) {
    // Hovering must stay safe until what is planned meanwhile can act on it: the end of this
    // hover, another as long (a plan dropped as stale), and a frame.
    hoverSafeUntil_ = end + (end - sim_.time()) + sim_.framePeriod();
    bool evaded = false;
    while (sim_.time() < end - kEps && !mission_.stopping()) {
        watchingHover_ = true;
        advanceUntil(end, false);
        watchingHover_ = false;
        if (!pendingEvasion_)
            break;
        planning::Plan escape = std::move(*pendingEvasion_);
        pendingEvasion_.reset();
        evaded = true;
        flyEscape(std::move(escape));
    }
    return evaded;
}

bool FlightLoop::flyTo(const FlatPose& goal, const planning::Plan* plan, std::size_t index) {
    sim_.drone().setGoal(goal);
    bool aborted = false;
    while (sim_.drone().hasGoal() && !mission_.stopping() && !aborted) {
        const std::uint64_t mapBefore = core_.map.revision();
        advanceUntil(sim_.time() + sim_.framePeriod(), true);
        const bool recheck = core_.map.revision() != mapBefore || core_.driver.usesPeople();
        if (plan && sim_.drone().hasGoal() && recheck) {
            const auto timed = core_.stages.time(Stage::Checks);
            aborted = !core_.driver.planner().keepFlying(context(), *plan, index);
        }
    }
    sim_.drone().clearGoal();
    return !aborted;
}

bool FlightLoop::fly(const planning::Plan& plan) {
    for (std::size_t i = 0; i < plan.waypoints.size() && !mission_.stopping(); ++i)
        if (!flyTo(plan.waypoints[i].pose, &plan, i))
            return false;
    return true;
}

void FlightLoop::takeOffAndLookAround(double climb) {
    sim_.takeFirstFrame();
    processFrame();
    FlatPose goal = sim_.drone().pose();
    goal.position.z() += climb;
    flyTo(goal);
    for (int quarter = 1; quarter <= 4; ++quarter) {
        goal.yaw = wrapAngle(quarter * M_PI / 2.0);
        flyTo(goal);
    }
}

void FlightLoop::flyEscape(planning::Plan escape) {
    for (;;) {
        ++hoverEvasions_;
        if (fly(escape) || mission_.stopping())
            return;
        // Dropped for a better escape from here (or the map closed it): take the fresh one.
        std::optional<planning::Plan> fresh =
            core_.driver.planner().evasion(context(), hoverSafeUntil_);
        if (!fresh)
            return;
        escape = std::move(*fresh);
    }
}

std::optional<planning::Plan> FlightLoop::planOnce(double recordTime) {
    PlannerDriver::Call made =
        core_.driver.planFlight(sim_.time(), sim_.drone().pose(), recordTime);
    const double framesBefore = sim_.nextFrameTime();
    if (hoverUntil(sim_.time() + made.chargedSec))
        return std::nullopt;
    const bool newFrames = sim_.nextFrameTime() != framesBefore;
    if (newFrames && core_.driver.usesPeople() &&
        made.plan.status == planning::Plan::Status::Path) {
        const auto timed = core_.stages.time(Stage::Checks);
        if (!core_.driver.planner().startsSafely(context(), made.plan)) {
            ++stalePlans_;
            return std::nullopt;
        }
    }
    return std::move(made.plan);
}

}  // namespace daep::mission
