// The ETH/UCY pedestrian-track reader, and the predictor evaluation on what it read.
#include <cstdint>

#include "FuzzSupport.h"
#include "daep/perception/PredictionEval.h"

namespace {
constexpr std::size_t kMaxEvaluatedFrames = 24;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = daep::fuzz::writeScratch(
        "tracks.txt", std::string(reinterpret_cast<const char*>(data), size));
    daep::fuzz::expectOnlyInputErrors([&] {
        const auto tracks = daep::perception::loadPedestrianTracks(path);
        // A few windows exercise the evaluation; more only cost time (Kalman filters under ASan).
        if (tracks.frames.size() <= kMaxEvaluatedFrames)
            daep::perception::evaluatePredictor(tracks, daep::perception::PredictorParams{});
    });
    return 0;
}
