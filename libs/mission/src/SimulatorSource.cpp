#include "SimulatorSource.h"

#include <mrpt/obs/CObservation3DRangeScan.h>

#include <algorithm>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>

#include "MissionSetup.h"
#include "StageClock.h"
#include "daep/common/Error.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/sim/DepthCamera.h"
#include "daep/sim/Drone.h"
#include "daep/world/People.h"

namespace daep::mission {
namespace {

/** Collision checks must not skip through a person: bound the simulation step. */
constexpr double kMaxStep = 0.05;
constexpr double kEps = 1e-9;

std::string formatPoint(const Eigen::Vector3d& p) {
    std::ostringstream o;
    o << std::fixed << std::setprecision(2) << "(" << p.x() << ", " << p.y() << ", " << p.z()
      << ")";
    return o.str();
}

const Eigen::Vector3d& startOf(const world::WorldSpec& world, int start) {
    if (start < 0 || std::size_t(start) >= world.starts.size())
        throw InputError(world.sourceFile + ": no start " + std::to_string(start) + " (it has " +
                         std::to_string(world.starts.size()) + ")");
    return world.starts[std::size_t(start)];
}

/** The drone rests on the start point: its box's bottom face is at the start's z. */
FlatPose restingOn(const Eigen::Vector3d& start, const sim::DroneParams& drone) {
    FlatPose p;
    p.position = start;
    p.position.z() += 0.5 * drone.boxSize.z();
    return p;
}

}  // namespace

SimulatorSource::SimulatorSource(world::WorldSpec world,
                                 const mrpt::config::CConfigFileBase& config, int start,
                                 double climb, std::uint64_t seed, StageClock* stages)
    : world_(std::move(world)),
      people_(world_.people, world::PeopleParams::fromConfig(config)),
      caster_(world_),
      statics_(world_),
      camera_(sim::CameraParams::fromConfig(config)),
      drone_(sim::DroneParams::fromConfig(config),
             restingOn(startOf(world_, start), sim::DroneParams::fromConfig(config))),
      monitor_(drone_.params().boxSize, people_.params().bodySize, &statics_),
      noise_(seed),
      depth_(std::make_shared<mrpt::obs::CObservation3DRangeScan>()),
      stages_(stages) {
    checkStartIsFree(start, climb);
    framePeriod_ = 1.0 / camera_.params().rateHz;
    frame_.depth = depth_;
}

SimulatorSource::SimulatorSource(const ExperimentConfig& experiment, StageClock* stages)
    : SimulatorSource(experiment, loadSettings(experiment), stages) {}

SimulatorSource::SimulatorSource(const ExperimentConfig& experiment, const Settings& settings,
                                 StageClock* stages)
    : SimulatorSource(loadWorld(settings, experiment.source()), experiment.config(), settings.start,
                      settings.climb, settings.seed, stages) {}

void SimulatorSource::checkStartIsFree(int start, double climb) const {
    const Eigen::Vector3d given = world_.starts[std::size_t(start)];
    const Eigen::Vector3d s = drone_.pose().position;
    const Eigen::Vector3d top = s + Eigen::Vector3d(0, 0, climb);
    const std::string which =
        world_.sourceFile + ": start " + std::to_string(start) + " " + formatPoint(given);
    for (double f = 0; f <= 1.0 + kEps; f += 0.1) {
        const Eigen::Vector3d p = s + f * (top - s);
        if (statics_.overlaps(p, drone_.params().boxSize, 0.0))
            throw InputError(which + ": the drone box at " + formatPoint(p) +
                             " (take-off) is inside static geometry");
    }
    if (!world_.explorationBox.contains(top))
        throw InputError(which + ": after the climb the drone is outside the exploration box");
}

void SimulatorSource::takeFrame() {
    const auto timed = stages_->time(Stage::Render);
    if (!world_.people.empty())
        caster_.setPeople(people_.states(), people_.params().bodySize);
    camera_.render(caster_, drone_.pose(), t_, noise_, *depth_);
    frame_.time = t_;
    frame_.robot = drone_.pose();
    frame_.truePeople = people_.states();
}

const Frame& SimulatorSource::takeFirstFrame() {
    takeFrame();
    nextFrame_ = framePeriod_;
    return frame_;
}

SimulatorSource::Step SimulatorSource::step(double limit, bool flying) {
    Step s;
    std::optional<StageClock::Scope> worldTime(std::in_place, *stages_, Stage::World);
    double h = std::max(std::min({limit, nextFrame_ - t_, kMaxStep}), 0.0);
    if (flying) {
        const Eigen::Vector3d before = drone_.pose().position;
        h = drone_.advance(h);
        s.reached = !drone_.hasGoal();
        s.moved = (drone_.pose().position - before).norm();
    }
    people_.advance(h);
    t_ += h;
    monitor_.update(t_, drone_.pose(), people_.states());
    worldTime.reset();
    if (t_ >= nextFrame_ - kEps) {
        takeFrame();
        nextFrame_ += framePeriod_;
        s.frameTaken = true;
    }
    return s;
}

bool SimulatorSource::next(Frame& frame) {
    while (!step(std::numeric_limits<double>::infinity(), drone_.hasGoal()).frameTaken) {
    }
    frame = frame_;
    return true;
}

CameraSight SimulatorSource::sight() const {
    return {&caster_, camera_.sensorPose(drone_.pose()), camera_.params()};
}

}  // namespace daep::mission
