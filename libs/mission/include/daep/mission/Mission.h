#pragma once

#include <atomic>
#include <iosfwd>
#include <memory>
#include <string>

#include "daep/eval/RunRecorder.h"

namespace daep::mission {

class ExperimentConfig;

/**
 * One exploration run on the built-in simulator: spawn, climb, turn a full circle, then
 * plan / hover while planning / fly, until the planner says it is finished or time is up.
 * The simulated clock drives everything; with planning_time = fixed a run is a pure function
 * of its config and seed.
 */
class Mission {
public:
    /** Builds the world, sensors, map and planner; throws InputError on bad parameters. */
    Mission(const ExperimentConfig& config, const std::string& outputDir, std::ostream* log);
    ~Mission();

    /** Runs to the end and writes all outputs; returns the summary it wrote. */
    eval::RunSummary run();

    /** Asks a running mission to stop at the next step (thread/signal safe). */
    void requestStop() { stopRequested_ = true; }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::atomic<bool> stopRequested_{false};
};

}  // namespace daep::mission
