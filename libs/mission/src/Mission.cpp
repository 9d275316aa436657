#include "daep/mission/Mission.h"

#include <mrpt/obs/CObservation3DRangeScan.h>

#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <iomanip>
#include <optional>
#include <ostream>
#include <random>
#include <sstream>

#include <octomap/OcTree.h>

#include "ComponentParams.h"
#include "FrameStep.h"
#include "MemoryLog.h"
#include "MissionSetup.h"
#include "Outputs.h"
#include "PeopleCsv.h"
#include "PlannerDriver.h"
#include "RawlogRecorder.h"
#include "SceneExport.h"
#include "SimulatorSource.h"
#include "StageClock.h"
#include "daep/common/Config.h"
#include "daep/common/ConfigChecks.h"
#include "daep/common/Error.h"
#include "daep/eval/Statistics.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/PeopleInput.h"
#include "daep/planning/Planner.h"
#include "daep/sim/CollisionMonitor.h"
#include "daep/sim/DepthCamera.h"
#include "daep/sim/Drone.h"
#include "daep/world/People.h"
#include "daep/world/RayCaster.h"
#include "daep/world/ReachableVolume.h"
#include "daep/world/WorldSpec.h"

namespace daep::mission {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kEps = 1e-9;

double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

}  // namespace

struct Mission::Impl {
    Impl(const ExperimentConfig& config, const std::string& outputDir, std::ostream* logStream)
        : configForReach(&config.config()),
          settings(loadSettings(config)),
          sim(loadWorld(settings, config.source()), config.config(), settings.start, settings.climb,
              settings.seed, &stages),
          map(loadMapParams(config.config()), sim.world().explorationBox),
          peopleInput(PeopleInputParams::fromConfig(config.config()),
                      settings.seed * 0xD1B54A32D192ED03ull + 7),
          log(logStream),
          recorder(outputDir),
          outputs(loadOutputParams(config.config())),
          scene(outputs, outputDir, logStream),
          memory(recorder.path("memory.csv"), outputs.memoryEvery),
          driver(planning::createPlanner(settings.plannerName, config.config(),
                                         settings.seed * 0x9E3779B97F4A7C15ull + 1),
                 driverSetup()) {
        // People the planner does not keep out of the map enter it as occupied cells.
        map.setPeopleMapped(!sim.world().people.empty() &&
                            !(driver.usesPeople() && peopleInput.excludesFromMap()));
        if (outputs.rawlog)
            rawlog = std::make_unique<RawlogRecorder>(recorder.path("run.rawlog"));
        if (driver.usesPeople() && outputs.peopleCsv)
            peopleCsv = std::make_unique<PeopleCsv>(recorder.path("people.csv"));
        frameStep.emplace(stepParts());
        nextScene = outputs.sceneEvery;
    }

    PlannerDriver::Setup driverSetup() {
        PlannerDriver::Setup d;
        d.map = &map;
        d.explorationBox = sim.world().explorationBox;
        d.motion.speed = sim.drone().params().speed;
        d.motion.yawRate = sim.drone().params().yawRate;
        d.droneSize = sim.drone().params().boxSize;
        d.personSize = sim.people().params().bodySize;
        d.people = &peopleInput;
        d.fixedTime = settings.planningTime == "fixed";
        d.fixedSeconds = settings.planningFixed;
        d.deadlineSeconds = settings.planningDeadline;
        d.recorder = &recorder;
        d.stages = &stages;
        return d;
    }

    FrameStep::Parts stepParts() {
        FrameStep::Parts p;
        p.map = &map;
        p.recorder = &recorder;
        p.stages = &stages;
        if (driver.usesPeople()) {
            p.people = &peopleInput;
            p.peopleOutOfMap = true;
        }
        p.bodySize = sim.people().params().bodySize;
        p.peopleCsv = peopleCsv.get();
        p.rawlog = rawlog.get();
        p.sourceName = sim.name();
        return p;
    }

    /** Known volume over the world's exploration volume (Cafe declares 510 m^3, as the paper). */
    double coveragePercent() const {
        return 100.0 * map.knownVolumeInBox() / sim.world().explorationVolume();
    }

    /** The most coverage this world and start allow, on the map's grid. */
    double reachablePercent() const {
        world::ReachParams p;
        p.resolution = map.resolution();
        p.robotRadius =
            requireNonNegative(ConfigReader(*configForReach, "planning"), "robot_radius");
        p.climb = settings.climb;
        return world::computeReachableVolume(sim.world(), sim.world().starts[settings.start], p)
            .reachablePercent;
    }

    double now() const { return sim.time(); }
    bool exploring() const { return exploreStart >= 0; }
    double explorationTime() const { return exploring() ? now() - exploreStart : 0.0; }
    bool timeUp() const { return exploring() && explorationTime() >= settings.maxTime - kEps; }
    bool stopping() const { return timeUp() || (stopFlag && *stopFlag); }

    /** The frame just taken through the one per-frame step, then the scene when one is due. */
    void processFrame() {
        const CameraSight sight = sim.sight();
        frameStep->process(sim.frame(), &sight);
        if (outputs.scene && outputs.sceneEvery > 0 && now() + kEps >= nextScene) {
            writeScene();
            nextScene += outputs.sceneEvery;
        }
    }

    void writeScene() {
        SceneContent c;
        c.map = &map;
        c.trajectory = &frameStep->trajectory();
        c.tree = &driver.lastTree();
        c.people = sim.people().states();
        c.bodySize = sim.people().params().bodySize;
        c.drone = sim.drone().pose();
        scene.write(c);
    }

    void recordDueSamples() {
        while (exploring() && explorationTime() + kEps >= nextSample) {
            eval::MetricsSample s;
            s.time = nextSample;
            s.coveragePercent = coveragePercent();
            s.pathLength = pathLength;
            s.planningTime = driver.chargedSeconds();
            s.collisions = sim.monitor().personCollisions();
            recorder.addSample(s);
            nextSample += settings.sampleEvery;
            printProgressIfDue(s);
        }
        while (exploring() && memory.due(explorationTime()))
            memory.addDue(map.knownVolumeInBox(), map.octree().size());
    }

    void printProgressIfDue(const eval::MetricsSample& s) {
        if (!log || settings.progressEvery <= 0 || s.time + kEps < nextProgress)
            return;
        nextProgress += settings.progressEvery;
        *log << "[t " << std::fixed << std::setprecision(0) << std::setw(5) << s.time
             << " s] coverage " << std::setprecision(1) << std::setw(5) << s.coveragePercent
             << " %  path " << std::setw(6) << s.pathLength << " m  plans " << std::setw(4)
             << driver.iterations() << "  collisions " << s.collisions << std::endl;
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
                limit = std::min(limit, settings.maxTime - explorationTime());
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
            if (step.frameTaken && !flying && watchingHover && driver.usesPeople()) {
                const auto timed = stages.time(Stage::Checks);
                pendingEvasion = driver.planner().evasion(context(), hoverSafeUntil);
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
            const std::uint64_t mapBefore = map.revision();
            advance(sim.framePeriod(), true);
            const bool recheck = map.revision() != mapBefore || driver.usesPeople();
            if (plan && sim.drone().hasGoal() && recheck) {
                const auto timed = stages.time(Stage::Checks);
                aborted = !driver.planner().keepFlying(context(), *plan, index);
            }
        }
        sim.drone().clearGoal();
        return !aborted;
    }

    void takeOffAndLookAround() {
        sim.takeFirstFrame();
        processFrame();
        FlatPose goal = sim.drone().pose();
        goal.position.z() += settings.climb;
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
        if (person < 0 || !driver.usesPeople())
            return -1;
        const Eigen::Vector2d at = sim.people().states()[static_cast<std::size_t>(person)].position;
        for (const perception::PersonForecast& f : peopleInput.forecasts())
            if ((f.at(now()).mean - at).norm() < sim.people().params().bodySize.x())
                return 1;
        return 0;
    }

    planning::PlanningContext context() const { return driver.context(now(), sim.drone().pose()); }

    /**
     * One plan, made from the state when planning began; the world goes on for the time it
     * takes, with the drone hovering and evading as needed (hoverUntil). nullopt when the plan
     * is stale by the time it is done: the drone evaded meanwhile, or the path is no longer
     * safe against what the frames taken meanwhile predict, its times counted from now.
     */
    std::optional<planning::Plan> planOnce() {
        PlannerDriver::Call made = driver.planFlight(now(), sim.drone().pose(), explorationTime());
        const double framesBefore = sim.nextFrameTime();
        if (hoverUntil(now() + made.chargedSec))
            return std::nullopt;
        const bool newFrames = sim.nextFrameTime() != framesBefore;
        if (newFrames && driver.usesPeople() && !made.plan.waypoints.empty() &&
            !startsSafely(made.plan)) {
            ++stalePlans;
            return std::nullopt;
        }
        return std::move(made.plan);
    }

    bool startsSafely(const planning::Plan& plan) {
        const auto timed = stages.time(Stage::Checks);
        return driver.planner().startsSafely(context(), plan);
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
                if (++failedPlans >= settings.maxFailedPlans) {
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
            recorder.flush();
        }
        endReason = timeUp() ? "time limit" : "interrupted";
    }

    eval::RunSummary summarize(double wallTime) {
        const sim::CollisionMonitor& monitor = sim.monitor();
        for (std::size_t i = 0; i < monitor.events().size(); ++i) {
            const sim::CollisionEvent& e = monitor.events()[i];
            recorder.addCollision(e.personIndex, e.start, e.end, collisionTracked[i]);
        }
        std::vector<double> ms;
        for (double s : recorder.chargedPlanTimes())
            ms.push_back(1e3 * s);
        eval::RunSummary s;
        s.coveragePercent = coveragePercent();
        s.reachablePercent = reachablePercent();
        s.explorationTime = explorationTime();
        s.pathLength = pathLength;
        s.planningTime = driver.chargedSeconds();
        s.planMsMedian = eval::median(ms);
        s.planMsP95 = eval::percentile(ms, 95);
        s.collisions = monitor.personCollisions();
        s.staticCollisions = monitor.staticCollisions();
        s.iterations = driver.iterations();
        s.abortedPaths = abortedPaths;
        s.hoverEvasions = hoverEvasions;
        s.stalePlans = stalePlans;
        s.finished = finished;
        s.endReason = endReason;
        s.wallTime = wallTime;
        s.knownVolume = map.knownVolumeInBox();
        s.boxVolume = sim.world().explorationVolume();
        s.explorationStart = exploreStart;
        s.labels = {{"world", sim.world().name},
                    {"mode", settings.mode},
                    {"planner", settings.plannerName},
                    {"start", std::to_string(settings.start)},
                    {"seed", std::to_string(settings.seed)}};
        s.provenance = invocation;
        return s;
    }

    /** Closes the streams and writes what is written at the end of a run. */
    void writeOutputs(const eval::RunSummary& summary) {
        memory.addFinal(explorationTime(), map.knownVolumeInBox(), map.octree().size());
        recorder.flush();
        if (peopleCsv)
            peopleCsv->flush();
        recorder.writeSummary(summary);
        recorder.writeTiming(summary.wallTime, now(), stages.report(summary.wallTime));
        recorder.writeCollisions();
        if (!map.writeBinary(recorder.path("map.bt")))
            throw std::runtime_error("cannot write " + recorder.path("map.bt"));
        if (rawlog)
            rawlog->close();
        if (outputs.scene)
            writeScene();
        memory.writePlot(recorder.path("memory.png"),
                         "Memory: " + settings.plannerName + ", " + sim.world().name);
    }

    StageClock stages;
    const mrpt::config::CConfigFileBase* configForReach;
    Settings settings;
    SimulatorSource sim;
    mapping::ExplorationMap map;
    PeopleInput peopleInput;
    std::ostream* log;
    eval::RunRecorder recorder;
    OutputParams outputs;
    SceneExporter scene;
    MemoryLog memory;
    PlannerDriver driver;
    std::unique_ptr<RawlogRecorder> rawlog;
    std::unique_ptr<PeopleCsv> peopleCsv;
    std::optional<FrameStep> frameStep;
    std::vector<int> collisionTracked;  ///< per monitor event, see trackedAtCollision
    double nextScene = 0.0;
    const std::atomic<bool>* stopFlag = nullptr;

    double exploreStart = -1.0;
    double nextSample = 0.0;
    double nextProgress = 0.0;
    double pathLength = 0.0;
    int abortedPaths = 0;
    int hoverEvasions = 0;  ///< escapes flown while hovering (planning, waiting)
    int stalePlans = 0;     ///< plans unsafe against the frames taken while they were made
    bool watchingHover = false;
    double hoverSafeUntil = 0.0;  ///< while watchingHover: how long hovering must stay safe
    std::optional<planning::Plan> pendingEvasion;
    bool finished = false;
    std::string endReason;
    RunProvenance invocation;
};

Mission::Mission(const ExperimentConfig& config, const std::string& outputDir, std::ostream* log)
    : impl_(std::make_unique<Impl>(config, outputDir, log)) {
    impl_->stopFlag = &stopRequested_;
    impl_->invocation = config.invocation();
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
