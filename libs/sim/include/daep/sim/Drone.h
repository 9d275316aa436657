#pragma once

#include <Eigen/Core>

#include "daep/common/Types.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace daep::sim {

struct DroneParams {
    double speed = 0.5;    ///< m/s, straight lines
    double yawRate = 1.0;  ///< rad/s, turns on the spot
    Eigen::Vector3d boxSize{0.4, 0.4, 0.1};

    /** Reads and validates [drone]; throws InputError naming the key. */
    static DroneParams fromConfig(const mrpt::config::CConfigFileBase& cfg);
};

/**
 * Turn-then-fly motion towards one waypoint: first turn on the spot to the waypoint's yaw,
 * then fly straight to its position keeping that yaw.
 */
class Drone {
public:
    Drone(DroneParams params, FlatPose start);

    const FlatPose& pose() const { return pose_; }
    const DroneParams& params() const { return params_; }
    bool hasGoal() const { return hasGoal_; }

    void setGoal(const FlatPose& goal);
    void clearGoal() { hasGoal_ = false; }

    /** Advances by up to dt; returns the time actually used (< dt when the goal is reached). */
    double advance(double dt);

    /** Time the turn-then-fly manoeuvre from `from` to `to` takes. */
    static double travelTime(const FlatPose& from, const FlatPose& to, const DroneParams& p);

private:
    DroneParams params_;
    FlatPose pose_;
    FlatPose goal_;
    bool hasGoal_ = false;
};

}  // namespace daep::sim
