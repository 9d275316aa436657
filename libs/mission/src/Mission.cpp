#include "daep/mission/Mission.h"

#include <chrono>
#include <cmath>
#include <exception>
#include <iomanip>
#include <optional>
#include <ostream>
#include <sstream>

#include <octomap/OcTree.h>

#include "MemoryLog.h"
#include "MissionCore.h"
#include "SimulatorSource.h"
#include "daep/common/Config.h"
#include "daep/common/ConfigChecks.h"
#include "daep/common/Error.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/world/ReachableVolume.h"

namespace daep::mission {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kEps = 1e-9;

}  // namespace

struct Mission::Impl {
    Impl(const ExperimentConfig& config, const std::string& outputDir, std::ostream* logStream)
        : configForReach(&config.config()),
          sim(config, &core.stages),  // only its address: the core is built next
          core(config, coreUse(), outputDir, logStream),
          memory(core.recorder.path("memory.csv"), core.outputs.memoryEvery) {
        nextScene = core.outputs.sceneEvery;
    }

    MissionCore::Use coreUse() const {
        MissionCore::Use use;
        use.explorationBox = sim.world().explorationBox;
        use.explorationVolume = sim.world().explorationVolume();
        use.framesMayShowPeople = !sim.world().people.empty();
        use.sourceName = sim.name();
        return use;
    }

    const Settings& settings() const { return core.settings; }

    double now() const { return sim.time(); }
    bool exploring() const { return exploreStart >= 0; }
    double explorationTime() const { return exploring() ? now() - exploreStart : 0.0; }
    bool timeUp() const { return exploring() && explorationTime() >= settings().maxTime - kEps; }
    bool stopping() const { return timeUp() || (stopFlag && *stopFlag); }

    /** The frame just taken through the one per-frame step, then the scene when one is due. */
    void processFrame() {
        const CameraSight sight = sim.sight();
        core.step.process(sim.frame(), &sight);
        if (core.outputs.scene && core.outputs.sceneEvery > 0 && now() + kEps >= nextScene) {
            core.scene.write(sceneContent());
            nextScene += core.outputs.sceneEvery;
        }
    }

    SceneContent sceneContent() const {
        SceneContent c = core.sceneBase();
        c.people = sim.people().states();
        c.drone = sim.drone().pose();
        return c;
    }

    void recordDueSamples() {
        if (!exploring())
            return;
        core.recordDueSamples(explorationTime(), pathLength, sim.monitor().personCollisions(), [&] {
            std::ostringstream o;
            o << std::fixed << std::setprecision(1) << "  path " << std::setw(6) << pathLength
              << " m  plans " << std::setw(4) << core.driver.iterations() << "  collisions "
              << sim.monitor().personCollisions();
            return o.str();
        });
        while (memory.due(explorationTime()))
            memory.addDue(core.map.knownVolumeInBox(), core.map.octree().size());
    }

    /**
     * Advances the world by dt (or until the drone reaches its goal when flying); returns true
     * when the drone reached its goal.
     */
    bool advance(double dt, bool flying) { return advanceUntil(now() + dt, flying); }

    /**
     * Advances the world to `end`, or until the drone reaches its goal when flying (true), or,
     * while hovering with watchingHover, until the planner asks to evade (pendingEvasion).
     */
    bool advanceUntil(double end, bool flying) {
        while (now() < end - kEps && !stopping()) {
            double limit = end - now();
            if (exploring())
                limit = std::min(limit, settings().maxTime - explorationTime());
            const std::size_t episodes = sim.monitor().events().size();
            const SimulatorSource::Step step = sim.step(limit, flying);
            if (flying && exploring())
                pathLength += step.moved;
            for (std::size_t e = episodes; e < sim.monitor().events().size(); ++e)
                collisionTracked.push_back(
                    trackedAtCollision(sim.monitor().events()[e].personIndex));
            if (step.frameTaken)
                processFrame();
            recordDueSamples();
            if (step.reached)
                return true;
            if (step.frameTaken && !flying && watchingHover && core.driver.usesPeople()) {
                const auto timed = core.stages.time(Stage::Checks);
                pendingEvasion = core.driver.planner().evasion(context(), hoverSafeUntil);
                if (pendingEvasion)
                    return false;
            }
        }
        return false;
    }

    /**
     * Hovers until `end` (while the planner plans, or waiting). At every frame a people-aware
     * planner is asked whether hovering here stays safe, and its escape is flown at once when
     * not; hovering then goes on to `end`. Returns whether the drone evaded (it moved).
     */
    bool hoverUntil(double end) {
        // Hovering must stay safe until what is planned meanwhile can act on it: the end of
        // this hover, another as long (a plan dropped as stale), and a frame.
        hoverSafeUntil = end + (end - now()) + sim.framePeriod();
        bool evaded = false;
        while (now() < end - kEps && !stopping()) {
            watchingHover = true;
            advanceUntil(end, false);
            watchingHover = false;
            if (!pendingEvasion)
                break;
            const planning::Plan escape = std::move(*pendingEvasion);
            pendingEvasion.reset();
            evaded = true;
            flyEscape(escape);
        }
        return evaded;
    }

    /** Flies to the goal; returns false when the planner aborted the flight. */
    bool flyTo(const FlatPose& goal, const planning::Plan* plan = nullptr, std::size_t index = 0) {
        sim.drone().setGoal(goal);
        bool aborted = false;
        while (sim.drone().hasGoal() && !stopping() && !aborted) {
            const std::uint64_t mapBefore = core.map.revision();
            advance(sim.framePeriod(), true);
            const bool recheck = core.map.revision() != mapBefore || core.driver.usesPeople();
            if (plan && sim.drone().hasGoal() && recheck) {
                const auto timed = core.stages.time(Stage::Checks);
                aborted = !core.driver.planner().keepFlying(context(), *plan, index);
            }
        }
        sim.drone().clearGoal();
        return !aborted;
    }

    void takeOffAndLookAround() {
        sim.takeFirstFrame();
        processFrame();
        FlatPose goal = sim.drone().pose();
        goal.position.z() += settings().climb;
        flyTo(goal);
        for (int quarter = 1; quarter <= 4; ++quarter) {
            goal.yaw = wrapAngle(quarter * M_PI / 2.0);
            flyTo(goal);
        }
    }

    void flyEscape(const planning::Plan& escape) {
        ++hoverEvasions;
        for (std::size_t i = 0; i < escape.waypoints.size() && !stopping(); ++i)
            flyTo(escape.waypoints[i].pose, &escape, i);
    }

    /** Whether a track lay on the person (within a body's width) as the collision began. */
    int trackedAtCollision(int person) const {
        if (person < 0 || !core.driver.usesPeople())
            return -1;
        const Eigen::Vector2d at = sim.people().states()[static_cast<std::size_t>(person)].position;
        for (const perception::PersonForecast& f : core.peopleInput.forecasts())
            if ((f.at(now()).mean - at).norm() < sim.people().params().bodySize.x())
                return 1;
        return 0;
    }

    planning::PlanningContext context() const {
        return core.driver.context(now(), sim.drone().pose());
    }

    /**
     * One plan, made from the state when planning began; the world goes on for the time it
     * takes, with the drone hovering and evading as needed (hoverUntil). nullopt when the plan
     * is stale by the time it is done: the drone evaded meanwhile, or the path is no longer
     * safe against what the frames taken meanwhile predict, its times counted from now.
     */
    std::optional<planning::Plan> planOnce() {
        PlannerDriver::Call made =
            core.driver.planFlight(now(), sim.drone().pose(), explorationTime());
        const double framesBefore = sim.nextFrameTime();
        if (hoverUntil(now() + made.chargedSec))
            return std::nullopt;
        const bool newFrames = sim.nextFrameTime() != framesBefore;
        if (newFrames && core.driver.usesPeople() && !made.plan.waypoints.empty() &&
            !startsSafely(made.plan)) {
            ++stalePlans;
            return std::nullopt;
        }
        return std::move(made.plan);
    }

    bool startsSafely(const planning::Plan& plan) {
        const auto timed = core.stages.time(Stage::Checks);
        return core.driver.planner().startsSafely(context(), plan);
    }

    void explore() {
        int failedPlans = 0;
        while (!stopping()) {
            const std::optional<planning::Plan> made = planOnce();
            if (!made)
                continue;  // stale by the time it was done: plan again from here
            const planning::Plan& plan = *made;
            if (plan.status == planning::Plan::Status::Finished) {
                finished = true;
                endReason = "planner finished: " + plan.reason;
                return;
            }
            if (plan.waypoints.empty() && plan.waitSeconds > 0) {
                hoverUntil(now() + plan.waitSeconds);  // the planner waits for people to pass
                continue;
            }
            if (plan.waypoints.empty()) {
                if (++failedPlans >= settings().maxFailedPlans) {
                    endReason = "planner returned no path " + std::to_string(failedPlans) +
                                " times in a row";
                    return;
                }
                continue;
            }
            failedPlans = 0;
            for (std::size_t i = 0; i < plan.waypoints.size() && !stopping(); ++i) {
                if (!flyTo(plan.waypoints[i].pose, &plan, i)) {
                    ++abortedPaths;
                    break;
                }
            }
            core.recorder.flush();
        }
        endReason = timeUp() ? "time limit" : "interrupted";
    }

    eval::RunSummary summarize(double wallTime) {
        const sim::CollisionMonitor& monitor = sim.monitor();
        for (std::size_t i = 0; i < monitor.events().size(); ++i) {
            const sim::CollisionEvent& e = monitor.events()[i];
            core.recorder.addCollision(e.personIndex, e.start, e.end, collisionTracked[i]);
        }
        eval::RunSummary s = core.summary(explorationTime(), pathLength, wallTime);
        s.reachablePercent =
            reachablePercent(sim.world(), settings(), *configForReach, core.map.resolution());
        s.collisions = monitor.personCollisions();
        s.staticCollisions = monitor.staticCollisions();
        s.abortedPaths = abortedPaths;
        s.hoverEvasions = hoverEvasions;
        s.stalePlans = stalePlans;
        s.finished = finished;
        s.endReason = endReason;
        s.explorationStart = exploreStart;
        s.labels = {{"world", sim.world().name},
                    {"mode", settings().mode},
                    {"planner", settings().plannerName},
                    {"start", std::to_string(settings().start)},
                    {"seed", std::to_string(settings().seed)}};
        return s;
    }

    void writeOutputs(const eval::RunSummary& summary) {
        memory.addFinal(explorationTime(), core.map.knownVolumeInBox(), core.map.octree().size());
        const SceneContent scene = sceneContent();
        core.writeOutputs(summary, now(), &scene);
        memory.writePlot(core.recorder.path("memory.png"),
                         "Memory: " + settings().plannerName + ", " + sim.world().name);
    }

    const mrpt::config::CConfigFileBase* configForReach;
    SimulatorSource sim;
    MissionCore core;
    MemoryLog memory;
    std::vector<int> collisionTracked;  ///< per monitor event, see trackedAtCollision
    double nextScene = 0.0;
    const std::atomic<bool>* stopFlag = nullptr;

    double exploreStart = -1.0;
    double pathLength = 0.0;
    int abortedPaths = 0;
    int hoverEvasions = 0;  ///< escapes flown while hovering (planning, waiting)
    int stalePlans = 0;     ///< plans unsafe against the frames taken while they were made
    bool watchingHover = false;
    double hoverSafeUntil = 0.0;  ///< while watchingHover: how long hovering must stay safe
    std::optional<planning::Plan> pendingEvasion;
    bool finished = false;
    std::string endReason;
};

Mission::Mission(const ExperimentConfig& config, const std::string& outputDir, std::ostream* log)
    : impl_(std::make_unique<Impl>(config, outputDir, log)) {
    impl_->stopFlag = &stopRequested_;
}

Mission::~Mission() = default;

eval::RunSummary Mission::run() {
    Impl& m = *impl_;
    const auto t0 = Clock::now();
    std::exception_ptr failure;
    try {
        m.takeOffAndLookAround();
        m.exploreStart = m.now();
        m.recordDueSamples();
        if (!stopRequested_)
            m.explore();
    } catch (const std::exception& e) {
        // Keep what the run produced so far: the outputs below are still written.
        failure = std::current_exception();
        m.endReason = "error: " + errorText(e);
    }
    if (m.endReason.empty())
        m.endReason = "interrupted";
    const eval::RunSummary summary = m.summarize(secondsSince(t0));
    m.writeOutputs(summary);
    if (failure)
        std::rethrow_exception(failure);
    return summary;
}

}  // namespace daep::mission
