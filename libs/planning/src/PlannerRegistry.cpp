#include "daep/planning/PlannerRegistry.h"

#include <map>
#include <stdexcept>
#include <utility>

#include "daep/common/Error.h"
#include "daep/planning/AepPlanner.h"
#include "daep/planning/DaepPlanner.h"
#include "daep/planning/DepPlanner.h"
#include "daep/planning/RhNbvpPlanner.h"

namespace daep::planning {
namespace {

/** A planner built from its own parameters, the shared [gain] section and the seed. */
template <class PlannerType, class ParamsType>
PlannerFactory fromParams() {
    return [](const mrpt::config::CConfigFileBase& config, std::uint64_t seed) {
        return std::make_unique<PlannerType>(ParamsType::fromConfig(config),
                                             GainParams::fromConfig(config), seed);
    };
}

/** Every planner by name. The built-in ones are here rather than registered from their own
 * files: a static library drops an object file nothing refers to, registration and all. */
std::map<std::string, PlannerFactory>& registry() {
    static std::map<std::string, PlannerFactory> planners = {
        {"aep", fromParams<AepPlanner, AepParams>()},
        {"daep", fromParams<DaepPlanner, DaepParams>()},
        {"dep", fromParams<DepPlanner, DepParams>()},
        {"rhnbvp", fromParams<RhNbvpPlanner, RhNbvpParams>()},
    };
    return planners;
}

}  // namespace

bool registerPlanner(const std::string& name, PlannerFactory factory) {
    if (name.empty() || !factory)
        throw std::logic_error("registerPlanner: a planner needs a name and a factory");
    if (!registry().emplace(name, std::move(factory)).second)
        throw std::logic_error("registerPlanner: a planner named '" + name + "' exists");
    return true;
}

std::vector<std::string> plannerNames() {
    std::vector<std::string> names;
    for (const auto& entry : registry())
        names.push_back(entry.first);
    return names;
}

std::unique_ptr<ExplorationPlanner> createPlanner(const std::string& name,
                                                  const mrpt::config::CConfigFileBase& config,
                                                  std::uint64_t seed) {
    const auto found = registry().find(name);
    if (found != registry().end())
        return found->second(config, seed);
    std::string valid;
    for (const std::string& n : plannerNames())
        valid += (valid.empty() ? "" : ", ") + n;
    throw InputError("unknown planner '" + name + "'; valid planners: " + valid);
}

}  // namespace daep::planning
