#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <string>

#include "daep/mission/FrameSource.h"
#include "daep/mission/PeopleInput.h"
#include "daep/sim/CollisionMonitor.h"
#include "daep/sim/DepthCamera.h"
#include "daep/sim/Drone.h"
#include "daep/world/People.h"
#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace daep::mission {

class ExperimentConfig;
class StageClock;
struct Settings;

/**
 * The built-in simulator as a frame source, closed loop: the world (walking people, the depth
 * camera, the collision monitor) goes on in simulated time while the drone flies to the goal it
 * was given or hovers, and a depth frame is taken at every camera period. next() is the open
 * loop over it (the drone keeps its command); a mission steps it itself (step) to react
 * between frames.
 */
class SimulatorSource : public FrameSource {
public:
    /**
     * The drone rests on start `start` of `world`; InputError when its box, or the climb of
     * `climb` m above it, is inside static geometry or leaves the exploration box.
     */
    SimulatorSource(world::WorldSpec world, const mrpt::config::CConfigFileBase& config, int start,
                    double climb, std::uint64_t seed, StageClock* stages);
    /** The experiment's world, start, climb and seed. */
    SimulatorSource(const ExperimentConfig& experiment, StageClock* stages);

    bool next(Frame& frame) override;
    std::string name() const override { return world_.sourceFile; }

    /** Takes the frame at spawn, the first of the run; the next falls due a period later. */
    const Frame& takeFirstFrame();

    /** What one step did. */
    struct Step {
        bool frameTaken = false;  ///< a frame fell due and was taken: frame()
        bool reached = false;     ///< the drone reached its goal (it has none any more)
        double moved = 0.0;       ///< m flown
    };

    /**
     * Advances the world by at most `limit` s, never past the next frame or by more than 50 ms
     * (collision checks must not skip through a person); the drone flies to its goal when
     * `flying` (stopping there), else it hovers.
     */
    Step step(double limit, bool flying);

    /** The frame taken last. */
    const Frame& frame() const { return frame_; }
    /** What measuring sensed people needs: the scene and the camera, as of the last frame. */
    CameraSight sight() const;

    double time() const { return t_; }
    double framePeriod() const { return framePeriod_; }
    /** When the next frame falls due; it changes only when a frame is taken. */
    double nextFrameTime() const { return nextFrame_; }

    sim::Drone& drone() { return drone_; }
    const sim::Drone& drone() const { return drone_; }
    const world::WorldSpec& world() const { return world_; }
    const world::PeopleSimulator& people() const { return people_; }
    const sim::CollisionMonitor& monitor() const { return monitor_; }

private:
    SimulatorSource(const ExperimentConfig& experiment, const Settings& settings,
                    StageClock* stages);
    void checkStartIsFree(int start, double climb) const;
    void takeFrame();

    world::WorldSpec world_;
    world::PeopleSimulator people_;
    world::RayCaster caster_;
    world::StaticCollisionChecker statics_;
    sim::DepthCamera camera_;
    sim::Drone drone_;
    sim::CollisionMonitor monitor_;
    std::mt19937_64 noise_;
    std::shared_ptr<mrpt::obs::CObservation3DRangeScan> depth_;
    Frame frame_;
    StageClock* stages_;
    double t_ = 0.0;
    double framePeriod_ = 0.1;
    double nextFrame_ = 0.0;
};

}  // namespace daep::mission
