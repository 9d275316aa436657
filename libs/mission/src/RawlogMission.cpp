#include "daep/mission/RawlogMission.h"

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <iomanip>
#include <optional>
#include <ostream>
#include <sstream>
#include <thread>

#include "MissionCore.h"
#include "RawlogParams.h"
#include "SceneExport.h"
#include "daep/common/Config.h"
#include "daep/common/Error.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/RawlogSource.h"

namespace daep::mission {
namespace {

using Clock = std::chrono::steady_clock;

/** Slack of the plan and sample clocks: a frame at a multiple of their period is due then. */
constexpr double kEps = 1e-6;

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
        : params(loadRawlogParams(config, !frames)),
          source(frames ? std::move(frames) : openRawlog(params)),
          frame(firstFrame(*source, params)),
          box(replayBox(config, params, frame.robot)),
          core(config, coreUse(), stages, outputDir, logStream) {
        core.peopleInput.checkSourceCanFeed(frame, false, source->name());
        const auto* fromRawlog = dynamic_cast<const RawlogSource*>(source.get());
        if (fromRawlog && !fromRawlog->lastFrameHadPose() && core.log)
            *core.log << "note: " << source->name()
                      << ": no robot pose with the first depth frame; frames without one are "
                      << "mapped at the identity pose (their sensorPose still applies)"
                      << std::endl;
    }

    /** Recorded data: the people are always tracked, and may be anywhere in the frames. */
    MissionCore::Use coreUse() const {
        MissionCore::Use use;
        use.explorationBox = box.box;
        use.explorationVolume = box.volume;
        use.plans = eval::PlansFormat::Replay;
        use.trackPeopleAlways = true;
        use.framesMayShowPeople = true;
        use.timeSlack = kEps;
        use.sourceName = source->name();
        return use;
    }

    /**
     * The frame through the per-frame step (people, then the map, then the records), then the
     * samples and the plan that are due at its time.
     */
    void handleFrame() {
        t = frame.time;
        if (params.realtime)
            waitForFrameTime();
        core.step.process(frame);
        ++frameCount;
        if (frameCount > 1)
            pathLength += (frame.robot.position - lastPose.position).norm();
        lastPose = frame.robot;
        core.recordDueSamples(t, pathLength, 0, [&] {
            std::ostringstream o;
            o << "  frames " << std::setw(6) << frameCount << "  plans " << std::setw(4)
              << core.driver.iterations();
            return o.str();
        });
        if (t + kEps >= nextPlan) {
            core.driver.planReplay(t, frame.robot);
            while (nextPlan <= t + kEps)
                nextPlan += params.planEvery;
        }
    }

    /** The rawlog's own pace: frame time t is due t after the start (a stop ends the wait). */
    void waitForFrameTime() const {
        const auto due = playStart + std::chrono::duration_cast<Clock::duration>(
                                         std::chrono::duration<double>(t));
        while (Clock::now() < due && !(stopFlag && *stopFlag))
            std::this_thread::sleep_until(
                std::min(due, Clock::now() + std::chrono::milliseconds(100)));
    }

    void noteFramesOutsidePoses() const {
        const auto* fromRawlog = dynamic_cast<const RawlogSource*>(source.get());
        if (fromRawlog && fromRawlog->framesOutsidePoses() > 0 && core.log)
            *core.log << "note: " << params.posesFile << ": " << fromRawlog->framesOutsidePoses()
                      << " depth frames outside its time span were skipped" << std::endl;
    }

    eval::RunSummary summarize(double wallTime) const {
        eval::RunSummary s = core.summary(t, pathLength, wallTime);
        s.finished = false;
        s.endReason = endReason;
        s.labels = {{"source", params.file.empty() ? "frames" : "rawlog"},
                    {"rawlog", source->name()},
                    {"world", box.worldName},
                    {"planner", core.settings.plannerName},
                    {"seed", std::to_string(core.settings.seed)}};
        return s;
    }

    void writeOutputs(const eval::RunSummary& summary) {
        SceneContent scene = core.sceneBase();
        scene.people = tracksAsPeople(t, core.peopleInput.forecasts());
        scene.drone = lastPose;
        core.writeOutputs(summary, t, &scene);
    }

    RawlogParams params;
    std::unique_ptr<FrameSource> source;
    Frame frame;  ///< read before any output exists: a file that is no rawlog leaves none
    ReplayBox box;
    StageClock stages;
    MissionCore core;
    FlatPose lastPose;
    Clock::time_point playStart = Clock::now();
    const std::atomic<bool>* stopFlag = nullptr;

    double t = 0.0;
    double nextPlan = 0.0;
    double pathLength = 0.0;
    std::size_t frameCount = 0;
    eval::EndReason endReason;
};

RawlogMission::RawlogMission(const ExperimentConfig& config, const std::string& outputDir,
                             std::ostream* log)
    : RawlogMission(config, nullptr, outputDir, log) {}

RawlogMission::RawlogMission(const ExperimentConfig& config, std::unique_ptr<FrameSource> frames,
                             const std::string& outputDir, std::ostream* log)
    : impl_(std::make_unique<Impl>(config, std::move(frames), outputDir, log)) {
    impl_->stopFlag = &stopRequested_;
}

RawlogMission::~RawlogMission() = default;

const mapping::ExplorationMap& RawlogMission::map() const {
    return impl_->core.map;
}

std::size_t RawlogMission::frames() const {
    return impl_->frameCount;
}

eval::RunSummary RawlogMission::run() {
    Impl& m = *impl_;
    return runKeepingOutputs(
        [&] {
            m.playStart = std::chrono::steady_clock::now();
            do {
                m.handleFrame();
            } while (!stopRequested_ && m.source->next(m.frame));
            m.noteFramesOutsidePoses();
            using Kind = eval::EndReason::Kind;
            m.endReason = eval::EndReason::of(stopRequested_          ? Kind::Interrupted
                                              : m.params.file.empty() ? Kind::EndOfFrames
                                                                      : Kind::EndOfRawlog);
        },
        m.endReason, [&](double wall) { return m.summarize(wall); },
        [&](const eval::RunSummary& s) { m.writeOutputs(s); });
}

}  // namespace daep::mission
