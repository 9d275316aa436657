#include "daep/planning/Planner.h"

#include <cmath>
#include <utility>

#include "daep/common/Error.h"
#include "daep/planning/AepPlanner.h"
#include "daep/planning/DaepPlanner.h"
#include "daep/planning/DepPlanner.h"
#include "daep/planning/RhNbvpPlanner.h"

namespace daep::planning {

double MotionLimits::travelTime(const FlatPose& a, const FlatPose& b) const {
    const double turn = std::abs(wrapAngle(b.yaw - a.yaw)) / yawRate;
    const double fly = (b.position - a.position).norm() / speed;
    return turn + fly;
}

void Plan::cutTo(std::size_t n) {
    if (n >= waypoints.size())
        return;
    waypoints.resize(n);
    if (n == 0 && status == Status::Path)
        status = Status::NoPath;
}

void Plan::waitFor(double seconds) {
    waypoints.clear();
    waitSeconds = seconds;
    status = seconds > 0.0 ? Status::Wait : Status::NoPath;
}

bool Plan::wellFormed() const {
    switch (status) {
        case Status::Path:
            return !waypoints.empty();
        case Status::Wait:
            return waypoints.empty() && waitSeconds > 0.0;
        case Status::NoPath:
        case Status::Finished:
            return waypoints.empty();
    }
    return false;
}

const char* statusName(Plan::Status status) {
    switch (status) {
        case Plan::Status::Path:
            return "path";
        case Plan::Status::Wait:
            return "wait";
        case Plan::Status::NoPath:
            return "no_path";
        case Plan::Status::Finished:
            return "finished";
    }
    return "?";
}

namespace {

using PlannerFactory = std::unique_ptr<ExplorationPlanner> (*)(
    const mrpt::config::CConfigFileBase& config, std::uint64_t seed);

/** Every planner reads its own parameters and the shared [gain] section. */
template <class PlannerType, class ParamsType>
std::unique_ptr<ExplorationPlanner> make(const mrpt::config::CConfigFileBase& config,
                                         std::uint64_t seed) {
    return std::make_unique<PlannerType>(ParamsType::fromConfig(config),
                                         GainParams::fromConfig(config), seed);
}

/** Every planner, by the name used in [experiment] planner; keep sorted by name. */
const std::vector<std::pair<std::string, PlannerFactory>>& factories() {
    static const std::vector<std::pair<std::string, PlannerFactory>> table = {
        {"aep", &make<AepPlanner, AepParams>},
        {"daep", &make<DaepPlanner, DaepParams>},
        {"dep", &make<DepPlanner, DepParams>},
        {"rhnbvp", &make<RhNbvpPlanner, RhNbvpParams>},
    };
    return table;
}

}  // namespace

std::vector<std::string> plannerNames() {
    std::vector<std::string> names;
    for (const auto& entry : factories())
        names.push_back(entry.first);
    return names;
}

std::unique_ptr<ExplorationPlanner> createPlanner(const std::string& name,
                                                  const mrpt::config::CConfigFileBase& config,
                                                  std::uint64_t seed) {
    for (const auto& [known, factory] : factories())
        if (known == name)
            return factory(config, seed);
    std::string valid;
    for (const std::string& n : plannerNames())
        valid += (valid.empty() ? "" : ", ") + n;
    throw InputError("unknown planner '" + name + "'; valid planners: " + valid);
}

}  // namespace daep::planning
