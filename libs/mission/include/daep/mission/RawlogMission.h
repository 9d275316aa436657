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
class FrameSource;

/**
 * An experiment on recorded data ([experiment] source = rawlog), or on any other open-loop
 * frame source (a live camera): streams the depth frames, puts each through the same per-frame
 * step as a simulated mission (the people of [tracking] people_source, tracked with [tracker];
 * then the map, at the robot pose the source gives), and every [rawlog] plan_every_s of frame
 * time asks the planner, with the tracked people, what it would fly from there (nothing is
 * flown). Writes plans.csv (pose, plan, gain, and whether the plan is safe against the map and
 * the people), people.csv (the confirmed tracks after each frame), timeseries.csv,
 * trajectory.csv, summary.json, timing.json, collisions.csv (empty), map.bt, run.rawlog with
 * [output] rawlog, and the scene with the tracks and their predicted paths.
 */
class RawlogMission {
public:
    /** Opens the rawlog and reads its first depth frame; throws InputError on bad input. */
    RawlogMission(const ExperimentConfig& config, const std::string& outputDir, std::ostream* log);
    /**
     * The same over another open-loop source; [experiment] rawlog_file is not needed, the
     * [rawlog] keys (box or world, plan_every_s, realtime) apply as for a rawlog.
     */
    RawlogMission(const ExperimentConfig& config, std::unique_ptr<FrameSource> frames,
                  const std::string& outputDir, std::ostream* log);
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
