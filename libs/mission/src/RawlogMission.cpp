#include "daep/mission/RawlogMission.h"

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <Eigen/Eigenvalues>
#include <chrono>
#include <cmath>
#include <exception>
#include <fstream>
#include <iomanip>
#include <optional>
#include <ostream>
#include <sstream>

#include "ComponentParams.h"
#include "MissionSetup.h"
#include "Outputs.h"
#include "RawlogReader.h"
#include "SceneExport.h"
#include "daep/common/Config.h"
#include "daep/common/Error.h"
#include "daep/eval/Statistics.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/PeopleInput.h"
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

/** The [rawlog] section and the rawlog keys of [experiment], validated. */
struct RawlogParams {
    std::string file, world, sensorLabel, poseLabel;
    double planEvery = 1.0;
    Eigen::Vector3d boxMin, boxMax;
};

/** A key whose empty value means "not set". */
std::string optionalString(const ConfigReader& r, const std::string& key) {
    const std::string v = r.config().read_string(r.section(), key, "", false);
    const auto b = v.find_first_not_of(" \t");
    const auto e = v.find_last_not_of(" \t\r");
    return b == std::string::npos ? std::string() : v.substr(b, e - b + 1);
}

Eigen::Vector3d readVector(const ConfigReader& r, const std::string& key,
                           const std::string& source) {
    std::istringstream is(r.requireString(key));
    Eigen::Vector3d v;
    if (!(is >> v.x() >> v.y() >> v.z()) || !(is >> std::ws).eof())
        throw InputError(source + ": [rawlog] " + key + ": expected three numbers \"x y z\"");
    return v;
}

RawlogParams loadRawlogParams(const ExperimentConfig& experiment) {
    const std::string& source = experiment.source();
    const ConfigReader e(experiment.config(), "experiment", source);
    const ConfigReader r(experiment.config(), "rawlog", source);
    RawlogParams p;
    p.file = resolveDataPath(optionalString(e, "rawlog_file"));
    if (p.file.empty())
        throw InputError(source + ": [experiment] rawlog_file: required when source = rawlog");
    p.planEvery = r.requireDouble("plan_every_s");
    if (p.planEvery <= 0)
        throw InputError(source + ": [rawlog] plan_every_s: must be > 0");
    p.world = optionalString(r, "world");
    p.boxMin = readVector(r, "box_min", source);
    p.boxMax = readVector(r, "box_max", source);
    if (p.world.empty() && !(p.boxMin.array() < p.boxMax.array()).all())
        throw InputError(source + ": [rawlog] box_min must be below box_max on every axis");
    p.sensorLabel = optionalString(r, "sensor_label");
    p.poseLabel = r.requireString("pose_label");
    return p;
}

/** Standard deviation (m) along the major axis of a position covariance. */
double majorSigma(const Eigen::Matrix2d& covariance) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(covariance, Eigen::EigenvaluesOnly);
    return std::sqrt(std::max(0.0, eig.eigenvalues().maxCoeff()));
}

/** people.csv: the confirmed tracks after every depth frame. */
class PeopleCsv {
public:
    explicit PeopleCsv(const std::string& path) : path_(path), out_(path) {
        if (!out_)
            throw std::runtime_error("cannot write " + path);
        out_ << "t,track,x,y,vx,vy,sigma\n";
    }

    void write(double t, const std::vector<perception::PersonForecast>& tracks) {
        for (const perception::PersonForecast& f : tracks) {
            const perception::PositionPrediction p = f.at(t);
            out_ << t << ',' << f.id << ',' << p.mean.x() << ',' << p.mean.y() << ','
                 << f.velocity().x() << ',' << f.velocity().y() << ',' << majorSigma(p.covariance)
                 << '\n';
        }
    }

    void flush() {
        out_.flush();
        if (!out_)
            throw std::runtime_error("cannot write " + path_);
    }

private:
    std::string path_;
    std::ofstream out_;
};

RawlogFrame firstFrame(RawlogReader& reader, const RawlogParams& params) {
    RawlogFrame frame;
    if (!reader.next(frame))
        throw InputError(params.file +
                         ": no depth frames (CObservation3DRangeScan with a range image" +
                         (params.sensorLabel.empty() ? "" : ", label " + params.sensorLabel) + ")");
    return frame;
}

std::string planStatus(const planning::Plan& plan) {
    return plan.status == planning::Plan::Status::Finished ? "finished" : "path";
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
    Impl(const ExperimentConfig& config, const std::string& outputDir, std::ostream* logStream)
        : settings(loadSettings(config)),
          params(loadRawlogParams(config)),
          reader(params.file, params.sensorLabel, params.poseLabel),
          frame(firstFrame(reader, params)),
          drone(loadDroneParams(config.config())),
          planner(planning::createPlanner(settings.plannerName, config.config(),
                                          settings.seed * 0x9E3779B97F4A7C15ull + 1)),
          log(logStream),
          recorder(outputDir, eval::PlansFormat::Replay),
          outputs(loadOutputParams(config.config())),
          scene(outputs, outputDir, logStream),
          detector(loadDetectorParams(config.config())),
          tracker(loadTrackerParams(config.config())),
          bodySize(loadPeopleParams(config.config()).bodySize),
          peopleCsv(recorder.path("people.csv")) {
        firstStamp = frame.stamp;
        setUpBox(config);
        map.emplace(loadMapParams(config.config()), box);
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
     * Detects and tracks the people in the current frame (against the map before the frame,
     * which is what they contradict), integrates the frame, then records and plans what is due
     * at its time.
     */
    void handleFrame() {
        t = frame.stamp - firstStamp;
        tracker.update(t, detector.detect(*frame.depth, frame.robot, *map),
                       seenEmptyIn({frame.depth.get(), frame.robot}, bodySize));
        peopleCsv.write(t, tracker.forecasts());
        map->insertObservation(*frame.depth, frame.robot);
        ++frameCount;
        if (frameCount > 1)
            pathLength += (frame.robot.position - lastPose.position).norm();
        lastPose = frame.robot;
        recorder.addPose(t, frame.robot);
        if (trajectory.empty() || (trajectory.back() - frame.robot.position).norm() > 0.05)
            trajectory.push_back(frame.robot.position);
        recordDueSamples();
        if (t + kEps >= nextPlan) {
            planOnce();
            while (nextPlan <= t + kEps)
                nextPlan += params.planEvery;
        }
    }

    void recordDueSamples() {
        while (t + kEps >= nextSample) {
            eval::MetricsSample s;
            s.time = nextSample;
            s.coveragePercent = coveragePercent();
            s.planningTime = planningWall;
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
             << iterations << std::endl;
    }

    planning::PlanningContext context() const {
        planning::PlanningContext ctx;
        ctx.time = t;
        ctx.pose = frame.robot;
        ctx.map = &*map;
        ctx.explorationBox = box;
        ctx.motion.speed = drone.speed;
        ctx.motion.yawRate = drone.yawRate;
        return ctx;
    }

    void planOnce() {
        const planning::PlanningContext ctx = context();
        const auto t0 = Clock::now();
        const planning::Plan plan = planner->plan(ctx);
        eval::ReplayPlanRecord r;
        r.wallSec = secondsSince(t0);
        r.time = t;
        r.pose = ctx.pose;
        r.status = planStatus(plan);
        r.gain = plan.gain;
        r.waypoints = static_cast<int>(plan.waypoints.size());
        if (!plan.waypoints.empty()) {
            r.firstWaypoint = plan.waypoints.front().pose;
            r.safe = planner->keepFlying(ctx, plan, 0) ? 1 : 0;
        }
        if (!plan.tree.empty())
            lastTree = plan.tree;
        ++iterations;
        planningWall += r.wallSec;
        recorder.addReplayPlan(r);
        recorder.flush();
    }

    eval::RunSummary summarize(double wallTime) const {
        std::vector<double> ms;
        for (double s : recorder.chargedPlanTimes())
            ms.push_back(1e3 * s);
        eval::RunSummary s;
        s.coveragePercent = coveragePercent();
        s.explorationTime = t;
        s.pathLength = pathLength;
        s.planningTime = planningWall;
        s.planMsMedian = eval::median(ms);
        s.planMsP95 = eval::percentile(ms, 95);
        s.iterations = iterations;
        s.finished = false;
        s.endReason = endReason;
        s.wallTime = wallTime;
        s.knownVolume = map->knownVolumeInBox();
        s.boxVolume = boxVolume;
        s.labels = {{"source", "rawlog"},
                    {"rawlog", params.file},
                    {"world", worldName},
                    {"planner", settings.plannerName},
                    {"seed", std::to_string(settings.seed)}};
        s.provenance = invocation;
        return s;
    }

    void writeOutputs(const eval::RunSummary& summary) {
        recorder.flush();
        peopleCsv.flush();
        recorder.writeSummary(summary);
        recorder.writeTiming(summary.wallTime, t);
        recorder.writeCollisions();
        if (!map->writeBinary(recorder.path("map.bt")))
            throw std::runtime_error("cannot write " + recorder.path("map.bt"));
        if (!outputs.scene)
            return;
        SceneContent c;
        c.map = &*map;
        c.trajectory = &trajectory;
        c.tree = &lastTree;
        c.drone = lastPose;
        scene.write(c);
    }

    Settings settings;
    RawlogParams params;
    RawlogReader reader;
    RawlogFrame frame;  ///< read before any output exists: a file that is no rawlog leaves none
    sim::DroneParams drone;
    std::unique_ptr<planning::ExplorationPlanner> planner;
    std::ostream* log;
    eval::RunRecorder recorder;
    OutputParams outputs;
    SceneExporter scene;
    perception::PeopleDetector detector;
    perception::PeopleTracker tracker;
    Eigen::Vector3d bodySize;  ///< of the people the detector looks for
    PeopleCsv peopleCsv;
    Aabb box;
    double boxVolume = 0.0;
    std::string worldName;
    std::optional<mapping::ExplorationMap> map;
    std::vector<Eigen::Vector3d> trajectory;
    std::vector<planning::TreeEdge> lastTree;
    FlatPose lastPose;

    double firstStamp = 0.0;
    double t = 0.0;
    double nextPlan = 0.0;
    double nextSample = 0.0;
    double nextProgress = 0.0;
    double pathLength = 0.0;
    double planningWall = 0.0;
    std::size_t frameCount = 0;
    int iterations = 0;
    std::string endReason;
    RunProvenance invocation;
};

RawlogMission::RawlogMission(const ExperimentConfig& config, const std::string& outputDir,
                             std::ostream* log)
    : impl_(std::make_unique<Impl>(config, outputDir, log)) {
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
    std::exception_ptr failure;
    try {
        do {
            m.handleFrame();
        } while (!stopRequested_ && m.reader.next(m.frame));
        m.endReason = stopRequested_ ? "interrupted" : "end of rawlog";
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
