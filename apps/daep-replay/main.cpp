// daep-replay: maps a recorded trajectory again with another camera or map setting.
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "daep/common/AppMain.h"
#include "daep/common/CommandLine.h"
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
    return daep::runApp([&] {
        std::vector<std::string> positional, overrides;
        daep::CommandLine cli("daep-replay", kUsage);
        cli.repeated("--set", overrides)
            .positionals(positional, 2, 2, "CONFIG.ini and TRAJECTORY.csv");
        if (!cli.parse(argc, argv))
            return 0;
        const auto config = daep::mission::ExperimentConfig::fromFile(positional[0], overrides);
        const auto r = daep::mission::replayTrajectory(config, positional[1]);
        std::cout << std::fixed << std::setprecision(2) << "frames " << r.frames << "  known "
                  << r.knownVolume << " m^3  coverage " << r.coveragePercent << " %\n";
        return 0;
    });
}
