#include "daep/perception/PredictionEval.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "daep/common/Error.h"

namespace daep::perception {

namespace {

/** Frames and ids are written as floats ("780.0"); they must be integers that fit an int. */
bool isIntegral(double value) {
    return std::abs(value) <= std::numeric_limits<int>::max() && value == std::floor(value);
}

}  // namespace

PedestrianTracks loadPedestrianTracks(const std::string& path) {
    std::ifstream in(path);
    if (!in)
        throw InputError(path + ": cannot open file");
    PedestrianTracks tracks;
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        if (line.find_first_not_of(" \t\r") == std::string::npos)
            continue;
        std::istringstream cells(line);
        double frame = 0, id = 0, x = 0, y = 0;
        if (!(cells >> frame >> id >> x >> y))
            throw InputError(path + ":" + std::to_string(lineNo) +
                             ": expected 'frame id x y', got '" + line + "'");
        if (!isIntegral(frame) || !isIntegral(id))
            throw InputError(path + ":" + std::to_string(lineNo) +
                             ": frame and id must be integers, got '" + line + "'");
        tracks.byFrame[static_cast<int>(frame)][static_cast<int>(id)] = {x, y};
    }
    if (tracks.byFrame.empty())
        throw InputError(path + ": no tracks");
    for (const auto& entry : tracks.byFrame)
        tracks.frames.push_back(entry.first);
    return tracks;
}

namespace {

/** Ids present in every frame of frames[first, first + count). */
std::vector<int> personsInAllFrames(const PedestrianTracks& tracks, std::size_t first,
                                    std::size_t count) {
    std::vector<int> ids;
    for (const auto& [id, pos] : tracks.byFrame.at(tracks.frames[first])) {
        bool everywhere = true;
        for (std::size_t k = 1; k < count && everywhere; ++k)
            everywhere = tracks.byFrame.at(tracks.frames[first + k]).count(id) > 0;
        if (everywhere)
            ids.push_back(id);
    }
    return ids;
}

}  // namespace

PredictionScore evaluatePredictor(const PedestrianTracks& tracks, const PredictorParams& params,
                                  const EvalProtocol& protocol) {
    const std::size_t window = static_cast<std::size_t>(protocol.observed + protocol.predicted);
    PredictionScore score;
    double sumAde = 0, sumFde = 0;
    std::size_t inside = 0, predictions = 0;
    for (std::size_t first = 0; first + window <= tracks.frames.size(); ++first) {
        for (const int id : personsInAllFrames(tracks, first, window)) {
            const auto pos = [&](std::size_t k) {
                return tracks.byFrame.at(tracks.frames[first + k]).at(id);
            };
            PersonTrack track(params, 0.0, pos(0));
            for (int k = 1; k < protocol.observed; ++k)
                track.update(k * protocol.stepSec, pos(k));
            double ade = 0, fde = 0;
            for (int k = protocol.observed; k < static_cast<int>(window); ++k) {
                const PositionPrediction p = track.predict(k * protocol.stepSec);
                const Eigen::Vector2d err = pos(k) - p.mean;
                ade += err.norm();
                fde = err.norm();
                inside += err.dot(p.covariance.ldlt().solve(err)) <= protocol.ellipseChi2;
                ++predictions;
            }
            sumAde += ade / protocol.predicted;
            sumFde += fde;
            ++score.windows;
        }
    }
    if (score.windows > 0) {
        score.ade = sumAde / score.windows;
        score.fde = sumFde / score.windows;
        score.coverage = double(inside) / double(predictions);
    }
    return score;
}

}  // namespace daep::perception
