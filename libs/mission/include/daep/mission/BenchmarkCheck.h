#pragma once

#include <string>
#include <vector>

#include "daep/eval/BenchmarkConfig.h"

namespace daep::mission {

/**
 * Checks a whole benchmark matrix the way daep-explore would load each run, before any is
 * launched: every planner known, every world loadable, every start within each world's starts,
 * every [set] / --set key known to the defaults, and every run's parameters valid. Returns the
 * runs with their inputs (effective parameters, world file digests, and their digest) filled.
 * Throws InputError naming file:line or the --set key.
 */
std::vector<eval::RunSpec> checkBenchmark(const eval::BenchmarkConfig& config);

/** SHA-256 of bytes, as 64 lowercase hex digits. */
std::string sha256Hex(const std::string& bytes);

}  // namespace daep::mission
