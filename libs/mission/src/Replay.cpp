#include "daep/mission/Replay.h"

#include <mrpt/obs/CObservation3DRangeScan.h>

#include <algorithm>
#include <fstream>
#include <random>
#include <sstream>
#include <vector>

#include "ComponentParams.h"
#include "MissionSetup.h"
#include "daep/common/Error.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/world/RayCaster.h"

namespace daep::mission {
namespace {

struct StampedPose {
    double time;
    FlatPose pose;
};

std::vector<StampedPose> readTrajectory(const std::string& path) {
    std::ifstream in(path);
    if (!in)
        throw InputError(path + ": cannot open file");
    std::string line;
    std::getline(in, line);
    if (line.rfind("sim_time,x,y,z,yaw", 0) != 0)
        throw InputError(path + ":1: expected the header 'sim_time,x,y,z,yaw'");
    std::vector<StampedPose> out;
    for (int lineNo = 2; std::getline(in, line); ++lineNo) {
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream cells(line);
        StampedPose s;
        if (!(cells >> s.time >> s.pose.position.x() >> s.pose.position.y() >>
              s.pose.position.z() >> s.pose.yaw))
            throw InputError(path + ":" + std::to_string(lineNo) + ": expected 5 numbers");
        if (!out.empty() && s.time < out.back().time)
            throw InputError(path + ":" + std::to_string(lineNo) + ": time goes backwards");
        out.push_back(s);
    }
    if (out.empty())
        throw InputError(path + ": no poses");
    return out;
}

/** Pose at time t, linear between samples (yaw along the shorter arc). */
FlatPose interpolate(const std::vector<StampedPose>& traj, double t, std::size_t& cursor) {
    while (cursor + 1 < traj.size() && traj[cursor + 1].time <= t)
        ++cursor;
    if (cursor + 1 >= traj.size())
        return traj.back().pose;
    const auto& a = traj[cursor];
    const auto& b = traj[cursor + 1];
    const double span = b.time - a.time;
    const double f = span > 0 ? (t - a.time) / span : 0.0;
    FlatPose p;
    p.position = a.pose.position + f * (b.pose.position - a.pose.position);
    p.yaw = wrapAngle(a.pose.yaw + f * wrapAngle(b.pose.yaw - a.pose.yaw));
    return p;
}

}  // namespace

ReplayResult replayTrajectory(const ExperimentConfig& config, const std::string& trajectoryCsv) {
    const Settings settings = loadSettings(config);
    const world::WorldSpec world = loadWorld(settings, config.source());
    const auto trajectory = readTrajectory(trajectoryCsv);
    world::PeopleSimulator people(world.people, loadPeopleParams(config.config()));
    world::RayCaster caster(world);
    const sim::DepthCamera camera(loadCameraParams(config.config()));
    mapping::ExplorationMap map(loadMapParams(config.config()), world.explorationBox);
    std::mt19937_64 noise(settings.seed);
    mrpt::obs::CObservation3DRangeScan frame;

    ReplayResult result;
    const double period = 1.0 / camera.params().rateHz;
    std::size_t cursor = 0;
    for (double t = trajectory.front().time; t <= trajectory.back().time + 1e-9; t += period) {
        people.advance(t - people.time());
        if (!world.people.empty())
            caster.setPeople(people.states(), people.params().bodySize);
        const FlatPose pose = interpolate(trajectory, t, cursor);
        camera.render(caster, pose, t, noise, frame);
        map.insertObservation(frame, pose);
        ++result.frames;
    }
    result.knownVolume = map.knownVolumeInBox();
    result.coveragePercent = 100.0 * result.knownVolume / world.explorationVolume();
    return result;
}

}  // namespace daep::mission
