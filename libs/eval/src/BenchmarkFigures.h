#pragma once

// Private to libs/eval: the paper's Fig. 4 layout from a benchmark's runs.

#include <string>
#include <vector>

#include "daep/eval/BenchmarkResults.h"
#include "daep/eval/Plot.h"

namespace daep::eval::detail {

/** One planner's ok runs of one world and mode, with its display name and colour. */
struct PlannerRuns {
    std::string name;
    Rgb color;
    std::vector<const RunResult*> runs;
};

/**
 * STEM.png/.svg/.pdf: coverage over time per planner (mean line, mean +- std and min-max bands
 * across runs) above a collision timeline (one row per run, each collision episode a bar from
 * its start to its end), on one time axis. Returns the paths written.
 */
std::vector<std::string> writeFig4(const std::string& world, const std::string& mode,
                                   const std::vector<PlannerRuns>& planners,
                                   const std::string& stem);

}  // namespace daep::eval::detail
