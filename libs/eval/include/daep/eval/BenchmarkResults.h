#pragma once

#include <map>
#include <string>
#include <vector>

#include "daep/eval/BenchmarkConfig.h"

namespace daep::eval {

/** What became of one run. */
struct RunResult {
    RunSpec spec;
    std::string status;  ///< ok | failed | pending
    int exitCode = -1;   ///< -1 when not (yet) known
    std::string log;     ///< path of run.log
    std::string directory;
    /** summary.json values by key (numbers and booleans as text), in file order. */
    std::vector<std::pair<std::string, std::string>> metrics;
    /** summary.json's "provenance" block, flattened ("git_commit", "libraries.MRPT", ...). */
    std::vector<std::pair<std::string, std::string>> provenance;
    /** Busy threads the runner kept beside the run (daep-benchmark --load), from run.json. */
    int loadThreads = 0;

    double metric(const std::string& key, double fallback = 0.0) const;
    /** A provenance value as text; "" when absent. */
    std::string provenanceValue(const std::string& key) const;
    /** "VERSION COMMIT7[-dirty]" of the daep-explore that made the run; "" when not recorded. */
    std::string build() const;
};

/** Per-run files written by the runner next to daep-explore's outputs. */
inline constexpr const char* kRunSpecFile = "run.json";
inline constexpr const char* kExitCodeFile = "exit_code";
inline constexpr const char* kRunLogFile = "run.log";

/**
 * Parses a JSON object into key/value text pairs, in file order: numbers as written, booleans
 * as true/false; members of nested objects get dotted keys ("provenance.git_commit"). Throws
 * std::runtime_error on malformed JSON.
 */
std::vector<std::pair<std::string, std::string>> parseFlatJson(const std::string& text);

/** run.json: the run's identification, its parameter digest and the build that launched it. */
/** run.json: the run's labels, digests, the build that launched it and the busy threads beside it.
 */
void writeRunSpec(const std::string& runDirectory, const RunSpec& spec, int loadThreads = 0);
/** Reads a run directory (run.json, exit_code, summary.json); throws if run.json is unreadable. */
RunResult readRun(const std::string& runDirectory);
/** Every run directory under DIR/runs that has a run.json, sorted by id. */
std::vector<RunResult> readRuns(const std::string& benchmarkDirectory);

/** One row per run: identification, status, exit code, log, then every summary.json metric. */
void writeResultsCsv(const std::vector<RunResult>& runs, const std::string& path);

/** Mean and sample standard deviation over worlds of the per-world mean of the ok runs. */
struct TableCell {
    double mean = 0.0;
    double stddev = 0.0;
    int worlds = 0;  ///< 0: no data
};

/** The paper's Table I for one mode: rows C, T, PL, PT, NOC; one column per planner. */
struct ResultTable {
    std::string mode;
    std::vector<std::string> planners;
    std::vector<std::string> rows;              ///< row labels
    std::vector<std::vector<TableCell>> cells;  ///< [row][planner]
    std::vector<int> best;                      ///< per row: index of the bold planner, -1 if none

    std::string markdown() const;
};

/** Tables for every mode present in the ok runs, planners in the given order (then others). */
std::vector<ResultTable> buildTables(const std::vector<RunResult>& runs,
                                     const std::vector<std::string>& plannerOrder = {});

/**
 * Per world of one mode (rows) and planner: the mean over its ok runs of C %, C as a share of
 * reachable_percent, T s, NOC and static collisions, with the number of runs. Markdown.
 */
std::string perWorldMarkdown(const std::vector<RunResult>& runs, const std::string& mode,
                             const std::vector<std::string>& planners);

/** Coverage-over-time plot per world/mode and a collision timeline per planner/world/mode. */
std::vector<std::string> writePlots(const std::vector<RunResult>& runs,
                                    const std::string& plotDirectory);

/** "daep VERSION COMMIT (build type, compiler; libraries)" of the build that made a run. */
std::string buildDescription(const RunResult& run);

/**
 * table.md's provenance header: the builds that made the runs (flagged when there are several),
 * the hosts, and the span of dates.
 */
std::string provenanceMarkdown(const std::vector<RunResult>& runs);

/** results.csv, table.md and plots/ in DIR from the run directories in DIR/runs; returns the number
 * of runs read. Throws InputError when DIR does not exist or holds no runs. */
std::size_t aggregateBenchmark(const std::string& benchmarkDirectory,
                               const std::vector<std::string>& plannerOrder = {});

}  // namespace daep::eval
