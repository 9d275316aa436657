#include "daep/sim/Drone.h"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "daep/common/ConfigChecks.h"
#include "daep/common/Error.h"

namespace daep::sim {

Drone::Drone(DroneParams params, FlatPose start) : params_(std::move(params)), pose_(start) {
    if (!(params_.speed > 0.0) || !(params_.yawRate > 0.0)) {
        throw std::invalid_argument("Drone: speed and yawRate must be positive");
    }
}

void Drone::setGoal(const FlatPose& goal) {
    goal_ = goal;
    hasGoal_ = true;
}

double Drone::advance(double dt) {
    if (!hasGoal_ || dt <= 0.0) {
        return 0.0;
    }
    double remaining = dt;

    const double turn = wrapAngle(goal_.yaw - pose_.yaw);
    const double turnTime = std::abs(turn) / params_.yawRate;
    if (turnTime > remaining) {
        pose_.yaw = wrapAngle(pose_.yaw + std::copysign(params_.yawRate * remaining, turn));
        return dt;
    }
    pose_.yaw = goal_.yaw;
    remaining -= turnTime;

    const Eigen::Vector3d toGoal = goal_.position - pose_.position;
    const double distance = toGoal.norm();
    const double flyTime = distance / params_.speed;
    if (flyTime > remaining) {
        pose_.position += toGoal * (params_.speed * remaining / distance);
        return dt;
    }
    pose_ = goal_;
    hasGoal_ = false;
    return (dt - remaining) + flyTime;
}

double Drone::travelTime(const FlatPose& from, const FlatPose& to, const DroneParams& p) {
    return std::abs(wrapAngle(to.yaw - from.yaw)) / p.yawRate +
           (to.position - from.position).norm() / p.speed;
}

DroneParams DroneParams::fromConfig(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "drone");
    DroneParams p;
    p.speed = requirePositive(r, "speed");
    p.yawRate = requirePositive(r, "yaw_rate_deg_s") * M_PI / 180.0;
    p.boxSize = requirePositiveXyz(r, "box");
    return p;
}

}  // namespace daep::sim
