// daep-detect-eval: scores the people detector and tracker on a recorded simulated run.
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "daep/common/AppMain.h"
#include "daep/common/CommandLine.h"
#include "daep/common/Error.h"
#include "daep/eval/Statistics.h"
#include "daep/mission/DetectionEval.h"
#include "daep/mission/ExperimentConfig.h"

namespace {

constexpr const char* kUsage =
    "usage: daep-detect-eval CONFIG.ini RUN.rawlog [--set section.key=value ...]\n"
    "                        [--range 5] [--min-visible 0.5] [--match 0.75] [--csv FILE]\n"
    "Replays RUN.rawlog (recorded with output.rawlog = true: depth frames, DRONE_POSE and the\n"
    "true PERSON_<i> poses) through the map, the people detector and the tracker with\n"
    "CONFIG's settings, and scores every frame's detections against the true people:\n"
    "recall over unoccluded people within --range m (at least --min-visible of the body's\n"
    "pixels return the body), precision over detections within --range m (a detection within\n"
    "--match m of a true body centre is a hit), and the position error of the hits.\n"
    "--csv writes one row per frame. The last line is\n"
    "recall=<r> precision=<p> error_mean=<m> error_p95=<m>.\n";

void print(const daep::mission::DetectionScore& s) {
    using daep::eval::mean;
    using daep::eval::percentile;
    std::cout << std::fixed << std::setprecision(3) << "frames " << s.frames << "\n"
              << "unoccluded people in range " << s.eligible << ", detected " << s.found
              << " (occluded or cut by the image border, not scored: " << s.occludedOrTruncated
              << ")\n"
              << "detections in range " << s.detections << ", true " << s.truePositives
              << ", false " << s.falsePositives << "\n"
              << "position error mean " << mean(s.errors) << " m, median "
              << percentile(s.errors, 50) << " m, p95 " << percentile(s.errors, 95) << " m\n"
              << "confirmed tracks in range " << s.confirmedTracks << ", on a person "
              << s.confirmedTrackMatches << " (" << s.trackPrecision() << ")\n"
              << "recall=" << s.recall() << " precision=" << s.precision()
              << " error_mean=" << mean(s.errors) << " error_p95=" << percentile(s.errors, 95)
              << "\n";
}

}  // namespace

int main(int argc, char** argv) {
    return daep::runApp([&] {
        std::vector<std::string> positional, overrides;
        daep::mission::DetectionEvalOptions options;
        std::string csvPath;
        daep::CommandLine cli("daep-detect-eval", kUsage);
        cli.repeated("--set", overrides)
            .number("--range", options.range)
            .number("--min-visible", options.minVisibleFraction)
            .number("--match", options.matchDistance)
            .option("--csv", csvPath)
            .positionals(positional, 2, 2, "CONFIG.ini and RUN.rawlog");
        if (!cli.parse(argc, argv))
            return 0;
        const auto config = daep::mission::ExperimentConfig::fromFile(positional[0], overrides);
        std::ofstream csv;
        if (!csvPath.empty()) {
            csv.open(csvPath);
            if (!csv)
                throw daep::InputError(csvPath + ": cannot write");
        }
        const auto score = daep::mission::evaluateDetection(config, positional[1], options,
                                                            csvPath.empty() ? nullptr : &csv);
        print(score);
        return 0;
    });
}
