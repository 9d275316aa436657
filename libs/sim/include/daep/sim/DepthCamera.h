#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

#include "daep/common/Types.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace mrpt::obs {
class CObservation3DRangeScan;
}

namespace daep::world {
class RayCaster;
}

namespace daep::sim {

/**
 * Pinhole depth camera with square pixels: fx = fy from the horizontal FoV; the vertical
 * span of the image follows from the height (86.8 deg at 640 x 480 and 103.2 deg).
 */
struct CameraParams {
    int width = 320;
    int height = 240;
    double hfovRad = 103.2 * M_PI / 180.0;
    double maxRange = 100.0;  ///< farther surfaces return no depth (0 in the image)
    double rateHz = 5.0;
    double noiseSigma = 0.005;                              ///< m, Gaussian on depth
    Eigen::Vector3d mountOffset = Eigen::Vector3d::Zero();  ///< sensor position in the drone frame

    double fx() const;
    double cx() const { return 0.5 * (width - 1); }
    double cy() const { return 0.5 * (height - 1); }
    double vfovRad() const;

    /** Reads and validates [camera]; throws InputError naming the key. */
    static CameraParams fromConfig(const mrpt::config::CConfigFileBase& cfg);
};

/** Renders depth frames by ray casting and packs them as MRPT observations. */
class DepthCamera {
public:
    explicit DepthCamera(CameraParams params);

    const CameraParams& params() const { return params_; }

    /** Pose of the sensor in the world for a drone pose. */
    FlatPose sensorPose(const FlatPose& drone) const;

    /**
     * Fills `obs` with a depth image (range_is_depth, metres along the optical axis) seen from
     * the drone pose, intrinsics, sensorPose relative to the drone, and the timestamp. Noise is
     * drawn from rng. Pixels with no return within maxRange are 0.
     */
    void render(const world::RayCaster& scene, const FlatPose& drone, double timeSec,
                std::mt19937_64& rng, mrpt::obs::CObservation3DRangeScan& obs) const;

    /** Depth image only (row-major, width*height, 0 = no return), for tests and benchmarks. */
    void renderDepth(const world::RayCaster& scene, const FlatPose& drone, std::mt19937_64* rng,
                     std::vector<float>& depth) const;

private:
    /** Calls emit(i, depth) for every pixel i in order, depth 0 for no return. */
    template <typename Emit>
    void forEachDepth(const world::RayCaster& scene, const FlatPose& drone, std::mt19937_64* rng,
                      const Emit& emit) const;

    CameraParams params_;
    std::vector<Eigen::Vector3f> pixelRaysCamera_;  ///< unit rays in the sensor frame (x fwd)
    std::vector<float> depthPerRange_;              ///< depth = range * depthPerRange_[i]
};

}  // namespace daep::sim
