// daep-predict-eval: scores the people predictor on real pedestrian tracks (ETH/UCY format).
#include <iomanip>
#include <iostream>
#include <string>

#include "daep/common/AppMain.h"
#include "daep/common/Error.h"
#include "daep/perception/PredictionEval.h"

namespace {

constexpr const char* kUsage =
    "usage: daep-predict-eval TRACKS.txt [--accel-noise Q] [--measurement-sigma S]\n"
    "                         [--observed 8] [--predicted 12] [--step 0.4]\n"
    "Scores the constant-velocity Kalman predictor on tracks in the ETH/UCY format\n"
    "(frame id x y): ADE, FDE and the fraction of true positions inside the predicted\n"
    "95 % ellipse, over Social-GAN windows (a person counts when seen in all frames).\n";

}  // namespace

int main(int argc, char** argv) {
    return daep::runApp([&] {
        std::string path;
        daep::perception::PredictorParams params;
        daep::perception::EvalProtocol protocol;
        for (int i = 1; i < argc; ++i) {
            const std::string arg = argv[i];
            if (arg == "--help" || arg == "-h") {
                std::cout << kUsage;
                return 0;
            }
            const bool hasValue = i + 1 < argc;
            if (arg == "--accel-noise" && hasValue)
                params.accelNoise = daep::parseNumber(arg, argv[++i]);
            else if (arg == "--measurement-sigma" && hasValue)
                params.measurementSigma = daep::parseNumber(arg, argv[++i]);
            else if (arg == "--observed" && hasValue)
                protocol.observed = static_cast<int>(daep::parseNumber(arg, argv[++i]));
            else if (arg == "--predicted" && hasValue)
                protocol.predicted = static_cast<int>(daep::parseNumber(arg, argv[++i]));
            else if (arg == "--step" && hasValue)
                protocol.stepSec = daep::parseNumber(arg, argv[++i]);
            else if (!arg.empty() && arg[0] != '-' && path.empty())
                path = arg;
            else
                throw daep::InputError("unexpected argument '" + arg + "'\n" + kUsage);
        }
        if (path.empty())
            throw daep::InputError(std::string("no tracks file given\n") + kUsage);
        if (protocol.observed < 2 || protocol.predicted < 1)
            throw daep::InputError("--observed must be >= 2 and --predicted >= 1");
        const auto tracks = daep::perception::loadPedestrianTracks(path);
        const auto s = daep::perception::evaluatePredictor(tracks, params, protocol);
        std::cout << path << ": " << s.windows << " person-windows, " << protocol.observed
                  << " observed / " << protocol.predicted << " predicted steps of "
                  << protocol.stepSec << " s\n"
                  << std::fixed << std::setprecision(3) << "ADE=" << s.ade << " FDE=" << s.fde
                  << " coverage95=" << s.coverage << "\n";
        return s.windows > 0 ? 0 : 2;
    });
}
