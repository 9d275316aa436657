#include <cmath>
#include <cstdint>

#include <algorithm>

#include "DepthPixels.h"
#include "MapImpl.h"
#include "PeopleBuckets.h"
#include "daep/mapping/DepthUnprojection.h"

namespace daep::mapping {
namespace {

constexpr std::uint64_t kNoKey = ~std::uint64_t(0);

std::uint64_t pack(const octomap::OcTreeKey& k) {
    return std::uint64_t(k[0]) | std::uint64_t(k[1]) << 16 | std::uint64_t(k[2]) << 32;
}

/** The drone's body box where it flies: whether a world point lies inside it. */
class Body {
public:
    Body(const FlatPose& robot, const Eigen::Vector3d& half)
        : centre_(robot.position.cast<float>()),
          half_(half.cast<float>()),
          cos_(float(std::cos(robot.yaw))),
          sin_(float(std::sin(robot.yaw))),
          reach2_(half_.squaredNorm()) {}

    bool contains(const Eigen::Vector3f& p) const {
        const Eigen::Vector3f d = p - centre_;
        if (!(reach2_ > 0.0f) || d.squaredNorm() > reach2_)
            return false;
        const float forward = cos_ * d.x() + sin_ * d.y();
        const float left = -sin_ * d.x() + cos_ * d.y();
        return std::abs(forward) <= half_.x() && std::abs(left) <= half_.y() &&
               std::abs(d.z()) <= half_.z();
    }

private:
    Eigen::Vector3f centre_, half_;
    float cos_, sin_, reach2_;
};

}  // namespace

/** What a frame's pixels are tested against before their cells become end cells. */
struct PixelTests {
    const Body& body;
    const PeopleBuckets& onPeople;
    bool hasPeople;
    Eigen::Vector3f origin;
    float maxRange2;
};

/** The key of the cell containing p: keyOf's, with octreeAxisKey<kFloored>. */
template <bool kFloored>
__attribute__((always_inline)) inline bool ExplorationMap::Impl::pixelKey(
    const Eigen::Vector3f& p, octomap::OcTreeKey& key) const {
    const double scale = pointIndex.scale;
    return octreeAxisKey<kFloored>(scale, p.x(), key[0]) &&
           octreeAxisKey<kFloored>(scale, p.y(), key[1]) &&
           octreeAxisKey<kFloored>(scale, p.z(), key[2]);
}

/**
 * One image row's end cells, each added once; most repeats, a pixel in the same cell as the
 * one to its left or above, skipped before even that lookup.
 */
template <bool kFloored>
__attribute__((always_inline)) inline void ExplorationMap::Impl::addRowEnds(
    const DepthRow& row, const PixelTests& tests) {
    std::uint64_t previous = kNoKey;  // the left neighbour's key, if it had a return
    for (std::size_t u = 0; u < row.returned.size(); ++u) {
        const Eigen::Vector3f p(row.x[u], row.y[u], row.z[u]);
        octomap::OcTreeKey key;
        if (!row.returned[u] || !pixelKey<kFloored>(p, key)) {
            previous = kNoKey;  // no return, or a point outside the tree
            continue;
        }
        std::uint64_t& above = rowAbove[u];
        if (tests.body.contains(p)) {
            previous = kNoKey;
            above = kNoKey;
            continue;
        }
        if (tests.hasPeople && (p - tests.origin).squaredNorm() <= tests.maxRange2 &&
            tests.onPeople.contains(p)) {
            personKeys.insert(key);
            previous = kNoKey;
            above = kNoKey;
            continue;
        }
        const std::uint64_t packed = pack(key);
        if (packed != previous && packed != above)
            addEnd(key);
        previous = packed;
        above = packed;
    }
}

void ExplorationMap::Impl::addRowEndsSse41(const DepthRow& row, const PixelTests& tests) {
    addRowEnds<true>(row, tests);
}

void ExplorationMap::Impl::addRowEnds(const DepthRow& row, const PixelTests& tests) {
    static const bool hasSse41 = __builtin_cpu_supports("sse4.1");
    if (hasSse41)
        addRowEndsSse41(row, tests);
    else
        addRowEnds<false>(row, tests);
}

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
    forEachDepthRow(obs, sensorFrameInWorld(obs, robot), [&points](int, const DepthRow& row) {
        for (std::size_t u = 0; u < row.returned.size(); ++u)
            if (row.returned[u])
                points.emplace_back(row.x[u], row.y[u], row.z[u]);
    });
    return points;
}

void ExplorationMap::insertObservation(const mrpt::obs::CObservation3DRangeScan& obs,
                                       const FlatPose& robot) {
    insertObservation(obs, robot, {});
}

/**
 * The discrete update reduces every end point to its voxel anyway, so each voxel is added once
 * as the pixels are read (addRowEnds) and the update walks one ray per voxel.
 */
void ExplorationMap::insertObservation(const mrpt::obs::CObservation3DRangeScan& obs,
                                       const FlatPose& robot,
                                       const std::vector<PersonFootprint>& people) {
    Impl& m = *impl_;
    const float maxRange2 = float(params_.maxRange * params_.maxRange);
    const SensorFrame frame = sensorFrameInWorld(obs, robot);
    const PeopleBuckets onPeople(people);
    const Body body(robot, params_.bodyHalfExtents);
    m.rowAbove.assign(std::size_t(obs.rangeImage.cols()), kNoKey);
    const PixelTests tests{body, onPeople, !people.empty(), frame.origin, maxRange2};
    forEachDepthRow(obs, frame,
                    [&m, &tests](int, const DepthRow& row) { m.addRowEnds(row, tests); });
    if (params_.noReturnIsFree)
        addNoReturnRays(obs, frame);
    const octomap::point3d o(frame.origin.x(), frame.origin.y(), frame.origin.z());
    knownInBox_ += m.integrate(o, params_.maxRange);
    markFlown(robot.position);
    ++revision_;
}

void ExplorationMap::markFlown(const Eigen::Vector3d& position) {
    Impl& m = *impl_;
    const std::int64_t i = gridIndex_(position);
    if (i < 0 || (m.flags[std::size_t(i)] & Impl::kFlown))
        return;
    m.flags[std::size_t(i)] |= Impl::kFlown;
    m.passCellChanged(i);
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
            impl_->addEndPoint(octomap::point3d(end.x(), end.y(), end.z()));
        }
    }
}

}  // namespace daep::mapping
