#pragma once

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3D.h>

#include <Eigen/Core>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "daep/common/Types.h"
#include "daep/mapping/DepthUnprojection.h"

namespace daep::mapping {

/**
 * Calls onPoint(row, col, worldPoint) for each pixel with a return, row-major. Uses MRPT's
 * pinhole model for range images: depth d along +X, y = (cx - col) d / fx,
 * z = (cy - row) d / fy.
 */
template <typename OnPoint>
void forEachDepthPoint(const mrpt::obs::CObservation3DRangeScan& obs, const SensorFrame& frame,
                       OnPoint onPoint) {
    if (!obs.hasRangeImage) {
        throw std::invalid_argument("depth observation has no range image");
    }
    const auto& image = obs.rangeImage;
    const int rows = int(image.rows());
    const int cols = int(image.cols());
    const auto& cam = obs.cameraParams;
    const float fx = float(cam.fx()), fy = float(cam.fy());
    const float cx = float(cam.cx()), cy = float(cam.cy());
    const float units = obs.rangeUnits;

    std::vector<float> ky(static_cast<std::size_t>(cols));
    for (int u = 0; u < cols; ++u) {
        ky[std::size_t(u)] = (cx - float(u)) / fx;
    }
    for (int v = 0; v < rows; ++v) {
        const float kz = (cy - float(v)) / fy;
        const Eigen::Vector3f rowDir = frame.forward + kz * frame.up;
        for (int u = 0; u < cols; ++u) {
            float d = float(image(v, u)) * units;
            if (d <= 0.0f) {
                continue;
            }
            const float kyu = ky[std::size_t(u)];
            if (!obs.range_is_depth) {
                d /= std::sqrt(1.0f + kyu * kyu + kz * kz);
            }
            onPoint(v, u, Eigen::Vector3f(frame.origin + d * (rowDir + kyu * frame.left)));
        }
    }
}

}  // namespace daep::mapping
