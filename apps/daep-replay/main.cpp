// daep-replay: maps a recorded trajectory again with another camera or map setting.
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "daep/common/AppMain.h"
#include "daep/common/Error.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/Replay.h"

namespace {
constexpr const char* kUsage =
    "usage: daep-replay CONFIG.ini TRAJECTORY.csv [--set section.key=value ...]\n"
    "Flies TRAJECTORY.csv (a run's trajectory.csv) again in CONFIG's world with CONFIG's\n"
    "camera and map settings and prints the coverage reached.\n";
}

int main(int argc, char** argv) {
    std::vector<std::string> positional, overrides;
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--help" || arg == "-h") {
            std::cout << kUsage;
            return 0;
        }
        if (arg == "--set" && i + 1 < argc)
            overrides.push_back(argv[++i]);
        else if (!arg.empty() && arg[0] == '-') {
            std::cerr << "error: unknown option " << arg << "\n" << kUsage;
            return 1;
        } else
            positional.push_back(arg);
    }
    if (positional.size() != 2) {
        std::cerr << kUsage;
        return 1;
    }
    return daep::runApp([&] {
        const auto config = daep::mission::ExperimentConfig::fromFile(positional[0], overrides);
        const auto r = daep::mission::replayTrajectory(config, positional[1]);
        std::cout << std::fixed << std::setprecision(2) << "frames " << r.frames << "  known "
                  << r.knownVolume << " m^3  coverage " << r.coveragePercent << " %\n";
        return 0;
    });
}
