#include "daep/mission/Replay.h"

#include "FrameStep.h"
#include "MissionSetup.h"
#include "StageClock.h"
#include "TrajectorySource.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/ExperimentConfig.h"

namespace daep::mission {

ReplayResult replayTrajectory(const ExperimentConfig& config, const std::string& trajectoryCsv) {
    const Settings settings = loadSettings(config);
    const world::WorldSpec world = loadWorld(settings, config.source());
    TrajectorySource source(world, config.config(), settings.seed, trajectoryCsv);
    mapping::ExplorationMap map(mapping::MapParams::fromConfig(config.config()),
                                world.explorationBox);
    StageClock stages;
    FrameStep::Parts parts;
    parts.map = &map;
    parts.stages = &stages;
    FrameStep step(parts);

    ReplayResult result;
    for (Frame frame; source.next(frame); ++result.frames)
        step.process(frame);
    result.knownVolume = map.knownVolumeInBox();
    result.coveragePercent = 100.0 * result.knownVolume / world.explorationVolume();
    return result;
}

}  // namespace daep::mission
