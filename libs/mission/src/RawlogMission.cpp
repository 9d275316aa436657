#include "daep/mission/RawlogMission.h"

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <chrono>
#include <cmath>
#include <exception>
#include <iomanip>
#include <optional>
#include <ostream>
#include <sstream>
#include <thread>

#include "ComponentParams.h"
#include "FrameStep.h"
#include "MissionSetup.h"
#include "Outputs.h"
#include "PeopleCsv.h"
#include "PlannerDriver.h"
#include "RawlogParams.h"
#include "RawlogRecorder.h"
#include "SceneExport.h"
#include "StageClock.h"
#include "daep/common/Config.h"
#include "daep/common/Error.h"
#include "daep/eval/Statistics.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/PeopleInput.h"
#include "daep/mission/RawlogSource.h"
#include "daep/perception/PeopleDetector.h"
#include "daep/perception/PeopleTracker.h"
#include "daep/planning/Planner.h"

namespace daep::mission {
namespace {

using Clock = std::chrono::steady_clock;

/** Rawlog timestamps are seconds since 1970 as doubles: compare rawlog times with slack. */
constexpr double kEps = 1e-6;

double secondsSince(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

/** The tracks as people for the scene: where each is now, walking as it is predicted to. */
std::vector<world::PersonState> tracksAsPeople(
    double t, const std::vector<perception::PersonForecast>& tracks) {
    std::vector<world::PersonState> out;
    for (const perception::PersonForecast& f : tracks) {
        world::PersonState p;
        p.position = f.at(t).mean;
        p.velocity = f.velocity();
        p.heading = std::atan2(p.velocity.y(), p.velocity.x());
        out.push_back(p);
    }
    return out;
}

}  // namespace

bool RawlogMission::selectedBy(const ExperimentConfig& config) {
    const ConfigReader e(config.config(), "experiment", config.source());
    const std::string source = optionalString(e, "source");
    if (source != "sim" && source != "rawlog")
        throw InputError(config.source() + ": [experiment] source: '" + source +
                         "' is not one of sim, rawlog");
    return source == "rawlog";
}

struct RawlogMission::Impl {
    Impl(const ExperimentConfig& config, std::unique_ptr<FrameSource> frames,
         const std::string& outputDir, std::ostream* logStream)
        : settings(loadSettings(config)),
          params(loadRawlogParams(config, !frames)),
          source(frames ? std::move(frames)
                        : std::make_unique<RawlogSource>(params.file, params.sensorLabel,
                                                         params.poseLabel)),
          frame(firstFrame(*source, params)),
          log(logStream),
          recorder(outputDir, eval::PlansFormat::Replay),
          outputs(loadOutputParams(config.config())),
          scene(outputs, outputDir, logStream),
          peopleInput(PeopleInputParams::fromConfig(config.config()),
                      settings.seed * 0xD1B54A32D192ED03ull + 7),
          bodySize(loadPeopleParams(config.config()).bodySize) {
        peopleInput.checkSourceCanFeed(frame, false, source->name());
        const auto* fromRawlog = dynamic_cast<const RawlogSource*>(source.get());
        if (fromRawlog && !fromRawlog->lastFrameHadPose() && log)
            *log << "note: " << source->name() << ": no robot pose with the first depth frame; "
                 << "frames without one are mapped at the identity pose (their sensorPose "
                 << "still applies)" << std::endl;
        setUpBox(config);
        map.emplace(loadMapParams(config.config()), box);
        driver.emplace(planning::createPlanner(settings.plannerName, config.config(),
                                               settings.seed * 0x9E3779B97F4A7C15ull + 1),
                       driverSetup(config));
        // Recorded data may hold people: those the planner does not keep out enter the map.
        map->setPeopleMapped(!(driver->usesPeople() && peopleInput.excludesFromMap()));
        if (outputs.peopleCsv)
            peopleCsv = std::make_unique<PeopleCsv>(recorder.path("people.csv"));
        if (outputs.rawlog)
            rawlog = std::make_unique<RawlogRecorder>(recorder.path("run.rawlog"));
        frameStep.emplace(stepParts());
    }

    static Frame firstFrame(FrameSource& source, const RawlogParams& params) {
        Frame first;
        if (!source.next(first))
            throw InputError(
                source.name() + ": no depth frames (CObservation3DRangeScan with a range image" +
                (params.sensorLabel.empty() ? "" : ", label " + params.sensorLabel) + ")");
        return first;
    }

    PlannerDriver::Setup driverSetup(const ExperimentConfig& config) {
        const sim::DroneParams drone = loadDroneParams(config.config());
        PlannerDriver::Setup d;
        d.map = &*map;
        d.explorationBox = box;
        d.motion.speed = drone.speed;
        d.motion.yawRate = drone.yawRate;
        d.droneSize = drone.boxSize;
        d.personSize = bodySize;
        d.people = &peopleInput;
        d.fixedTime = settings.planningTime == "fixed";
        d.fixedSeconds = settings.planningFixed;
        d.deadlineSeconds = settings.planningDeadline;
        d.recorder = &recorder;
        d.stages = &stages;
        return d;
    }

    /** Recorded data: the people are always tracked (people.csv), whatever plans on them. */
    FrameStep::Parts stepParts() {
        FrameStep::Parts p;
        p.map = &*map;
        p.recorder = &recorder;
        p.stages = &stages;
        p.people = &peopleInput;
        p.peopleOutOfMap = driver->usesPeople();
        p.bodySize = bodySize;
        p.peopleCsv = peopleCsv.get();
        p.rawlog = rawlog.get();
        p.sourceName = source->name();
        return p;
    }

    void setUpBox(const ExperimentConfig& config) {
        if (params.world.empty()) {
            box.min = frame.robot.position + params.boxMin;
            box.max = frame.robot.position + params.boxMax;
            boxVolume = box.volume();
            worldName = "none";
            return;
        }
        Settings s = settings;  // loadWorld resolves the name like [experiment] world
        s.worldName = params.world;
        s.mode = "static";
        s.start = 0;
        const world::WorldSpec w = loadWorld(s, config.source());
        box = w.explorationBox;
        boxVolume = w.explorationVolume();
        worldName = w.name;
    }

    double coveragePercent() const { return 100.0 * map->knownVolumeInBox() / boxVolume; }

    /**
     * The frame through the per-frame step (people, then the map, then the records), then the
     * samples and the plan that are due at its time.
     */
    void handleFrame() {
        t = frame.time;
        if (params.realtime)  // the rawlog's own pace: frame time t is due t after the start
            std::this_thread::sleep_until(playStart + std::chrono::duration_cast<Clock::duration>(
                                                          std::chrono::duration<double>(t)));
        frameStep->process(frame);
        ++frameCount;
        if (frameCount > 1)
            pathLength += (frame.robot.position - lastPose.position).norm();
        lastPose = frame.robot;
        recordDueSamples();
        if (t + kEps >= nextPlan) {
            driver->planReplay(t, frame.robot);
            while (nextPlan <= t + kEps)
                nextPlan += params.planEvery;
        }
    }

    void recordDueSamples() {
        while (t + kEps >= nextSample) {
            eval::MetricsSample s;
            s.time = nextSample;
            s.coveragePercent = coveragePercent();
            s.planningTime = driver->chargedSeconds();
            s.pathLength = pathLength;
            recorder.addSample(s);
            nextSample += settings.sampleEvery;
            printProgressIfDue(s);
        }
    }

    void printProgressIfDue(const eval::MetricsSample& s) {
        if (!log || settings.progressEvery <= 0 || s.time + kEps < nextProgress)
            return;
        nextProgress += settings.progressEvery;
        *log << "[t " << std::fixed << std::setprecision(0) << std::setw(5) << s.time
             << " s] coverage " << std::setprecision(1) << std::setw(5) << s.coveragePercent
             << " %  frames " << std::setw(6) << frameCount << "  plans " << std::setw(4)
             << driver->iterations() << std::endl;
    }

    eval::RunSummary summarize(double wallTime) const {
        std::vector<double> ms;
        for (double s : recorder.chargedPlanTimes())
            ms.push_back(1e3 * s);
        eval::RunSummary s;
        s.coveragePercent = coveragePercent();
        s.explorationTime = t;
        s.pathLength = pathLength;
        s.planningTime = driver->chargedSeconds();
        s.planMsMedian = eval::median(ms);
        s.planMsP95 = eval::percentile(ms, 95);
        s.iterations = driver->iterations();
        s.finished = false;
        s.endReason = endReason;
        s.wallTime = wallTime;
        s.knownVolume = map->knownVolumeInBox();
        s.boxVolume = boxVolume;
        s.labels = {{"source", params.file.empty() ? "frames" : "rawlog"},
                    {"rawlog", source->name()},
                    {"world", worldName},
                    {"planner", settings.plannerName},
                    {"seed", std::to_string(settings.seed)}};
        s.provenance = invocation;
        return s;
    }

    void writeOutputs(const eval::RunSummary& summary) {
        recorder.flush();
        if (peopleCsv)
            peopleCsv->flush();
        recorder.writeSummary(summary);
        recorder.writeTiming(summary.wallTime, t, stages.report(summary.wallTime));
        recorder.writeCollisions();
        if (!map->writeBinary(recorder.path("map.bt")))
            throw std::runtime_error("cannot write " + recorder.path("map.bt"));
        if (rawlog)
            rawlog->close();
        if (!outputs.scene)
            return;
        SceneContent c;
        c.map = &*map;
        c.trajectory = &frameStep->trajectory();
        c.tree = &driver->lastTree();
        c.people = tracksAsPeople(t, peopleInput.forecasts());
        c.bodySize = bodySize;
        c.drone = lastPose;
        scene.write(c);
    }

    StageClock stages;
    Settings settings;
    RawlogParams params;
    std::unique_ptr<FrameSource> source;
    Frame frame;  ///< read before any output exists: a file that is no rawlog leaves none
    std::ostream* log;
    eval::RunRecorder recorder;
    OutputParams outputs;
    SceneExporter scene;
    PeopleInput peopleInput;
    Eigen::Vector3d bodySize;  ///< of the people the detector looks for
    Aabb box;
    double boxVolume = 0.0;
    std::string worldName;
    std::optional<mapping::ExplorationMap> map;
    std::optional<PlannerDriver> driver;
    std::unique_ptr<PeopleCsv> peopleCsv;
    std::unique_ptr<RawlogRecorder> rawlog;
    std::optional<FrameStep> frameStep;
    FlatPose lastPose;
    Clock::time_point playStart = Clock::now();

    double t = 0.0;
    double nextPlan = 0.0;
    double nextSample = 0.0;
    double nextProgress = 0.0;
    double pathLength = 0.0;
    std::size_t frameCount = 0;
    std::string endReason;
    RunProvenance invocation;
};

RawlogMission::RawlogMission(const ExperimentConfig& config, const std::string& outputDir,
                             std::ostream* log)
    : RawlogMission(config, nullptr, outputDir, log) {}

RawlogMission::RawlogMission(const ExperimentConfig& config, std::unique_ptr<FrameSource> frames,
                             const std::string& outputDir, std::ostream* log)
    : impl_(std::make_unique<Impl>(config, std::move(frames), outputDir, log)) {
    impl_->invocation = config.invocation();
}

RawlogMission::~RawlogMission() = default;

const mapping::ExplorationMap& RawlogMission::map() const {
    return *impl_->map;
}

std::size_t RawlogMission::frames() const {
    return impl_->frameCount;
}

eval::RunSummary RawlogMission::run() {
    Impl& m = *impl_;
    const auto t0 = Clock::now();
    m.playStart = t0;
    std::exception_ptr failure;
    try {
        do {
            m.handleFrame();
        } while (!stopRequested_ && m.source->next(m.frame));
        m.endReason = stopRequested_          ? "interrupted"
                      : m.params.file.empty() ? "end of frames"
                                              : "end of rawlog";
    } catch (const std::exception& e) {
        failure = std::current_exception();  // keep the outputs of the part that ran
        m.endReason = "error: " + errorText(e);
    }
    const eval::RunSummary summary = m.summarize(secondsSince(t0));
    m.writeOutputs(summary);
    if (failure)
        std::rethrow_exception(failure);
    return summary;
}

}  // namespace daep::mission
