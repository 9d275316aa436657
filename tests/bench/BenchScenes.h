#pragma once

#include <mrpt/obs/CObservation3DRangeScan.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "daep/mapping/ExplorationMap.h"
#include "daep/sim/DepthCamera.h"
#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace daep::bench {

/**
 * The world's map after the mission's take-off at its first `starts` start positions: 1 m up,
 * the 320 x 240 camera turns a full circle in 20 degree steps and every frame is integrated.
 * Returns the map; `poses` gets the pose at each start.
 */
inline std::unique_ptr<mapping::ExplorationMap> lookAroundAtStarts(const world::WorldSpec& world,
                                                                   const world::RayCaster& caster,
                                                                   std::size_t starts,
                                                                   std::vector<FlatPose>& poses) {
    sim::CameraParams cp;
    cp.width = 320;
    cp.height = 240;
    const sim::DepthCamera camera(cp);
    auto map =
        std::make_unique<mapping::ExplorationMap>(mapping::MapParams{}, world.explorationBox);
    std::mt19937_64 rng(1);
    mrpt::obs::CObservation3DRangeScan obs;
    for (std::size_t s = 0; s < std::min(starts, world.starts.size()); ++s) {
        FlatPose pose{world.starts[s] + Eigen::Vector3d(0, 0, 1.0), 0.0};
        for (int step = 0; step < 18; ++step) {
            pose.yaw = wrapAngle(step * M_PI / 9.0);
            camera.render(caster, pose, 0.0, rng, obs);
            map->insertObservation(obs, pose);
        }
        poses.push_back(pose);
    }
    return map;
}

/** The q-quantile (0..1) of the values, nearest rank: for p95 and max aggregates. */
inline double quantile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(std::lround(q * static_cast<double>(v.size() - 1)))];
}

}  // namespace daep::bench
