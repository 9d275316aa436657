#include "TrajectorySource.h"

#include <mrpt/obs/CObservation3DRangeScan.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "daep/common/Error.h"
#include "daep/sim/DepthCamera.h"
#include "daep/world/People.h"

namespace daep::mission {
namespace {

std::vector<TrajectorySource::StampedPose> readTrajectory(const std::string& path) {
    std::ifstream in(path);
    if (!in)
        throw InputError(path + ": cannot open file");
    std::string line;
    std::getline(in, line);
    if (line.rfind("sim_time,x,y,z,yaw", 0) != 0)
        throw InputError(path + ":1: expected the header 'sim_time,x,y,z,yaw'");
    std::vector<TrajectorySource::StampedPose> out;
    for (int lineNo = 2; std::getline(in, line); ++lineNo) {
        std::replace(line.begin(), line.end(), ',', ' ');
        std::istringstream cells(line);
        TrajectorySource::StampedPose s;
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
FlatPose interpolate(const std::vector<TrajectorySource::StampedPose>& traj, double t,
                     std::size_t& cursor) {
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

TrajectorySource::TrajectorySource(const world::WorldSpec& world,
                                   const mrpt::config::CConfigFileBase& config, std::uint64_t seed,
                                   const std::string& trajectoryCsv)
    : path_(trajectoryCsv),
      trajectory_(readTrajectory(trajectoryCsv)),
      world_(world),
      people_(world.people, world::PeopleParams::fromConfig(config)),
      caster_(world),
      camera_(sim::CameraParams::fromConfig(config)),
      noise_(seed),
      period_(1.0 / camera_.params().rateHz),
      t_(trajectory_.front().time) {}

bool TrajectorySource::next(Frame& frame) {
    if (t_ > trajectory_.back().time + 1e-9)
        return false;
    people_.advance(t_ - people_.time());
    if (!world_.people.empty())
        caster_.setPeople(people_.states(), people_.params().bodySize);
    const FlatPose pose = interpolate(trajectory_, t_, cursor_);
    auto depth = std::make_shared<mrpt::obs::CObservation3DRangeScan>();
    camera_.render(caster_, pose, t_, noise_, *depth);
    frame.time = t_;
    frame.depth = std::move(depth);
    frame.robot = pose;
    frame.truePeople = people_.states();
    t_ += period_;
    return true;
}

}  // namespace daep::mission
