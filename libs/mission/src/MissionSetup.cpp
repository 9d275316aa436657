#include "MissionSetup.h"
#include "daep/common/ConfigChecks.h"
#include "daep/world/ReachableVolume.h"

#include <filesystem>

#include "daep/common/Config.h"
#include "daep/common/Error.h"
#include "daep/mission/ExperimentConfig.h"

namespace daep::mission {

std::string resolveExperimentWorld(const std::string& worldName,
                                   const std::string& experimentSource) {
    const std::filesystem::path besideConfig =
        std::filesystem::path(experimentSource).parent_path() / worldName;
    if (std::filesystem::path(worldName).is_relative() &&
        std::filesystem::is_regular_file(besideConfig))
        return besideConfig.string();
    return world::resolveWorldPath(worldName);
}

Settings loadSettings(const ExperimentConfig& experiment) {
    const ConfigReader r(experiment.config(), "experiment", experiment.source());
    Settings s;
    s.worldName = r.requireString("world");
    s.mode = requireOneOf(r, "mode", {"static", "dynamic"});
    s.plannerName = r.requireString("planner");
    s.start = r.requireInt("start");
    const std::string seedText = r.requireString("seed");
    try {
        std::size_t used = 0;
        s.seed = std::stoull(seedText, &used);
        if (used != seedText.size())
            throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
        throw InputError(r.where("seed") + ": [experiment] seed: '" + seedText +
                         "' is not a non-negative integer");
    }
    s.maxTime = r.requireDouble("max_time_s");
    if (s.maxTime <= 0)
        throw InputError(r.where("max_time_s") + ": [experiment] max_time_s: must be > 0");
    s.planningTime = requireEnum<PlanningTime>(
        r, "planning_time", {{"measured", PlanningTime::Measured}, {"fixed", PlanningTime::Fixed}});
    s.planningFixed = r.requireDouble("planning_fixed_s");
    s.climb = r.requireDouble("climb_m");
    s.sampleEvery = r.requireDouble("timeseries_every_s");
    if (s.sampleEvery <= 0)
        throw InputError(r.where("timeseries_every_s") +
                         ": [experiment] timeseries_every_s: must be > 0");
    s.progressEvery = r.requireDouble("progress_every_s");
    s.maxFailedPlans = r.requireInt("max_failed_plans");
    const ConfigReader planning(experiment.config(), "planning", experiment.source());
    s.planningDeadline = planning.requireDouble("deadline_s");
    if (!(s.planningDeadline > 0))
        throw InputError(planning.where("deadline_s") + ": [planning] deadline_s: must be > 0");
    if (s.planningTime == PlanningTime::Fixed && s.planningFixed > s.planningDeadline)
        throw InputError(planning.where("deadline_s") +
                         ": [planning] deadline_s: " + planning.requireString("deadline_s") +
                         " s is below [experiment] planning_fixed_s (" +
                         r.requireString("planning_fixed_s") +
                         " s): with planning_time = fixed every plan would miss it");
    return s;
}

world::WorldSpec loadWorld(const Settings& s, const std::string& experimentSource) {
    world::WorldSpec w =
        world::loadWorldFile(resolveExperimentWorld(s.worldName, experimentSource));
    if (s.mode == "static")
        w.people.clear();
    if (s.start < 0 || s.start >= static_cast<int>(w.starts.size()))
        throw InputError("[experiment] start: " + std::to_string(s.start) + " is out of range 0.." +
                         std::to_string(static_cast<int>(w.starts.size()) - 1) + " for world " +
                         w.name);
    return w;
}

double reachablePercent(const world::WorldSpec& world, const Settings& s,
                        const mrpt::config::CConfigFileBase& config, double resolution) {
    world::ReachParams p;
    p.resolution = resolution;
    p.robotRadius = requireNonNegative(ConfigReader(config, "planning"), "robot_radius");
    p.climb = s.climb;
    return world::computeReachableVolume(world, world.starts[std::size_t(s.start)], p)
        .reachablePercent;
}

}  // namespace daep::mission
