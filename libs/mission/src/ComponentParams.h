#pragma once

#include "daep/common/Config.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/perception/PeopleDetector.h"
#include "daep/perception/PeopleTracker.h"
#include "daep/sim/DepthCamera.h"
#include "daep/sim/Drone.h"
#include "daep/world/People.h"

namespace daep::mission {

sim::CameraParams loadCameraParams(const mrpt::config::CConfigFileBase& cfg);
sim::DroneParams loadDroneParams(const mrpt::config::CConfigFileBase& cfg);
world::PeopleParams loadPeopleParams(const mrpt::config::CConfigFileBase& cfg);
mapping::MapParams loadMapParams(const mrpt::config::CConfigFileBase& cfg);
perception::DetectorParams loadDetectorParams(const mrpt::config::CConfigFileBase& cfg);
/** [tracker]: association, birth and death of tracks, and the constant-velocity predictor. */
perception::TrackerParams loadTrackerParams(const mrpt::config::CConfigFileBase& cfg);

}  // namespace daep::mission
