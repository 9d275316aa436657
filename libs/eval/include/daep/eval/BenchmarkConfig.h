#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace daep::eval {

/** What a run's outcome depends on; filled by daep::mission::checkBenchmark. */
struct RunInputs {
    std::string
        parameters;  ///< the effective parameters as ini text (as daep-explore's config.ini)
    /** The world's files (the world file, then the files it references): name and SHA-256. */
    std::vector<std::pair<std::string, std::string>> files;
    /** SHA-256 over the parameters and the files' digests; empty when not checked. */
    std::string digest;
};

/** One mission of the experiment matrix. */
struct RunSpec {
    std::string world;
    std::string mode;
    std::string planner;
    int start = 0;
    int repetition = 0;
    int seed = 0;
    RunInputs inputs;

    /** Directory name under OUT/runs: <world>_<mode>_<planner>_s<start>_r<rep>. */
    std::string id() const;
};

/**
 * A benchmark ini: [benchmark] (planners, worlds, modes, starts, repetitions, seed, experiment)
 * and an optional [set] of `section.key = value` overrides passed to every run.
 */
struct BenchmarkConfig {
    std::string source;  ///< path of the benchmark ini
    std::vector<std::string> planners;
    std::vector<std::string> worlds;
    std::vector<std::string> modes;
    std::vector<int> starts;
    int repetitions = 1;
    int seed = 1;
    std::string experiment;  ///< absolute path of the daep-explore experiment ini
    /** `section.key` -> value, from [set] and non-benchmark --set, in order. */
    std::vector<std::pair<std::string, std::string>> sets;
    /** Where each [benchmark] key ("planners") and [set] key ("experiment.max_time_s") was given:
     * "file:line" or "--set section.key". */
    std::map<std::string, std::string> origins;

    /** planners x worlds x modes x starts x repetitions, seed = seed + repetition. */
    std::vector<RunSpec> expand() const;
    /** The `section.key=value` overrides daep-explore gets for one run: [set], then the matrix's.
     */
    std::vector<std::string> runOverrides(const RunSpec& run) const;
    /** origins[key], or the config's path when unknown. */
    std::string where(const std::string& key) const;
};

/**
 * Reads a benchmark ini strictly; `overrides` are `section.key=value` from the command line:
 * `benchmark.*` replace [benchmark] keys, anything else is added to the runs' overrides.
 * Throws daep::InputError naming file:line (or the --set) and the key.
 */
BenchmarkConfig loadBenchmarkConfig(const std::string& path,
                                    const std::vector<std::string>& overrides = {});

/** "0-4", "0,2" or "0-1,3" -> the listed non-negative integers, in order, no duplicates. */
std::vector<int> parseIntList(const std::string& text);

}  // namespace daep::eval
