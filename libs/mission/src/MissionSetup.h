#pragma once

#include <cstdint>
#include <string>

#include "daep/world/WorldSpec.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace daep::mission {

class ExperimentConfig;

/** [experiment] planning_time: what a plan call costs the simulated clock. */
enum class PlanningTime {
    Fixed,     ///< planning_fixed_s per call: runs repeat bit for bit
    Measured,  ///< the call's wall time, with the [planning] deadline
};

/** The [experiment] section (and [planning] deadline_s), validated. */
struct Settings {
    std::string worldName, mode, plannerName;
    PlanningTime planningTime = PlanningTime::Fixed;
    int start = 0;
    std::uint64_t seed = 0;
    double maxTime = 0, planningFixed = 0, climb = 0, sampleEvery = 0, progressEvery = 0;
    double planningDeadline = 0;  ///< [planning] deadline_s: wall-clock budget of a plan call
    int maxFailedPlans = 0;
};

Settings loadSettings(const ExperimentConfig& experiment);

/** A world name or path -> its file; a relative path is looked up next to the experiment first. */
std::string resolveExperimentWorld(const std::string& worldName,
                                   const std::string& experimentSource);

/**
 * The most coverage the world allows from the experiment's start, on a grid of `resolution`
 * ([planning] robot_radius, the climb): daep::world::computeReachableVolume.
 */
double reachablePercent(const world::WorldSpec& world, const Settings& s,
                        const mrpt::config::CConfigFileBase& config, double resolution);

/** The experiment's world, people removed in static mode, start index checked. */
world::WorldSpec loadWorld(const Settings& s, const std::string& experimentSource);

}  // namespace daep::mission
