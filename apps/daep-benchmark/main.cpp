// daep-benchmark: runs planners x worlds x modes x starts x repetitions as daep-explore
// processes, resumably, and aggregates them into results.csv, table.md and plots.
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "daep/common/AppMain.h"
#include "daep/common/CommandLine.h"
#include "daep/common/Config.h"
#include "daep/common/Error.h"
#include "daep/eval/BenchmarkResults.h"
#include "daep/eval/BenchmarkRunner.h"
#include "daep/mission/BenchmarkCheck.h"

namespace fs = std::filesystem;

namespace {

const char* kUsage =
    "usage: daep-benchmark CONFIG.ini [--jobs N] [--out DIR] [--set section.key=value ...]\n"
    "                      [--retry-failed] [--load N] [--explore PATH] [--emit-jobs FILE]\n"
    "       daep-benchmark --aggregate DIR\n"
    "Runs every planner x world x mode x start x repetition of CONFIG.ini as a daep-explore\n"
    "process (N at a time, default: number of CPUs) into DIR/runs/<run>/, skipping runs done\n"
    "before, then writes DIR/results.csv, DIR/table.md and DIR/plots/*.png.\n"
    "  --set benchmark.key=v   override a [benchmark] key; other section.key=v go to every run\n"
    "  --retry-failed          run failed runs again (by default they are kept as failed)\n"
    "  --load N                keep N more threads busy while the runs go (a loaded machine,\n"
    "                          for planning_time = measured); recorded in each run.json\n"
    "  --explore PATH          the daep-explore binary (default: next to this one)\n"
    "  --emit-jobs FILE        write one shell command per pending run and exit (for GNU\n"
    "                          parallel or a Slurm array); aggregate later with --aggregate\n"
    "  --aggregate DIR         rebuild results.csv, table.md and plots from DIR/runs/*\n"
    "Exit: 0 all runs ok, 1 bad input, 2 a run failed or an error, 130 interrupted.\n";

struct Options {
    std::string config, out, explore, emitJobs, aggregate;
    std::vector<std::string> sets;
    int jobs = 0;
    int load = 0;
    bool retryFailed = false;
};

/** An option's integer in [lo, hi], or an error naming the option. */
int parseCount(const std::string& option, const std::string& text, int lo, int hi) {
    std::size_t used = 0;
    int n = 0;
    try {
        n = std::stoi(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (text.empty() || used != text.size() || n < lo || n > hi)
        throw daep::InputError(option + ": '" + text + "' is not an integer from " +
                               std::to_string(lo) + " to " + std::to_string(hi));
    return n;
}

/** The options, or nullopt when there is nothing to run (--help, --version). */
std::optional<Options> parseArguments(int argc, char** argv) {
    Options o;
    std::vector<std::string> config;
    daep::CommandLine cli("daep-benchmark", kUsage);
    cli.option("-j,--jobs",
               [&o](const std::string& text) { o.jobs = parseCount("--jobs", text, 1, 4096); })
        .option("--load",
                [&o](const std::string& text) { o.load = parseCount("--load", text, 0, 1024); })
        .option("--out", o.out)
        .repeated("--set", o.sets)
        .option("--explore", o.explore)
        .option("--emit-jobs", o.emitJobs)
        .option("--aggregate", o.aggregate)
        .flag("--retry-failed", o.retryFailed)
        .positionals(config, 0, 1, "benchmark config");
    if (!cli.parse(argc, argv))
        return std::nullopt;
    if (!config.empty())
        o.config = daep::resolveDataPath(config.front());
    if (o.aggregate.empty() && o.config.empty())
        throw daep::InputError(
            "daep-benchmark: no benchmark config given (see daep-benchmark --help)");
    if (!o.aggregate.empty() && !o.config.empty())
        throw daep::InputError("--aggregate DIR takes no config");
    return o;
}

/** daep-explore of the same build tree (apps/daep-explore/) or installed alongside. */
std::string findExplore() {
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (ec)
        throw daep::InputError("cannot locate daep-explore; pass --explore PATH");
    for (const auto& candidate :
         {self.parent_path().parent_path() / "daep-explore" / "daep-explore",
          self.parent_path() / "daep-explore"})
        if (fs::exists(candidate))
            return candidate.string();
    throw daep::InputError("no daep-explore next to " + self.string() + "; pass --explore PATH");
}

int aggregate(const std::string& dir, const std::vector<std::string>& planners) {
    const auto runs = daep::eval::aggregateBenchmark(dir, planners);
    std::cout << "aggregated " << runs << " runs: " << (fs::path(dir) / "results.csv").string()
              << ", " << (fs::path(dir) / "table.md").string() << ", "
              << (fs::path(dir) / "plots").string() << "/\n";
    return 0;
}

int benchmark(const Options& o) {
    const auto config = daep::eval::loadBenchmarkConfig(o.config, o.sets);
    auto runs = daep::mission::checkBenchmark(config);  // before anything is launched
    daep::eval::RunnerOptions ro;
    ro.outDirectory = o.out.empty() ? "benchmark-" + fs::path(o.config).stem().string() : o.out;
    ro.exploreBinary = o.explore.empty() ? findExplore() : o.explore;
    if (!fs::exists(ro.exploreBinary))
        throw daep::InputError("--explore: no such file " + ro.exploreBinary);
    const unsigned cpus = std::thread::hardware_concurrency();
    ro.jobs = o.jobs > 0 ? o.jobs : static_cast<int>(cpus ? cpus : 1);
    ro.retryFailed = o.retryFailed;
    ro.loadThreads = o.load;
    ro.interactive = ::isatty(STDOUT_FILENO) != 0;
    fs::create_directories(ro.outDirectory);
    daep::eval::BenchmarkRunner runner(config, ro, std::move(runs));

    if (!o.emitJobs.empty()) {
        const auto n = runner.emitJobs(o.emitJobs);
        std::cout << "wrote " << n << " commands to " << o.emitJobs << "; after running them: "
                  << "daep-benchmark --aggregate " << ro.outDirectory << "\n";
        return 0;
    }
    std::cout << config.expand().size() << " runs (" << config.planners.size() << " planners x "
              << config.worlds.size() << " worlds x " << config.modes.size() << " modes x "
              << config.starts.size() << " starts x " << config.repetitions << " repetitions), "
              << ro.jobs << " at a time"
              << (ro.loadThreads > 0 ? " beside " + std::to_string(ro.loadThreads) +
                                           " busy thread" + (ro.loadThreads == 1 ? "" : "s")
                                     : "")
              << ", into " << ro.outDirectory << std::endl;
    const auto report = runner.run(std::cout);
    aggregate(ro.outDirectory, config.planners);
    if (report.interrupted) {
        std::cout << "interrupted; run the same command again to resume\n";
        return 130;
    }
    std::cout << report.succeeded << " runs ok, " << report.failed << " failed, " << report.skipped
              << " skipped (done before";
    if (report.failedBefore > 0)
        std::cout << "; " << report.failedBefore << " of them failed, see results.csv";
    std::cout << ")\n";
    return report.failed + report.failedBefore > 0 ? 2 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    return daep::runApp([&] {
        const auto o = parseArguments(argc, argv);
        if (!o)
            return 0;
        return o->aggregate.empty() ? benchmark(*o) : aggregate(o->aggregate, {});
    });
}
