#include "daep/sim/DepthCamera.h"

#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3D.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "DepthQuantise.h"
#include "GaussianSampler.h"
#include "daep/common/ConfigChecks.h"
#include "daep/common/Error.h"
#include "daep/world/RayCaster.h"

namespace daep::sim {
namespace {

constexpr const char* kSensorLabel = "DEPTH_CAM";
constexpr double kRangeUnits = 1e-3;  ///< 1 mm steps: uint16 then holds depths up to 65.5 m
/// Headroom above maxRange for noisy depths before the uint16 saturates.
constexpr double kNoiseHeadroom = 1.05;
constexpr float kMinDepth = 1e-4f;

void validate(const CameraParams& p) {
    if (p.width <= 0 || p.height <= 0) {
        throw std::invalid_argument("DepthCamera: image size must be positive");
    }
    if (!(p.hfovRad > 0.0 && p.hfovRad < M_PI)) {
        throw std::invalid_argument("DepthCamera: horizontal FoV must be in (0, 180) deg");
    }
    if (!(p.maxRange > 0.0) || !(p.noiseSigma >= 0.0)) {
        throw std::invalid_argument("DepthCamera: maxRange must be > 0 and noiseSigma >= 0");
    }
}

/// 1 mm, or coarser when maxRange (plus noise) would not fit into a uint16.
float rangeUnitsFor(double maxRange) {
    const double needed = maxRange * kNoiseHeadroom / std::numeric_limits<uint16_t>::max();
    return static_cast<float>(std::max(kRangeUnits, needed));
}

mrpt::img::TCamera intrinsics(const CameraParams& p) {
    mrpt::img::TCamera cam;
    cam.ncols = static_cast<uint32_t>(p.width);
    cam.nrows = static_cast<uint32_t>(p.height);
    cam.setIntrinsicParamsFromValues(p.fx(), p.fx(), p.cx(), p.cy());
    cam.dist.fill(0.0);
    return cam;
}

}  // namespace

double CameraParams::fx() const {
    return 0.5 * width / std::tan(0.5 * hfovRad);
}

double CameraParams::vfovRad() const {
    return 2.0 * std::atan(0.5 * height / fx());
}

DepthCamera::DepthCamera(CameraParams params) : params_(std::move(params)) {
    validate(params_);
    const double f = params_.fx();
    const std::size_t n = static_cast<std::size_t>(params_.width) * params_.height;
    pixelRaysCamera_.reserve(n);
    depthPerRange_.reserve(n);
    for (int v = 0; v < params_.height; ++v) {
        for (int u = 0; u < params_.width; ++u) {
            const Eigen::Vector3d ray(1.0, -(u - params_.cx()) / f, -(v - params_.cy()) / f);
            const Eigen::Vector3d unit = ray.normalized();
            pixelRaysCamera_.push_back(unit.cast<float>());
            depthPerRange_.push_back(static_cast<float>(unit.x()));
        }
    }
}

FlatPose DepthCamera::sensorPose(const FlatPose& drone) const {
    const double c = std::cos(drone.yaw);
    const double s = std::sin(drone.yaw);
    const Eigen::Vector3d& m = params_.mountOffset;
    FlatPose sensor;
    sensor.position =
        drone.position + Eigen::Vector3d(c * m.x() - s * m.y(), s * m.x() + c * m.y(), m.z());
    sensor.yaw = drone.yaw;
    return sensor;
}

template <typename Emit>
void DepthCamera::forEachDepth(const world::RayCaster& scene, const FlatPose& drone,
                               std::mt19937_64* rng, const Emit& emit) const {
    // Per-thread scratch: render() is const and may run on several threads at once.
    thread_local std::vector<float> ranges;

    const FlatPose sensor = sensorPose(drone);
    const world::RayCaster::YawTurn turn{static_cast<float>(std::cos(sensor.yaw)),
                                         static_cast<float>(std::sin(sensor.yaw))};
    const std::size_t n = pixelRaysCamera_.size();
    scene.castRays(sensor.position.cast<float>(), pixelRaysCamera_, turn,
                   static_cast<float>(params_.maxRange), ranges);

    const bool noisy = rng != nullptr && params_.noiseSigma > 0.0;
    const GaussianSampler& normal = standardNormal();
    const double sigma = params_.noiseSigma;
    SplitMix64 frameRng(noisy ? (*rng)() : 0);
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(ranges[i])) {
            emit(i, 0.0f);
            continue;
        }
        const float depth = ranges[i] * depthPerRange_[i];
        // Noise must not turn a return into the "no return" value 0.
        emit(i, noisy ? std::max(depth + static_cast<float>(sigma * normal(frameRng)), kMinDepth)
                      : depth);
    }
}

void DepthCamera::renderDepth(const world::RayCaster& scene, const FlatPose& drone,
                              std::mt19937_64* rng, std::vector<float>& depth) const {
    depth.resize(pixelRaysCamera_.size());
    forEachDepth(scene, drone, rng, [&depth](std::size_t i, float d) { depth[i] = d; });
}

void DepthCamera::render(const world::RayCaster& scene, const FlatPose& drone, double timeSec,
                         std::mt19937_64& rng, mrpt::obs::CObservation3DRangeScan& obs) const {
    const float units = rangeUnitsFor(params_.maxRange);
    obs.rangeImage_setSize(params_.height, params_.width);
    uint16_t* pixels = obs.rangeImage.data();
    forEachDepth(scene, drone, &rng,
                 [pixels, units](std::size_t i, float d) { pixels[i] = quantiseDepth(d, units); });
    obs.hasRangeImage = true;
    obs.range_is_depth = true;
    obs.rangeUnits = units;
    obs.hasPoints3D = false;
    obs.hasIntensityImage = false;
    obs.hasConfidenceImage = false;
    obs.cameraParams = intrinsics(params_);
    obs.cameraParamsIntensity = obs.cameraParams;
    obs.maxRange = static_cast<float>(params_.maxRange);
    obs.stdError = static_cast<float>(params_.noiseSigma);
    const Eigen::Vector3d& m = params_.mountOffset;
    obs.sensorPose = mrpt::poses::CPose3D(m.x(), m.y(), m.z(), 0.0, 0.0, 0.0);
    obs.timestamp = mrpt::Clock::fromDouble(timeSec);
    obs.sensorLabel = kSensorLabel;
}

CameraParams CameraParams::fromConfig(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "camera");
    CameraParams p;
    p.width = requireIntAtLeast(r, "width", 2);
    p.height = requireIntAtLeast(r, "height", 2);
    p.hfovRad = requireBetween(r, "hfov_deg", 0.0, 180.0) * M_PI / 180.0;
    p.maxRange = requirePositive(r, "max_range");
    p.rateHz = requirePositive(r, "rate_hz");
    p.noiseSigma = requireNonNegative(r, "noise_sigma");
    return p;
}

}  // namespace daep::sim
