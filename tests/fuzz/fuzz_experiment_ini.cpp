// The strict experiment ini with --set overrides, then every component's typed reading of it.
// Input: the experiment file, then optionally a line "--set" and one override per line.
#include <cstdint>

#include "FuzzSupport.h"
#include "MissionSetup.h"
#include "Outputs.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/PeopleInput.h"
#include "daep/perception/PeopleDetector.h"
#include "daep/perception/PeopleTracker.h"
#include "daep/planning/Planner.h"
#include "daep/planning/PlannerRegistry.h"
#include "daep/sim/DepthCamera.h"
#include "daep/sim/Drone.h"
#include "daep/world/People.h"

namespace {

void readEveryComponent(const daep::mission::ExperimentConfig& experiment) {
    using namespace daep::mission;
    const auto& cfg = experiment.config();
    const Settings settings = loadSettings(experiment);
    daep::sim::CameraParams::fromConfig(cfg);
    daep::sim::DroneParams::fromConfig(cfg);
    daep::world::PeopleParams::fromConfig(cfg);
    daep::mapping::MapParams::fromConfig(cfg);
    daep::perception::DetectorParams::fromConfig(cfg);
    daep::perception::TrackerParams::fromConfig(cfg);
    loadOutputParams(cfg);
    PeopleInputParams::fromConfig(cfg);
    for (const auto& name : daep::planning::plannerNames())
        daep::planning::createPlanner(name, cfg, settings.seed);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const auto parts = daep::fuzz::splitParts(data, size, "--set");
    std::vector<std::string> overrides;
    for (std::size_t i = 1; i < parts.size(); ++i)
        for (const auto& line : daep::fuzz::lines(parts[i]))
            overrides.push_back(line);
    daep::fuzz::expectOnlyInputErrors([&] {
        const auto experiment =
            daep::mission::ExperimentConfig::fromText(parts[0], "fuzz.ini", overrides);
        experiment.dump();
        readEveryComponent(experiment);
    });
    return 0;
}
