#include "daep/planning/Planner.h"

#include <cmath>

#include "daep/common/Error.h"
#include "daep/planning/RhNbvpPlanner.h"

namespace daep::planning {

double MotionLimits::travelTime(const FlatPose& a, const FlatPose& b) const {
    const double turn = std::abs(wrapAngle(b.yaw - a.yaw)) / yawRate;
    const double fly = (b.position - a.position).norm() / speed;
    return turn + fly;
}

std::vector<std::string> plannerNames() {
    return {"rhnbvp"};
}

std::unique_ptr<ExplorationPlanner> createPlanner(const std::string& name,
                                                  const mrpt::config::CConfigFileBase& config,
                                                  std::uint64_t seed) {
    if (name == "rhnbvp") {
        return std::make_unique<RhNbvpPlanner>(RhNbvpParams::fromConfig(config),
                                               GainParams::fromConfig(config), seed);
    }
    std::string valid;
    for (const std::string& n : plannerNames())
        valid += (valid.empty() ? "" : ", ") + n;
    throw InputError("unknown planner '" + name + "'; valid planners: " + valid);
}

}  // namespace daep::planning
