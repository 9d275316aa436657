#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "daep/planning/Planner.h"

namespace daep::planning {

/** Builds a planner from the config (its own section, [gain], [planning]) and the run's seed. */
using PlannerFactory = std::function<std::unique_ptr<ExplorationPlanner>(
    const mrpt::config::CConfigFileBase& config, std::uint64_t seed)>;

/**
 * Adds a planner under `name` (lower case, as [experiment] planner spells it), so that
 * createPlanner builds it and plannerNames lists it. The built-in planners are registered in
 * PlannerRegistry.cpp, one line each; a program or a test adds its own before any mission
 * starts (the registry is not guarded for threads). Returns true, so it can initialise a static.
 * Throws std::logic_error for an empty name or one already taken.
 */
bool registerPlanner(const std::string& name, PlannerFactory factory);

/** Planner names accepted by createPlanner, sorted. */
std::vector<std::string> plannerNames();

/**
 * Creates a planner by name, reading its parameters from the config. Throws InputError for an
 * unknown name (listing the valid ones) or a missing/bad key.
 */
std::unique_ptr<ExplorationPlanner> createPlanner(const std::string& name,
                                                  const mrpt::config::CConfigFileBase& config,
                                                  std::uint64_t seed);

}  // namespace daep::planning
