#pragma once

#include <cstddef>
#include <string>

namespace daep::mission {

class ExperimentConfig;

struct ReplayResult {
    double coveragePercent = 0.0;
    double knownVolume = 0.0;
    std::size_t frames = 0;
};

/**
 * Flies a recorded trajectory (trajectory.csv of a run: sim_time,x,y,z,yaw) again through the
 * experiment's world, with the experiment's camera and map settings, and returns the coverage.
 * The people walk as in the original run. This isolates the sensor settings from the planner:
 * the same path mapped with two cameras.
 */
ReplayResult replayTrajectory(const ExperimentConfig& config, const std::string& trajectoryCsv);

}  // namespace daep::mission
