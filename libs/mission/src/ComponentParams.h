#pragma once

#include "daep/common/Config.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/sim/DepthCamera.h"
#include "daep/sim/Drone.h"
#include "daep/world/People.h"

namespace daep::mission {

sim::CameraParams loadCameraParams(const mrpt::config::CConfigFileBase& cfg);
sim::DroneParams loadDroneParams(const mrpt::config::CConfigFileBase& cfg);
world::PeopleParams loadPeopleParams(const mrpt::config::CConfigFileBase& cfg);
mapping::MapParams loadMapParams(const mrpt::config::CConfigFileBase& cfg);

}  // namespace daep::mission
