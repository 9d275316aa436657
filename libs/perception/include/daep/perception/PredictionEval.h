#pragma once

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "daep/perception/PersonTrack.h"

namespace daep::perception {

/** Pedestrian tracks in the ETH/UCY text format: `frame id x y` per line, metres. */
struct PedestrianTracks {
    std::vector<int> frames;                                ///< sorted, unique
    std::map<int, std::map<int, Eigen::Vector2d>> byFrame;  ///< frame -> id -> position
};

/** Loads a tracks file; throws InputError naming file:line for malformed lines. */
PedestrianTracks loadPedestrianTracks(const std::string& path);

struct EvalProtocol {
    int observed = 8;                        ///< steps the filter sees
    int predicted = 12;                      ///< steps it predicts
    double stepSec = 0.4;                    ///< time between consecutive frames of the file
    double ellipseChi2 = 5.991464547107979;  ///< chi-square, 2 dof, 95 %
};

struct PredictionScore {
    double ade = 0.0;         ///< mean displacement error over all predicted steps, m
    double fde = 0.0;         ///< mean displacement error at the last step, m
    double coverage = 0.0;    ///< fraction of true positions inside the predicted ellipse
    std::size_t windows = 0;  ///< person-windows evaluated
};

/**
 * Social-GAN windowing: every run of observed+predicted consecutive frames (stride one frame);
 * a person counts when present in all of them. The filter sees the first `observed`
 * positions, then predicts the rest.
 */
PredictionScore evaluatePredictor(const PedestrianTracks& tracks, const PredictorParams& params,
                                  const EvalProtocol& protocol = {});

}  // namespace daep::perception
