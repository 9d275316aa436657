#include "daep/mission/ExploreApp.h"

#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

#include "Outputs.h"
#include "SceneExport.h"
#include "daep/common/AppMain.h"
#include "daep/common/CommandLine.h"
#include "daep/common/Error.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/Mission.h"
#include "daep/mission/RawlogMission.h"
#include "daep/planning/Planner.h"
#include "daep/planning/PlannerRegistry.h"
#include "daep/world/WorldSpec.h"

namespace daep::mission {
namespace {

Mission* g_running = nullptr;
RawlogMission* g_replaying = nullptr;

extern "C" void onInterrupt(int) {
    if (g_running)
        g_running->requestStop();
    if (g_replaying)
        g_replaying->requestStop();
}

/** Runs a Mission or RawlogMission with Ctrl-C asking it to stop. */
template <typename M>
eval::RunSummary runInterruptible(M& mission, M*& registered) {
    registered = &mission;
    const auto previous = std::signal(SIGINT, onInterrupt);
    try {
        const eval::RunSummary summary = mission.run();
        std::signal(SIGINT, previous);
        registered = nullptr;
        return summary;
    } catch (...) {
        std::signal(SIGINT, previous);
        registered = nullptr;
        throw;
    }
}

std::string joined(const std::vector<std::string>& v) {
    std::string out;
    for (const auto& s : v)
        out += (out.empty() ? "" : ", ") + s;
    return out;
}

/** "planner daep, world cafe, mode dynamic, start 0, seed 1": which run the figures are of. */
std::string runLabels(const eval::RunSummary& s) {
    std::string text;
    for (const char* key : {"planner", "world", "mode", "start", "seed", "rawlog"})
        if (const auto it = s.labels.find(key); it != s.labels.end())
            text += (text.empty() ? "" : ", ") + std::string(key) + " " + it->second;
    return text;
}

void printSummary(const eval::RunSummary& s, const std::string& dir) {
    std::cout << std::fixed << std::setprecision(2) << "\n== Result (" << dir << ")\n"
              << "  run                 " << runLabels(s) << "\n"
              << "  coverage C          " << s.coveragePercent << " %  (" << s.knownVolume << " of "
              << s.boxVolume << " m^3)\n";
    if (s.reachablePercent)
        std::cout << "  reachable at most   " << *s.reachablePercent << " %\n";
    std::cout << "  exploration time T  " << s.explorationTime << " s\n"
              << "  path length PL      " << s.pathLength << " m\n"
              << "  planning time PT    " << s.planningTime << " s  (median " << s.planMsMedian
              << " ms, p95 " << s.planMsP95 << " ms per call)\n"
              << "  collisions NOC      " << s.collisions << "  (static: " << s.staticCollisions
              << ")\n"
              << "  plans               " << s.iterations << "\n"
              << "  finished            " << (s.finished ? "yes" : "no") << " ("
              << s.endReason.text() << ")\n"
              << "  wall time           " << s.wallTime << " s  ("
              << (s.wallTime > 0 ? (s.explorationTime / s.wallTime) : 0.0) << " x real time)\n";
}

/** Every file a run writes to its output folder. */
const char* const kRunOutputs[] = {"summary.json",
                                   "timeseries.csv",
                                   "trajectory.csv",
                                   "plans.csv",
                                   "collisions.csv",
                                   "timing.json",
                                   "config.ini",
                                   "map.bt",
                                   "people.csv",
                                   "people_truth.csv",
                                   "run.rawlog",
                                   "scene.3Dscene",
                                   "scene_perspective.png",
                                   "scene_top.png",
                                   "trajectory_tum.txt"};

/**
 * A reused output folder must not mix runs: the files an earlier run wrote there go before this
 * one starts (other files in the folder, such as daep-benchmark's run.log, stay).
 */
void removeEarlierOutputs(const std::string& dir) {
    for (const char* file : kRunOutputs) {
        std::error_code ec;
        std::filesystem::remove(std::filesystem::path(dir) / file, ec);
        if (ec)
            throw std::runtime_error(std::string("cannot remove the earlier ") + file + " in " +
                                     dir + ": " + ec.message());
    }
}

}  // namespace

std::string ExploreApp::usage() {
    return "usage: daep-explore CONFIG.ini [--set section.key=value ...] [--out DIR] [--quiet]\n"
           "       daep-explore --render-scene RUN_DIR [--set section.key=value ...]\n"
           "       daep-explore --list-worlds | --list-planners | --help\n"
           "\n"
           "Runs one exploration mission in the built-in simulator and writes summary.json,\n"
           "timeseries.csv, trajectory.csv, plans.csv, collisions.csv, timing.json, config.ini\n"
           "and map.bt to DIR (default: out/<CONFIG name>). With experiment.source=rawlog it\n"
           "replays experiment.rawlog_file instead: maps it and runs the planner on it.\n"
           "--render-scene renders RUN_DIR/scene.3Dscene of a run made with\n"
           "output.render_png = false to its two PNGs, at the size in RUN_DIR/config.ini.\n";
}

bool ExploreApp::initialize(int argc, const char* const* argv) {
    invocation_ = runProvenance(argc, argv);
    bool listWorlds = false, listPlanners = false;
    std::vector<std::string> config;
    CommandLine cli("daep-explore", usage());
    cli.repeated("--set", overrides_)
        .option("--out", outputDir_)
        .option("--render-scene", renderSceneDir_)
        .flag("-q,--quiet", quiet_)
        .flag("--list-worlds", listWorlds)
        .flag("--list-planners", listPlanners)
        .positionals(config, 0, 1, "config file");
    if (!cli.parse(argc, argv))
        return false;
    if (listWorlds)
        std::cout << joined(world::builtinWorldNames()) << "\n";
    if (listPlanners)
        std::cout << joined(planning::plannerNames()) << "\n";
    if (listWorlds || listPlanners)
        return false;
    if (!renderSceneDir_.empty()) {
        if (!config.empty() || !outputDir_.empty())
            throw InputError(
                "daep-explore: --render-scene takes the run's folder alone, no "
                "config file or --out");
        return true;
    }
    if (config.empty())
        throw InputError("daep-explore: no config file given (see daep-explore --help)");
    configPath_ = config.front();
    if (outputDir_.empty())
        outputDir_ = "out/" + std::filesystem::path(configPath_).stem().string();
    return true;
}

int ExploreApp::renderScene() const {
    return runApp([&] {
        const ExperimentConfig config =
            ExperimentConfig::fromFile(renderSceneDir_ + "/config.ini", overrides_);
        const OutputParams output = loadOutputParams(config.config());
        renderSceneFile(renderSceneDir_, output.pngWidth, output.pngHeight);
        if (!quiet_)
            std::cout << "wrote " << renderSceneDir_ << "/scene_perspective.png and "
                      << renderSceneDir_ << "/scene_top.png\n";
        return 0;
    });
}

int ExploreApp::run() {
    if (!renderSceneDir_.empty())
        return renderScene();
    return runApp([&] {
        ExperimentConfig config = ExperimentConfig::fromFile(configPath_, overrides_);
        config.setInvocation(invocation_);
        if (!quiet_)
            std::cout << "# Effective parameters (" << configPath_ << ")\n" << config.dump();
        std::ostream* log = quiet_ ? nullptr : &std::cout;
        removeEarlierOutputs(outputDir_);
        if (RawlogMission::selectedBy(config)) {
            RawlogMission replay(config, outputDir_, log);
            std::ofstream(outputDir_ + "/config.ini") << config.dump();
            summary_ = runInterruptible(replay, g_replaying);
        } else {
            Mission mission(config, outputDir_, log);
            std::ofstream(outputDir_ + "/config.ini") << config.dump();
            summary_ = runInterruptible(mission, g_running);
        }
        printSummary(summary_, outputDir_);
        return summary_.endReason.kind == eval::EndReason::Kind::Interrupted ? 130 : 0;
    });
}

}  // namespace daep::mission
