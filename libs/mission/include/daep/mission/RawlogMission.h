#pragma once

#include <atomic>
#include <iosfwd>
#include <memory>
#include <string>

#include "daep/eval/RunRecorder.h"

namespace daep::mapping {
class ExplorationMap;
}

namespace daep::mission {

class ExperimentConfig;

/**
 * An experiment on recorded data ([experiment] source = rawlog): streams the depth frames of
 * [experiment] rawlog_file, integrates each into the exploration map at the robot pose the
 * rawlog gives, and every [rawlog] plan_every_s of rawlog time asks the planner what it would
 * fly from there (nothing is flown). Writes plans.csv (pose, plan, gain, keepFlying verdict),
 * timeseries.csv, trajectory.csv, summary.json, timing.json, collisions.csv (empty), map.bt
 * and the scene, like Mission. People are detected in every frame ([detector]) and tracked
 * ([tracker]); people.csv has the confirmed tracks after each frame. The planner does not see
 * them yet: it plans on the map only.
 */
class RawlogMission {
public:
    /** Opens the rawlog and reads its first depth frame; throws InputError on bad input. */
    RawlogMission(const ExperimentConfig& config, const std::string& outputDir, std::ostream* log);
    ~RawlogMission();

    /** Replays to the end of the rawlog and writes all outputs; returns the summary. */
    eval::RunSummary run();

    /** Asks a running replay to stop at the next frame (thread/signal safe). */
    void requestStop() { stopRequested_ = true; }

    /** The map built so far. */
    const mapping::ExplorationMap& map() const;
    /** Depth frames integrated so far. */
    std::size_t frames() const;

    /** True for [experiment] source = rawlog, false for sim; InputError for anything else. */
    static bool selectedBy(const ExperimentConfig& config);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::atomic<bool> stopRequested_{false};
};

}  // namespace daep::mission
