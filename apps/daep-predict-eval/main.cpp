// daep-predict-eval: scores the people predictor on real pedestrian tracks (ETH/UCY format).
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include "daep/common/AppMain.h"
#include "daep/common/CommandLine.h"
#include "daep/common/Error.h"
#include "daep/perception/PredictionEval.h"

namespace {

constexpr const char* kUsage =
    "usage: daep-predict-eval TRACKS.txt [--accel-noise Q] [--measurement-sigma S]\n"
    "                         [--observed 8] [--predicted 12] [--step 0.4]\n"
    "Scores the constant-velocity Kalman predictor on tracks in the ETH/UCY format\n"
    "(frame id x y): ADE, FDE and the fraction of true positions inside the predicted\n"
    "95 % ellipse, over Social-GAN windows (a person counts when seen in all frames).\n"
    "When no window can be scored it prints ADE=n/a FDE=n/a coverage95=n/a and exits 2.\n";

}  // namespace

int main(int argc, char** argv) {
    return daep::runApp([&] {
        std::vector<std::string> path;
        daep::perception::PredictorParams params;
        daep::perception::EvalProtocol protocol;
        daep::CommandLine cli("daep-predict-eval", kUsage);
        cli.number("--accel-noise", params.accelNoise)
            .number("--measurement-sigma", params.measurementSigma)
            .integer("--observed", protocol.observed)
            .integer("--predicted", protocol.predicted)
            .number("--step", protocol.stepSec)
            .positionals(path, 1, 1, "tracks file");
        if (!cli.parse(argc, argv))
            return 0;
        if (protocol.observed < 2 || protocol.predicted < 1)
            throw daep::InputError("--observed must be >= 2 and --predicted >= 1");
        const auto tracks = daep::perception::loadPedestrianTracks(path.front());
        const auto s = daep::perception::evaluatePredictor(tracks, params, protocol);
        std::cout << path.front() << ": " << s.windows << " person-windows, " << protocol.observed
                  << " observed / " << protocol.predicted << " predicted steps of "
                  << protocol.stepSec << " s\n";
        if (s.windows == 0) {
            // Zeros would read as a perfect predictor: say that nothing could be scored.
            std::cout << "ADE=n/a FDE=n/a coverage95=n/a\n";
            std::cerr << "error: " << path.front() << ": nothing scored: no person is seen in "
                      << protocol.observed + protocol.predicted << " consecutive frames\n";
            return 2;
        }
        std::cout << std::fixed << std::setprecision(3) << "ADE=" << s.ade << " FDE=" << s.fde
                  << " coverage95=" << s.coverage << "\n";
        return 0;
    });
}
