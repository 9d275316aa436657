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
#include "MemoryLog.h"
#include "MissionSetup.h"
#include "Outputs.h"
#include "RawlogRecorder.h"
#include "SceneExport.h"
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

/** Collision checks must not skip through a person: bound the simulation step. */
constexpr double kMaxStep = 0.05;
constexpr double kEps = 1e-9;

double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

const char* statusName(const planning::Plan& plan) {
    if (plan.status == planning::Plan::Status::Finished)
        return "finished";
    return plan.waypoints.empty() && plan.waitSeconds > 0 ? "wait" : "path";
}

std::string formatPoint(const Eigen::Vector3d& p) {
    std::ostringstream o;
    o << std::fixed << std::setprecision(2) << "(" << p.x() << ", " << p.y() << ", " << p.z()
      << ")";
    return o.str();
}

}  // namespace

struct Mission::Impl {
    Impl(const ExperimentConfig& config, const std::string& outputDir, std::ostream* logStream)
        : configForStart(&config.config()),
          settings(loadSettings(config)),
          world(loadWorld(settings, config.source())),
          people(world.people, loadPeopleParams(config.config())),
          caster(world),
          statics(world),
          camera(loadCameraParams(config.config())),
          drone(loadDroneParams(config.config()), startPose()),
          monitor(drone.params().boxSize, people.params().bodySize, &statics),
          map(loadMapParams(config.config()), world.explorationBox),
          planner(planning::createPlanner(settings.plannerName, config.config(),
                                          settings.seed * 0x9E3779B97F4A7C15ull + 1)),
          noiseRng(settings.seed),
          peopleInput(PeopleInputParams::fromConfig(config.config()),
                      settings.seed * 0xD1B54A32D192ED03ull + 7),
          log(logStream),
          recorder(outputDir),
          outputs(loadOutputParams(config.config())),
          scene(outputs, outputDir, logStream),
          memory(recorder.path("memory.csv"), outputs.memoryEvery) {
        checkStartIsFree();
        // People the planner does not keep out of the map enter it as occupied cells.
        map.setPeopleMapped(!world.people.empty() &&
                            !(planner->usesPeople() && peopleInput.excludesFromMap()));
        framePeriod = 1.0 / camera.params().rateHz;
        if (outputs.rawlog)
            rawlog = std::make_unique<RawlogRecorder>(recorder.path("run.rawlog"));
        nextScene = outputs.sceneEvery;
    }

    /** The drone rests on the start point: its box's bottom face is at the start's z. */
    FlatPose startPose() const {
        FlatPose p;
        p.position = world.starts[settings.start];
        p.position.z() += 0.5 * loadDroneParams(*configForStart).boxSize.z();
        return p;
    }

    void checkStartIsFree() const {
        const Eigen::Vector3d given = world.starts[settings.start];
        const Eigen::Vector3d s = startPose().position;
        const Eigen::Vector3d top = s + Eigen::Vector3d(0, 0, settings.climb);
        const std::string which = world.sourceFile + ": start " + std::to_string(settings.start) +
                                  " " + formatPoint(given);
        for (double f = 0; f <= 1.0 + kEps; f += 0.1) {
            const Eigen::Vector3d p = s + f * (top - s);
            if (statics.overlaps(p, drone.params().boxSize, 0.0))
                throw InputError(which + ": the drone box at " + formatPoint(p) +
                                 " (take-off) is inside static geometry");
        }
        if (!world.explorationBox.contains(top))
            throw InputError(which + ": after the climb the drone is outside the exploration box");
    }

    /** Known volume over the world's exploration volume (Cafe declares 510 m^3, as the paper). */
    double coveragePercent() const {
        return 100.0 * map.knownVolumeInBox() / world.explorationVolume();
    }

    /** The most coverage this world and start allow, on the map's grid. */
    double reachablePercent() const {
        world::ReachParams p;
        p.resolution = map.resolution();
        p.robotRadius =
            requireNonNegative(ConfigReader(*configForStart, "planning"), "robot_radius");
        p.climb = settings.climb;
        return world::computeReachableVolume(world, world.starts[settings.start], p)
            .reachablePercent;
    }

    bool exploring() const { return exploreStart >= 0; }
    double explorationTime() const { return exploring() ? t - exploreStart : 0.0; }
    bool timeUp() const { return exploring() && explorationTime() >= settings.maxTime - kEps; }
    bool stopping() const { return timeUp() || (stopFlag && *stopFlag); }

    void captureFrame() {
        render();
        if (planner->usesPeople()) {
            std::vector<mapping::PersonFootprint> footprints;
            {
                const auto timed = stages.time(Stage::People);
                observePeople();  // before the map takes the frame: the detector needs the old map
                footprints = peopleInput.mapFootprints(t, people.params().bodySize);
            }
            const auto timed = stages.time(Stage::Map);
            map.insertObservation(frame, drone.pose(), footprints);
        } else {
            const auto timed = stages.time(Stage::Map);
            map.insertObservation(frame, drone.pose());
        }
        record();
    }

    void render() {
        const auto timed = stages.time(Stage::Render);
        if (!world.people.empty())
            caster.setPeople(people.states(), people.params().bodySize);
        camera.render(caster, drone.pose(), t, noiseRng, frame);
    }

    void record() {
        const auto timed = stages.time(Stage::Recording);
        recorder.addPose(t, drone.pose());
        if (rawlog)
            rawlog->addFrame(frame, t, drone.pose(), people.states(), people.params().bodySize);
        if (trajectory.empty() || (trajectory.back() - drone.pose().position).norm() > 0.05)
            trajectory.push_back(drone.pose().position);
        if (outputs.scene && outputs.sceneEvery > 0 && t + kEps >= nextScene) {
            writeScene();
            nextScene += outputs.sceneEvery;
        }
    }

    void observePeople() {
        if (peopleInput.detects())
            peopleInput.detect(t, frame, drone.pose(), map, people.params().bodySize);
        else
            peopleInput.observe(t, people.states(), caster, camera.sensorPose(drone.pose()),
                                camera.params(), people.params().bodySize, {&frame, drone.pose()});
    }

    void writeScene() {
        SceneContent c;
        c.map = &map;
        c.trajectory = &trajectory;
        c.tree = &lastTree;
        c.people = people.states();
        c.bodySize = people.params().bodySize;
        c.drone = drone.pose();
        scene.write(c);
    }

    void recordDueSamples() {
        while (exploring() && explorationTime() + kEps >= nextSample) {
            eval::MetricsSample s;
            s.time = nextSample;
            s.coveragePercent = coveragePercent();
            s.pathLength = pathLength;
            s.planningTime = planningCharged;
            s.collisions = monitor.personCollisions();
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
             << iterations << "  collisions " << s.collisions << std::endl;
    }

    /**
     * Advances the world by dt (or until the drone reaches its goal when flying); returns true
     * when the drone reached its goal.
     */
    bool advance(double dt, bool flying) { return advanceUntil(t + dt, flying); }

    /**
     * Advances the world to `end`, or until the drone reaches its goal when flying (true), or,
     * while hovering with watchingHover, until the planner asks to evade (pendingEvasion).
     */
    bool advanceUntil(double end, bool flying) {
        while (t < end - kEps && !stopping()) {
            double h = std::min({end - t, nextFrame - t, kMaxStep});
            if (exploring())
                h = std::min(h, settings.maxTime - explorationTime());
            h = std::max(h, 0.0);
            bool reached = false;
            std::optional<StageClock::Scope> worldTime(std::in_place, stages, Stage::World);
            if (flying) {
                const Eigen::Vector3d before = drone.pose().position;
                const double used = drone.advance(h);
                reached = !drone.hasGoal();
                h = used;
                if (exploring())
                    pathLength += (drone.pose().position - before).norm();
            }
            people.advance(h);
            t += h;
            const std::size_t episodes = monitor.events().size();
            monitor.update(t, drone.pose(), people.states());
            for (std::size_t e = episodes; e < monitor.events().size(); ++e)
                collisionTracked.push_back(trackedAtCollision(monitor.events()[e].personIndex));
            worldTime.reset();
            bool captured = false;
            if (t >= nextFrame - kEps) {
                captureFrame();
                nextFrame += framePeriod;
                captured = true;
            }
            recordDueSamples();
            if (reached)
                return true;
            if (captured && !flying && watchingHover && planner->usesPeople()) {
                const auto timed = stages.time(Stage::Checks);
                pendingEvasion = planner->evasion(context(), hoverSafeUntil);
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
        hoverSafeUntil = end + (end - t) + framePeriod;
        bool evaded = false;
        while (t < end - kEps && !stopping()) {
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
        drone.setGoal(goal);
        bool aborted = false;
        while (drone.hasGoal() && !stopping() && !aborted) {
            const std::uint64_t mapBefore = map.revision();
            advance(framePeriod, true);
            const bool recheck = map.revision() != mapBefore || planner->usesPeople();
            if (plan && drone.hasGoal() && recheck) {
                const auto timed = stages.time(Stage::Checks);
                aborted = !planner->keepFlying(context(), *plan, index);
            }
        }
        drone.clearGoal();
        return !aborted;
    }

    void takeOffAndLookAround() {
        captureFrame();
        nextFrame = framePeriod;
        FlatPose goal = drone.pose();
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
        if (person < 0 || !planner->usesPeople())
            return -1;
        const Eigen::Vector2d at = people.states()[static_cast<std::size_t>(person)].position;
        for (const perception::PersonForecast& f : peopleInput.forecasts())
            if ((f.at(t).mean - at).norm() < people.params().bodySize.x())
                return 1;
        return 0;
    }

    planning::PlanningContext context() const {
        planning::PlanningContext ctx;
        ctx.time = t;
        ctx.pose = drone.pose();
        ctx.map = &map;
        ctx.explorationBox = world.explorationBox;
        ctx.motion.speed = drone.params().speed;
        ctx.motion.yawRate = drone.params().yawRate;
        ctx.droneSize = drone.params().boxSize;
        ctx.personSize = people.params().bodySize;
        if (planner->usesPeople()) {
            ctx.people = &peopleInput.forecasts();
            ctx.peopleFromCamera = peopleInput.fromCamera();
        }
        return ctx;
    }

    /**
     * One plan, made from the state when planning began; the world goes on for the time it
     * takes, with the drone hovering and evading as needed (hoverUntil). nullopt when the plan
     * is stale by the time it is done: the drone evaded meanwhile, or the path is no longer
     * safe against what the frames taken meanwhile predict, its times counted from now.
     */
    std::optional<planning::Plan> planOnce() {
        planning::PlanningContext ctx = context();
        const auto t0 = Clock::now();
        if (settings.planningTime == "measured")  // wall time: never where runs must repeat
            ctx.deadline = planning::PlanningDeadline::in(settings.planningDeadline);
        planning::Plan plan = [&] {
            const auto timed = stages.time(Stage::Planning);
            return planner->plan(ctx);
        }();
        const double wall = secondsSince(t0);
        if (!plan.tree.empty())
            lastTree = plan.tree;
        const double charged = settings.planningTime == "fixed" ? settings.planningFixed : wall;
        ++iterations;
        planningCharged += charged;
        recorder.addPlan(explorationTime(), charged, wall, statusName(plan), plan.gain,
                         static_cast<int>(plan.waypoints.size()), plan.reason);
        const double framesBefore = nextFrame;
        if (hoverUntil(t + charged))
            return std::nullopt;
        const bool newFrames = nextFrame != framesBefore;
        if (newFrames && planner->usesPeople() && !plan.waypoints.empty() && !startsSafely(plan)) {
            ++stalePlans;
            return std::nullopt;
        }
        return plan;
    }

    bool startsSafely(const planning::Plan& plan) {
        const auto timed = stages.time(Stage::Checks);
        return planner->startsSafely(context(), plan);
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
                hoverUntil(t + plan.waitSeconds);  // the planner waits for people to pass
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
        s.planningTime = planningCharged;
        s.planMsMedian = eval::median(ms);
        s.planMsP95 = eval::percentile(ms, 95);
        s.collisions = monitor.personCollisions();
        s.staticCollisions = monitor.staticCollisions();
        s.iterations = iterations;
        s.abortedPaths = abortedPaths;
        s.hoverEvasions = hoverEvasions;
        s.stalePlans = stalePlans;
        s.finished = finished;
        s.endReason = endReason;
        s.wallTime = wallTime;
        s.knownVolume = map.knownVolumeInBox();
        s.boxVolume = world.explorationVolume();
        s.explorationStart = exploreStart;
        s.labels = {{"world", world.name},
                    {"mode", settings.mode},
                    {"planner", settings.plannerName},
                    {"start", std::to_string(settings.start)},
                    {"seed", std::to_string(settings.seed)}};
        s.provenance = invocation;
        return s;
    }

    const mrpt::config::CConfigFileBase* configForStart;
    Settings settings;
    world::WorldSpec world;
    world::PeopleSimulator people;
    world::RayCaster caster;
    world::StaticCollisionChecker statics;
    sim::DepthCamera camera;
    sim::Drone drone;
    sim::CollisionMonitor monitor;
    mapping::ExplorationMap map;
    std::unique_ptr<planning::ExplorationPlanner> planner;
    std::mt19937_64 noiseRng;
    PeopleInput peopleInput;
    std::ostream* log;
    eval::RunRecorder recorder;
    mrpt::obs::CObservation3DRangeScan frame;
    OutputParams outputs;
    SceneExporter scene;
    MemoryLog memory;
    std::unique_ptr<RawlogRecorder> rawlog;
    std::vector<Eigen::Vector3d> trajectory;  ///< flown path, for the scene
    std::vector<int> collisionTracked;        ///< per monitor event, see trackedAtCollision
    std::vector<planning::TreeEdge> lastTree;
    double nextScene = 0.0;
    const std::atomic<bool>* stopFlag = nullptr;

    double t = 0.0;
    double framePeriod = 0.1;
    double nextFrame = 0.0;
    double exploreStart = -1.0;
    double nextSample = 0.0;
    double nextProgress = 0.0;
    double pathLength = 0.0;
    double planningCharged = 0.0;
    int iterations = 0;
    int abortedPaths = 0;
    int hoverEvasions = 0;  ///< escapes flown while hovering (planning, waiting)
    int stalePlans = 0;     ///< plans unsafe against the frames taken while they were made
    bool watchingHover = false;
    StageClock stages;
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
        m.exploreStart = m.t;
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
    m.memory.addFinal(m.explorationTime(), m.map.knownVolumeInBox(), m.map.octree().size());
    m.recorder.flush();
    m.recorder.writeSummary(summary);
    m.recorder.writeTiming(summary.wallTime, m.t, m.stages.report(summary.wallTime));
    m.recorder.writeCollisions();
    if (!m.map.writeBinary(m.recorder.path("map.bt")))
        throw std::runtime_error("cannot write " + m.recorder.path("map.bt"));
    if (m.rawlog)
        m.rawlog->close();
    if (m.outputs.scene)
        m.writeScene();
    m.memory.writePlot(m.recorder.path("memory.png"),
                       "Memory: " + m.settings.plannerName + ", " + m.world.name);
    if (failure)
        std::rethrow_exception(failure);
    return summary;
}

}  // namespace daep::mission
