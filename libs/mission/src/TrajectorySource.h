#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "daep/mission/FrameSource.h"
#include "daep/sim/DepthCamera.h"
#include "daep/world/People.h"
#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace daep::mission {

/**
 * A recorded trajectory (trajectory.csv of a run: sim_time,x,y,z,yaw) flown again through a
 * world, open loop: a frame every camera period from its first pose to its last, at the pose
 * interpolated there, with the people walking as in the original run. The same path seen with
 * other camera or map settings.
 */
class TrajectorySource : public FrameSource {
public:
    /** Reads the trajectory; InputError naming the file and line on bad input. */
    TrajectorySource(const world::WorldSpec& world, const mrpt::config::CConfigFileBase& config,
                     std::uint64_t seed, const std::string& trajectoryCsv);

    bool next(Frame& frame) override;
    std::string name() const override { return path_; }

    struct StampedPose {
        double time;
        FlatPose pose;
    };

private:
    std::string path_;
    std::vector<StampedPose> trajectory_;
    const world::WorldSpec& world_;
    world::PeopleSimulator people_;
    world::RayCaster caster_;
    sim::DepthCamera camera_;
    std::mt19937_64 noise_;
    double period_;
    double t_;
    std::size_t cursor_ = 0;
};

}  // namespace daep::mission
