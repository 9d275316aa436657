#pragma once

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3D.h>

#include <Eigen/Core>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "daep/common/Types.h"
#include "daep/mapping/DepthRays.h"
#include "daep/mapping/DepthUnprojection.h"

namespace daep::mapping {

/**
 * Calls onPoint(row, col, worldPoint) for each pixel with a return, row-major, along the
 * frame's DepthRays.
 */
template <typename OnPoint>
void forEachDepthPoint(const mrpt::obs::CObservation3DRangeScan& obs, const SensorFrame& frame,
                       OnPoint onPoint) {
    if (!obs.hasRangeImage) {
        throw std::invalid_argument("depth observation has no range image");
    }
    const auto& image = obs.rangeImage;
    const DepthRays rays(obs);
    const float units = obs.rangeUnits;
    for (int v = 0; v < rays.rows(); ++v) {
        const float kz = rays.up(v);
        const Eigen::Vector3f rowDir = frame.forward + kz * frame.up;
        for (int u = 0; u < rays.cols(); ++u) {
            float d = float(image(v, u)) * units;
            if (d <= 0.0f) {
                continue;
            }
            const float kyu = rays.left(u);
            d = rays.depthOf(d, kyu, kz);
            onPoint(v, u, Eigen::Vector3f(frame.origin + d * (rowDir + kyu * frame.left)));
        }
    }
}

}  // namespace daep::mapping
