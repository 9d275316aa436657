#pragma once

#include <mrpt/obs/CObservation3DRangeScan.h>

#include <Eigen/Core>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "daep/mapping/DepthRays.h"
#include "daep/mapping/DepthUnprojection.h"

namespace daep::mapping {

/**
 * One image row's pixels as world points along the frame's DepthRays, a pass at a time over
 * arrays (the points' pass vectorizes): x, y, z of every pixel, and whether it had a return
 * (depth > 0; the point of a pixel without one means nothing).
 */
struct DepthRow {
    std::vector<float> x, y, z;
    std::vector<std::uint8_t> returned;

    void compute(const std::uint16_t* pixels, float units, const DepthRays& rays, int row,
                 const SensorFrame& frame) {
        const std::size_t n = std::size_t(rays.cols());
        x.resize(n);
        y.resize(n);
        z.resize(n);
        returned.resize(n);
        const float* left = rays.lefts();
        const float kz = rays.up(row);
        for (std::size_t u = 0; u < n; ++u) {
            x[u] = float(pixels[u]) * units;
            returned[u] = x[u] > 0.0f;
        }
        if (!rays.rangeIsDepth())
            for (std::size_t u = 0; u < n; ++u)
                x[u] = rays.depthOf(x[u], left[u], kz);
        const Eigen::Vector3f rowDir = frame.forward + kz * frame.up;
        const Eigen::Vector3f& o = frame.origin;
        const Eigen::Vector3f& l = frame.left;
        for (std::size_t u = 0; u < n; ++u) {
            const float d = x[u], kyu = left[u];
            x[u] = o.x() + d * (rowDir.x() + kyu * l.x());
            y[u] = o.y() + d * (rowDir.y() + kyu * l.y());
            z[u] = o.z() + d * (rowDir.z() + kyu * l.z());
        }
    }
};

/** Calls onRow(row, depthRow) for each image row, top to bottom. */
template <typename OnRow>
void forEachDepthRow(const mrpt::obs::CObservation3DRangeScan& obs, const SensorFrame& frame,
                     OnRow onRow) {
    if (!obs.hasRangeImage) {
        throw std::invalid_argument("depth observation has no range image");
    }
    const DepthRays rays(obs);
    DepthRow row;
    for (int v = 0; v < rays.rows(); ++v) {
        row.compute(&obs.rangeImage(v, 0), obs.rangeUnits, rays, v, frame);
        onRow(v, row);
    }
}

}  // namespace daep::mapping
