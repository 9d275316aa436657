#pragma once

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3D.h>

#include <cmath>
#include <cstdint>

namespace daep::mapping::test {

/**
 * A depth camera frame (range_is_depth), 90 degrees wide, filled with `depth` metres everywhere
 * (0: no pixel returns), the camera at `sensorPose` on the drone.
 */
inline mrpt::obs::CObservation3DRangeScan depthFrame(
    int width, int height, double depth,
    const mrpt::poses::CPose3D& sensorPose = mrpt::poses::CPose3D()) {
    mrpt::obs::CObservation3DRangeScan obs;
    obs.hasRangeImage = true;
    obs.range_is_depth = true;
    obs.rangeUnits = 0.001f;
    obs.rangeImage_setSize(height, width);
    obs.rangeImage.fill(std::uint16_t(std::lround(depth / obs.rangeUnits)));
    obs.cameraParams.ncols = std::uint32_t(width);
    obs.cameraParams.nrows = std::uint32_t(height);
    const double f = 0.5 * width;
    obs.cameraParams.setIntrinsicParamsFromValues(f, f, 0.5 * (width - 1), 0.5 * (height - 1));
    obs.sensorPose = sensorPose;
    return obs;
}

}  // namespace daep::mapping::test
