#include <cmath>
#include <cstdint>

#include <algorithm>
#include <stdexcept>

#include "DepthPixels.h"
#include "MapImpl.h"
#include "PeopleBuckets.h"
#include "daep/mapping/DepthUnprojection.h"

namespace daep::mapping {
namespace {

constexpr std::uint64_t kNoKey = ~std::uint64_t(0);

}  // namespace

SensorFrame sensorFrameInWorld(const mrpt::obs::CObservation3DRangeScan& obs,
                               const FlatPose& robot) {
    const mrpt::poses::CPose3D robotPose(robot.position.x(), robot.position.y(), robot.position.z(),
                                         robot.yaw, 0.0, 0.0);
    const mrpt::poses::CPose3D sensor = robotPose + obs.sensorPose;
    const auto& r = sensor.getRotationMatrix();
    const auto column = [&r](int c) {
        return Eigen::Vector3f(float(r(0, c)), float(r(1, c)), float(r(2, c)));
    };
    return {column(0), column(1), column(2),
            Eigen::Vector3f(float(sensor.x()), float(sensor.y()), float(sensor.z()))};
}

bool seesPast(const mrpt::obs::CObservation3DRangeScan& obs, const SensorFrame& frame,
              const Eigen::Vector3f& point, float margin) {
    return seesPast(DepthRays(obs), obs, frame, point, margin);
}

bool seesPast(const DepthRays& rays, const mrpt::obs::CObservation3DRangeScan& obs,
              const SensorFrame& frame, const Eigen::Vector3f& point, float margin) {
    const std::optional<DepthRays::Projection> p = rays.project(frame, point);
    if (!obs.hasRangeImage || !p)
        return false;
    const int u = int(std::lround(p->col));
    const int v = int(std::lround(p->row));
    if (!rays.inImage(v, u))
        return false;
    const float measured = float(obs.rangeImage(v, u)) * obs.rangeUnits;
    if (measured <= 0.0f)
        return p->depth < obs.maxRange;
    return rays.depthOf(measured, p->left, p->up) > p->depth + margin;
}

std::vector<Eigen::Vector3f> unprojectDepthImage(const mrpt::obs::CObservation3DRangeScan& obs,
                                                 const FlatPose& robot) {
    std::vector<Eigen::Vector3f> points;
    points.reserve(std::size_t(obs.rangeImage.rows() * obs.rangeImage.cols()));
    forEachDepthPoint(obs, sensorFrameInWorld(obs, robot),
                      [&points](int, int, const Eigen::Vector3f& p) { points.push_back(p); });
    return points;
}

void ExplorationMap::insertObservation(const mrpt::obs::CObservation3DRangeScan& obs,
                                       const FlatPose& robot) {
    insertObservation(obs, robot, {});
}

namespace {

/**
 * One image row's pixels as world points and packed octree keys (kNoKey where the pixel has no
 * return or its point lies outside the tree), a pass at a time over arrays (the points' pass
 * vectorizes): the arithmetic of forEachDepthPoint and of the octree's key, bit for bit.
 */
struct DepthRow {
    std::vector<float> x, y, z;
    std::vector<std::uint64_t> key;

    void compute(const std::uint16_t* pixels, float units, const DepthRays& rays, int row,
                 const SensorFrame& frame, double scale) {
        const std::size_t n = std::size_t(rays.cols());
        x.resize(n);
        y.resize(n);
        z.resize(n);
        key.resize(n);
        const float kz = rays.up(row);
        const Eigen::Vector3f rowDir = frame.forward + kz * frame.up;
        const Eigen::Vector3f& o = frame.origin;
        const Eigen::Vector3f& l = frame.left;
        const float* left = rays.lefts();
        for (std::size_t u = 0; u < n; ++u) {
            x[u] = float(pixels[u]) * units;
            key[u] = x[u] > 0.0f ? 0 : kNoKey;
        }
        if (!rays.rangeIsDepth())
            for (std::size_t u = 0; u < n; ++u)
                x[u] = rays.depthOf(x[u], left[u], kz);
        for (std::size_t u = 0; u < n; ++u) {
            const float d = x[u], kyu = left[u];
            x[u] = o.x() + d * (rowDir.x() + kyu * l.x());
            y[u] = o.y() + d * (rowDir.y() + kyu * l.y());
            z[u] = o.z() + d * (rowDir.z() + kyu * l.z());
        }
        axisKeys(scale, x.data(), 0, n);
        axisKeys(scale, y.data(), 16, n);
        axisKeys(scale, z.data(), 32, n);
    }

    /**
     * One axis of the octree keys (octreeAxisKey's arithmetic), shifted into key[]; a pixel
     * without a return or a point outside the tree gets kNoKey.
     */
    void axisKeys(double scale, const float* c, int shift, std::size_t n) {
        constexpr double kHalfSpan = 32768.0;
        for (std::size_t u = 0; u < n; ++u) {
            const double v = scale * double(c[u]);
            const bool inside = v >= -kHalfSpan && v < kHalfSpan;
            const double w = inside ? v : 0.0;  // int(v) must not overflow
            const std::uint64_t k = std::uint32_t(floorToInt(w) + int(kHalfSpan));
            key[u] = inside ? key[u] | k << shift : kNoKey;
        }
    }
};

octomap::OcTreeKey unpack(std::uint64_t packed) {
    return octomap::OcTreeKey(octomap::key_type(packed & 0xffff),
                              octomap::key_type(packed >> 16 & 0xffff),
                              octomap::key_type(packed >> 32 & 0xffff));
}

}  // namespace

/**
 * The discrete update reduces every end point to its voxel anyway, so feeding it one voxel
 * centre per run of neighbouring pixels (same voxel as the pixel to the left or above) gives
 * the same update with far fewer end points.
 */
void ExplorationMap::insertObservation(const mrpt::obs::CObservation3DRangeScan& obs,
                                       const FlatPose& robot,
                                       const std::vector<PersonFootprint>& people) {
    if (!obs.hasRangeImage)
        throw std::invalid_argument("depth observation has no range image");
    Impl& m = *impl_;
    const float maxRange2 = float(params_.maxRange * params_.maxRange);
    const SensorFrame frame = sensorFrameInWorld(obs, robot);
    const PeopleBuckets onPeople(people);
    const DepthRays rays(obs);
    thread_local DepthRow row;
    m.cloud.clear();
    m.rowAbove.assign(std::size_t(rays.cols()), kNoKey);
    for (int v = 0; v < rays.rows(); ++v) {
        row.compute(&obs.rangeImage(v, 0), obs.rangeUnits, rays, v, frame, m.pointIndex.scale);
        std::uint64_t previous = kNoKey;  // the left neighbour's key, if it had a return
        for (std::size_t u = 0; u < row.key.size(); ++u) {
            const std::uint64_t packed = row.key[u];
            if (packed == kNoKey) {
                previous = kNoKey;  // no return, or a point outside the tree
                continue;
            }
            const Eigen::Vector3f p(row.x[u], row.y[u], row.z[u]);
            std::uint64_t& above = m.rowAbove[u];
            if (!people.empty() && (p - frame.origin).squaredNorm() <= maxRange2 &&
                onPeople.contains(p)) {
                m.personKeys.insert(unpack(packed));
                previous = kNoKey;
                above = kNoKey;
                continue;
            }
            if (packed != previous && packed != above)
                m.cloud.push_back(m.tree.keyToCoord(unpack(packed)));
            previous = packed;
            above = packed;
        }
    }
    if (params_.noReturnIsFree)
        addNoReturnRays(obs, frame);
    const octomap::point3d o(frame.origin.x(), frame.origin.y(), frame.origin.z());
    knownInBox_ += m.integrate(o, params_.maxRange);
    ++revision_;
}

void ExplorationMap::addNoReturnRays(const mrpt::obs::CObservation3DRangeScan& obs,
                                     const SensorFrame& frame) {
    const auto& image = obs.rangeImage;
    const auto& cam = obs.cameraParams;
    // A pixel subset whose neighbouring rays stay within half a cell of each other at maxRange.
    const int stride = std::max(
        1, int(0.5 * params_.resolution * std::min(cam.fx(), cam.fy()) / params_.maxRange));
    // Beyond maxRange: the ray is cleared up to maxRange and no end point is marked occupied.
    const float beyond = float(params_.maxRange + 2.0 * params_.resolution);
    const DepthRays rays(obs);
    for (int v = 0; v < rays.rows(); v += stride) {
        for (int u = 0; u < rays.cols(); u += stride) {
            if (image(v, u) > 0)
                continue;
            const Eigen::Vector3f dir = rays.ray(frame, v, u).normalized();
            const Eigen::Vector3f end = frame.origin + beyond * dir;
            impl_->cloud.push_back(octomap::point3d(end.x(), end.y(), end.z()));
        }
    }
}

}  // namespace daep::mapping
