#pragma once

#include <Eigen/Core>
#include <chrono>
#include <exception>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>

#include "FrameStep.h"
#include "MissionSetup.h"
#include "Outputs.h"
#include "PeopleCsv.h"
#include "PlannerDriver.h"
#include "RawlogRecorder.h"
#include "SceneExport.h"
#include "StageClock.h"
#include "daep/common/Error.h"
#include "daep/eval/RunRecorder.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/PeopleInput.h"

namespace daep::mission {

class ExperimentConfig;

/**
 * Runs a mission's loop and writes its outputs whatever happens: an error ends the loop with
 * end reason "error: ...", the outputs of the part that ran are written, then it is rethrown.
 * `summarize(wallSeconds)` gives the summary that `write(summary)` writes.
 */
template <typename Loop, typename Summarize, typename Write>
eval::RunSummary runKeepingOutputs(Loop&& loop, eval::EndReason& endReason, Summarize&& summarize,
                                   Write&& write) {
    const auto t0 = std::chrono::steady_clock::now();
    std::exception_ptr failure;
    try {
        loop();
    } catch (const std::exception& e) {
        failure = std::current_exception();
        endReason = eval::EndReason::error(errorText(e));
    }
    const eval::RunSummary summary = summarize(secondsSince(t0));
    write(summary);
    if (failure)
        std::rethrow_exception(failure);
    return summary;
}

/**
 * What every mission has, whatever its frames come from (the simulator, closed loop; a rawlog
 * or another open-loop source): the map, the people input, the planner driver, the per-frame
 * step, the records and the outputs written at the end. Built from the experiment's config.
 */
struct MissionCore {
    /** How a mission uses its people and its clock. */
    struct Use {
        Aabb explorationBox;
        double explorationVolume = 0.0;  ///< coverage's denominator (a world may declare it)
        eval::PlansFormat plans = eval::PlansFormat::Flight;
        /** Tracked even when the planner does not use them (recorded data: what it shows). */
        bool trackPeopleAlways = false;
        /** The frames may show people (a dynamic world, recorded data). */
        bool framesMayShowPeople = true;
        /** Slack (s) of the sample and progress clocks. */
        double timeSlack = 1e-9;
        std::string sourceName;
    };

    /** `stages` (the mission's, shared with its frame source) must outlive the core. */
    MissionCore(const ExperimentConfig& config, const Use& use, StageClock& stages,
                const std::string& outputDir, std::ostream* log);

    /** timeseries.csv rows due by `time`, and the progress line (`progress` adds its figures). */
    template <typename Progress>
    void recordDueSamples(double time, double pathLength, int collisions, Progress&& progress) {
        while (time + use.timeSlack >= nextSample) {
            eval::MetricsSample s;
            s.time = nextSample;
            s.coveragePercent = coveragePercent();
            s.pathLength = pathLength;
            s.planningTime = driver.chargedSeconds();
            s.collisions = collisions;
            recorder.addSample(s);
            nextSample += settings.sampleEvery;
            if (log && settings.progressEvery > 0 && s.time + use.timeSlack >= nextProgress) {
                nextProgress += settings.progressEvery;
                printProgress(s, progress());
            }
        }
    }

    /** Known volume over the box's (or the world's declared) volume. */
    double coveragePercent() const {
        return 100.0 * map.knownVolumeInBox() / use.explorationVolume;
    }

    /** The figures every mission reports; the caller adds its own. */
    eval::RunSummary summary(double explorationTime, double pathLength, double wallTime) const;

    /** Closes the streams and writes summary.json, timing.json, collisions.csv, map.bt, scene. */
    void writeOutputs(const eval::RunSummary& summary, double simTime,
                      const SceneContent* sceneContent);

    /** The scene's map, trajectory and tree; the caller adds people and the drone. */
    SceneContent sceneBase() const;

    StageClock& stages;
    Settings settings;
    Use use;
    std::ostream* log;
    eval::RunRecorder recorder;
    OutputParams outputs;
    SceneExporter scene;
    mapping::ExplorationMap map;
    PeopleInput peopleInput;
    Eigen::Vector3d bodySize;
    PlannerDriver driver;
    std::unique_ptr<PeopleCsv> peopleCsv;
    std::unique_ptr<RawlogRecorder> rawlog;
    FrameStep step;
    RunProvenance invocation;

private:
    PlannerDriver::Setup driverSetup(const ExperimentConfig& config);
    FrameStep::Parts stepParts();
    void printProgress(const eval::MetricsSample& s, const std::string& figures) const;

    double nextSample = 0.0;
    double nextProgress = 0.0;
};

}  // namespace daep::mission
