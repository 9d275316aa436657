#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "daep/eval/BenchmarkConfig.h"

namespace daep::eval {

struct RunnerOptions {
    std::string outDirectory;   ///< OUT; runs go to OUT/runs/<id>
    std::string exploreBinary;  ///< daep-explore
    int jobs = 1;
    bool retryFailed = false;
    /** Threads kept busy beside the runs (CpuLoad), recorded in each run's run.json. */
    int loadThreads = 0;
    /** Progress bar updated in place (a TTY) or one line per finished run. */
    bool interactive = false;
};

/** What a benchmark invocation did. */
struct RunnerReport {
    std::size_t total = 0;
    std::size_t skipped = 0;  ///< already done (or failed, without --retry-failed)
    std::size_t succeeded = 0;
    std::size_t failed = 0;
    std::size_t failedBefore = 0;  ///< failed in an earlier invocation, not retried
    bool interrupted = false;
};

/**
 * Runs the matrix as separate daep-explore processes, `jobs` at a time. A run whose summary.json
 * exists and whose exit code was 0 is skipped, a failed one re-run only with retryFailed; either
 * runs again when its inputs' digest (RunSpec::inputs) differs from the one it ran with. SIGINT
 * stops launching and forwards the interrupt to the running missions (a second one kills them);
 * interrupted runs stay pending for the next invocation.
 */
class BenchmarkRunner {
public:
    /** `runs`: the checked matrix (with digests); empty: config.expand(), without digests. */
    BenchmarkRunner(BenchmarkConfig config, RunnerOptions options, std::vector<RunSpec> runs = {});

    /** The daep-explore arguments (without the binary) of one run. */
    std::vector<std::string> arguments(const RunSpec& run) const;
    std::string runDirectory(const RunSpec& run) const;
    /** Runs still to do, by the resume rule. */
    std::vector<RunSpec> pendingRuns() const;
    /**
     * Why a run that ran before has to run again: what changed in its parameters or world files
     * since ("[experiment] max_time_s: 30 -> 60"); "" when nothing did or it never ran.
     */
    std::string changeSinceLastRun(const RunSpec& run) const;

    RunnerReport run(std::ostream& progress);

    /** One shell line per pending run (for GNU parallel or a Slurm array); returns the count. */
    std::size_t emitJobs(const std::string& path) const;

private:
    bool isDone(const RunSpec& run) const;
    /** One line per re-run (what changed) and per kept run made by another build. */
    void reportResumeDecisions(std::ostream& out) const;

    BenchmarkConfig config_;
    RunnerOptions options_;
    std::vector<RunSpec> runs_;
};

/** Quotes a word for POSIX sh (single quotes, unless it is plainly safe). */
std::string shellQuote(const std::string& word);

}  // namespace daep::eval
