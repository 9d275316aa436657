#include <gtest/gtest.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3D.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "DepthQuantise.h"
#include "SimTestWorlds.h"
#include "daep/sim/DepthCamera.h"
#include "daep/world/RayCaster.h"

namespace daep::sim {
namespace {

using test::box;
using test::distanceToBoxSurface;

constexpr double kDeg = M_PI / 180.0;

FlatPose pose(double x, double y, double z, double yaw) {
    FlatPose p;
    p.position = Eigen::Vector3d(x, y, z);
    p.yaw = yaw;
    return p;
}

mrpt::poses::CPose3D toMrpt(const FlatPose& p) {
    return mrpt::poses::CPose3D(p.position.x(), p.position.y(), p.position.z(), p.yaw, 0, 0);
}

/** The paper's camera (640 x 480) without noise. */
CameraParams noiselessParams(double maxRange = 20.0) {
    CameraParams p;
    p.width = 640;
    p.height = 480;
    p.maxRange = maxRange;
    p.noiseSigma = 0.0;
    p.mountOffset = Eigen::Vector3d(0.1, 0.05, -0.03);
    return p;
}

/** Unprojects with MRPT into world coordinates, the way the mapper does. */
std::vector<Eigen::Vector3d> unprojectToWorld(mrpt::obs::CObservation3DRangeScan& obs,
                                              const FlatPose& drone) {
    mrpt::obs::T3DPointsProjectionParams pp;
    pp.takeIntoAccountSensorPoseOnRobot = true;
    pp.robotPoseInTheWorld = toMrpt(drone);
    mrpt::maps::CSimplePointsMap cloud;
    obs.unprojectInto(cloud, pp);
    std::vector<Eigen::Vector3d> points(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i) {
        float x, y, z;
        cloud.getPoint(i, x, y, z);
        points[i] = Eigen::Vector3d(x, y, z);
    }
    return points;
}

std::size_t countNonZero(const mrpt::math::CMatrix_u16& image) {
    const uint16_t* d = image.data();
    return static_cast<std::size_t>(
        std::count_if(d, d + image.rows() * image.cols(), [](uint16_t v) { return v != 0; }));
}

/** An asymmetric closed room (x in [-3,7], y in [-4,5], z in [0,3]) with a yawed pillar. */
class RoomScene : public ::testing::Test {
protected:
    RoomScene() {
        const Eigen::Vector3d c(2.0, 0.5, 1.5);
        world_.name = "room";
        world_.boxes = {
            box("floor", {c.x(), c.y(), -0.5}, {12, 11, 1}),
            box("ceiling", {c.x(), c.y(), 3.5}, {12, 11, 1}),
            box("west", {-3.5, c.y(), c.z()}, {1, 11, 5}),
            box("east", {7.5, c.y(), c.z()}, {1, 11, 5}),
            box("south", {c.x(), -4.5, c.z()}, {12, 1, 5}),
            box("north", {c.x(), 5.5, c.z()}, {12, 1, 5}),
            box("pillar", {4.0, 2.0, 1.0}, {0.8, 1.2, 2.0}, 0.5),
        };
        person_.position = Eigen::Vector2d(1.5, -1.5);
        person_.heading = 0.7;
        personBox_ = box("person", {1.5, -1.5, 0.9}, personSize_, 0.7);
        scene_ = std::make_unique<world::RayCaster>(world_);
        scene_->setPeople({person_}, personSize_);
    }

    double distanceToSurface(const Eigen::Vector3d& p) const {
        const double room = std::min({std::abs(p.x() + 3), std::abs(7 - p.x()), std::abs(p.y() + 4),
                                      std::abs(5 - p.y()), std::abs(p.z()), std::abs(3 - p.z())});
        return std::min({room, distanceToBoxSurface(p, world_.boxes.back()),
                         distanceToBoxSurface(p, personBox_)});
    }

    world::WorldSpec world_;
    Eigen::Vector3d personSize_{1.0, 1.0, 1.8};
    world::PersonState person_;
    world::BoxShape personBox_;
    std::unique_ptr<world::RayCaster> scene_;
};

TEST(DepthCamera, IntrinsicsFromHorizontalFov) {
    const CameraParams p;  // 320 x 240, 103.2 deg
    EXPECT_NEAR(p.fx(), 160.0 / std::tan(51.6 * kDeg), 1e-9);
    EXPECT_NEAR(p.vfovRad() / kDeg, 86.8, 0.05);
    EXPECT_DOUBLE_EQ(p.cx(), 159.5);
    EXPECT_DOUBLE_EQ(p.cy(), 119.5);
}

TEST(DepthCamera, SensorPoseComposesMountOffsetWithYaw) {
    CameraParams p;
    p.mountOffset = Eigen::Vector3d(0.2, 0.1, -0.05);
    const DepthCamera camera(p);
    const FlatPose s = camera.sensorPose(pose(1, 2, 3, M_PI / 2));
    EXPECT_TRUE(s.position.isApprox(Eigen::Vector3d(0.9, 2.2, 2.95), 1e-12));
    EXPECT_DOUBLE_EQ(s.yaw, M_PI / 2);
}

TEST_F(RoomScene, UnprojectedPointsLieOnTheTrueSurfaces) {
    const DepthCamera camera(noiselessParams());
    const std::vector<FlatPose> drones{pose(0, 0, 1.5, 0.0), pose(2.5, 1.0, 1.2, 2.3),
                                       pose(-1, -2, 0.8, -1.9), pose(5, 3, 2.0, -0.4),
                                       pose(0.2, -1.4, 1.0, -0.1)};
    std::mt19937_64 rng(1);
    for (const FlatPose& drone : drones) {
        mrpt::obs::CObservation3DRangeScan obs;
        camera.render(*scene_, drone, 12.5, rng, obs);
        // Every pixel hits something in a closed room.
        ASSERT_EQ(countNonZero(obs.rangeImage), 640u * 480u);
        const auto points = unprojectToWorld(obs, drone);
        ASSERT_EQ(points.size(), 640u * 480u);
        double worst = 0.0;
        for (const Eigen::Vector3d& p : points) {
            worst = std::max(worst, distanceToSurface(p));
        }
        // 0.5 mm depth quantisation, at most doubled along the corner rays.
        EXPECT_LT(worst, 2e-3) << "drone at " << drone.position.transpose() << " yaw " << drone.yaw;
    }
}

TEST_F(RoomScene, PersonIsSeenWhereItStands) {
    const DepthCamera camera(noiselessParams());
    // Drone looks along +x at the person standing 3 m ahead, turned by 0.7 rad. The optical
    // axis (mounted 0.1 m forward, 0.05 m left) meets the face whose normal is -(cos, sin) 0.7.
    const FlatPose drone = pose(-1.5, -1.5, 1.0, 0.0);
    std::mt19937_64 rng(1);
    mrpt::obs::CObservation3DRangeScan obs;
    camera.render(*scene_, drone, 0.0, rng, obs);
    int onPerson = 0;
    for (const Eigen::Vector3d& p : unprojectToWorld(obs, drone)) {
        onPerson += distanceToBoxSurface(p, personBox_) < 2e-3 ? 1 : 0;
    }
    // At about 2.3 m the 1 x 1.8 m person covers roughly a tenth of the image.
    EXPECT_GT(onPerson, 10000);
    const std::size_t centre = 240 * 640 + 320;
    const double depth = obs.rangeImage.data()[centre] * obs.rangeUnits;
    EXPECT_NEAR(depth, 3.0 - 0.1 - (0.5 + 0.05 * std::sin(0.7)) / std::cos(0.7), 0.01);
}

TEST(DepthCamera, WallAheadHasKnownDepthAndMissesAreZero) {
    world::WorldSpec world;
    world.boxes = {box("wall", {3.5, 0, 1.5}, {1, 2, 1})};  // front face x = 3, 2 x 1 m
    const world::RayCaster scene(world);
    const CameraParams params = noiselessParams(10.0);
    const DepthCamera camera(params);
    const FlatPose drone = pose(0, 0, 1.5 - params.mountOffset.z(), 0.0);

    std::mt19937_64 rng(7);
    mrpt::obs::CObservation3DRangeScan obs;
    camera.render(scene, drone, 3.25, rng, obs);
    const uint16_t centre = obs.rangeImage(240, 320);
    EXPECT_NEAR(centre * obs.rangeUnits, 3.0 - params.mountOffset.x(), 1e-3);
    EXPECT_EQ(obs.rangeImage(0, 0), 0);
    EXPECT_EQ(obs.rangeImage(479, 639), 0);

    const auto points = unprojectToWorld(obs, drone);
    ASSERT_EQ(points.size(), countNonZero(obs.rangeImage));
    ASSERT_GT(points.size(), 1000u);
    for (const Eigen::Vector3d& p : points) {
        ASSERT_NEAR(p.x(), 3.0, 1e-3);
        ASSERT_LE(std::abs(p.y()), 1.0 + 1e-3);
        ASSERT_NEAR(p.z(), 1.5, 0.5 + 1e-3);
    }
}

TEST(DepthCamera, ImageAxesFollowTheWorld) {
    // A box up-left of the view axis shows in the upper-left quadrant only.
    world::WorldSpec world;
    world.boxes = {box("target", {3, 1.5, 2.5}, {0.5, 0.5, 0.5})};
    const world::RayCaster scene(world);
    const DepthCamera camera(noiselessParams(10.0));
    std::vector<float> depth;
    camera.renderDepth(scene, pose(0, 0, 1, 0.0), nullptr, depth);
    int upperLeft = 0;
    for (int v = 0; v < 480; ++v) {
        for (int u = 0; u < 640; ++u) {
            if (depth[v * 640 + u] > 0.0f) {
                ASSERT_LT(u, 320);
                ASSERT_LT(v, 240);
                ++upperLeft;
            }
        }
    }
    EXPECT_GT(upperLeft, 100);
    // Yawing towards the box (counter-clockwise) centres it horizontally.
    camera.renderDepth(scene, pose(0, 0, 1, std::atan2(1.5, 3.0)), nullptr, depth);
    double columnSum = 0.0;
    int hits = 0;
    for (int v = 0; v < 480; ++v) {
        for (int u = 0; u < 640; ++u) {
            if (depth[v * 640 + u] > 0.0f) {
                columnSum += u;
                ++hits;
            }
        }
    }
    ASSERT_GT(hits, 100);
    EXPECT_NEAR(columnSum / hits, 319.5, 25.0);
}

TEST(DepthCamera, RenderMatchesRenderDepthAndFillsTheObservation) {
    world::WorldSpec world;
    world.boxes = {box("wall", {4.5, 0, 0}, {1, 40, 40})};
    const world::RayCaster scene(world);
    CameraParams params = noiselessParams(10.0);
    params.noiseSigma = 0.01;
    params.width = 320;
    params.height = 240;
    const DepthCamera camera(params);
    const FlatPose drone = pose(0.3, -0.2, 1.1, 0.15);

    std::mt19937_64 rngA(42), rngB(42);
    std::vector<float> depth;
    camera.renderDepth(scene, drone, &rngA, depth);
    mrpt::obs::CObservation3DRangeScan obs;
    camera.render(scene, drone, 17.75, rngB, obs);

    ASSERT_EQ(obs.rangeImage.rows(), 240);
    ASSERT_EQ(obs.rangeImage.cols(), 320);
    // The same depths, noise and all, each quantised as the image's own pixel is.
    for (std::size_t i = 0; i < depth.size(); ++i) {
        ASSERT_EQ(obs.rangeImage.data()[i], quantiseDepth(depth[i], obs.rangeUnits)) << i;
    }
    EXPECT_TRUE(obs.hasRangeImage);
    EXPECT_TRUE(obs.range_is_depth);
    EXPECT_FALSE(obs.hasIntensityImage);
    EXPECT_FLOAT_EQ(obs.rangeUnits, 1e-3f);
    EXPECT_EQ(obs.cameraParams.ncols, 320u);
    EXPECT_EQ(obs.cameraParams.nrows, 240u);
    EXPECT_NEAR(obs.cameraParams.fx(), params.fx(), 1e-9);
    EXPECT_NEAR(obs.cameraParams.fy(), params.fx(), 1e-9);
    EXPECT_DOUBLE_EQ(obs.cameraParams.cx(), 159.5);
    EXPECT_DOUBLE_EQ(obs.cameraParams.cy(), 119.5);
    EXPECT_EQ(obs.cameraParamsIntensity.ncols, 320u);
    EXPECT_NEAR(obs.sensorPose.x(), 0.1, 1e-12);
    EXPECT_NEAR(obs.sensorPose.y(), 0.05, 1e-12);
    EXPECT_NEAR(obs.sensorPose.z(), -0.03, 1e-12);
    EXPECT_EQ(obs.sensorPose.yaw(), 0.0);
    EXPECT_NEAR(mrpt::Clock::toDouble(obs.timestamp), 17.75, 1e-6);
    EXPECT_EQ(obs.sensorLabel, "DEPTH_CAM");
}

TEST(DepthCamera, NoiseIsDeterministicPerSeedWithTheConfiguredSigma) {
    world::WorldSpec world;
    world.boxes = {box("wall", {3.5, 0, 1}, {1, 100, 100})};
    const world::RayCaster scene(world);
    CameraParams params = noiselessParams(10.0);
    params.noiseSigma = 0.05;
    const DepthCamera camera(params);
    const FlatPose drone = pose(0, 0, 1, 0.0);
    const double truth = 3.0 - params.mountOffset.x();

    std::vector<float> a, b, c;
    std::mt19937_64 rng1(5), rng2(5), rng3(6);
    camera.renderDepth(scene, drone, &rng1, a);
    camera.renderDepth(scene, drone, &rng2, b);
    camera.renderDepth(scene, drone, &rng3, c);
    EXPECT_EQ(a, b);
    EXPECT_NE(a, c);

    double sum = 0.0, sumSq = 0.0;
    std::array<int, 4> beyond{};  // |error| > 1, 2, 3, 4 sigma
    for (float d : a) {
        ASSERT_GT(d, 0.0f);
        const double e = d - truth;
        sum += e;
        sumSq += e * e;
        for (int k = 0; k < 4; ++k) {
            beyond[k] += std::abs(e) > (k + 1) * 0.05 ? 1 : 0;
        }
    }
    const double n = static_cast<double>(a.size());
    const double mean = sum / n;
    const double sigma = std::sqrt(sumSq / n - mean * mean);
    EXPECT_NEAR(mean, 0.0, 5e-4);
    EXPECT_NEAR(sigma, 0.05, 0.05 * 0.01);
    // Gaussian tail fractions (erfc(k / sqrt 2)), each within about 5 standard errors.
    EXPECT_NEAR(beyond[0] / n, 0.317311, 0.005);
    EXPECT_NEAR(beyond[1] / n, 0.045500, 0.002);
    EXPECT_NEAR(beyond[2] / n, 0.002700, 0.0005);
    EXPECT_NEAR(beyond[3] / n, 0.0000633, 0.00007);
    EXPECT_GT(beyond[3], 0);

    std::vector<float> clean;
    camera.renderDepth(scene, drone, nullptr, clean);  // no rng: no noise
    for (float d : clean) {
        ASSERT_NEAR(d, truth, 1e-4);
    }
}

TEST(DepthCamera, LongRangesStillFitTheImage) {
    world::WorldSpec world;
    world.boxes = {box("far wall", {80.5, 0, 1}, {1, 400, 400})};
    const world::RayCaster scene(world);
    CameraParams params = noiselessParams(100.0);
    params.width = 64;
    params.height = 48;
    params.mountOffset.setZero();
    const DepthCamera camera(params);
    std::mt19937_64 rng(3);
    mrpt::obs::CObservation3DRangeScan obs;
    camera.render(scene, pose(0, 0, 1, 0), 0.0, rng, obs);
    EXPECT_GT(obs.rangeUnits, 1e-3f);
    EXPECT_NEAR(obs.rangeImage(24, 32) * obs.rangeUnits, 80.0, obs.rangeUnits);
}

/** quantiseDepth is clamp(std::round(depth / units), 1, 65535), bit for bit. */
TEST(DepthCamera, QuantiseRoundsAsStdRound) {
    const auto reference = [](float depth, float units) -> std::uint16_t {
        if (depth <= 0.0f)
            return 0;
        return std::uint16_t(std::clamp(std::round(depth / units), 1.0f, 65535.0f));
    };
    std::vector<float> depths = {1e-9f,
                                 2.5e-4f,
                                 4.9999997e-4f,
                                 5e-4f,
                                 5.0000006e-4f,
                                 1.5e-3f,
                                 2.5e-3f,
                                 65.5345f,
                                 65.5349f,
                                 65.535f,
                                 65.6f,
                                 1e6f,
                                 std::numeric_limits<float>::max(),
                                 std::numeric_limits<float>::infinity(),
                                 0.0f,
                                 -1.0f};
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> anywhere(0.0f, 70.0f);
    for (int i = 0; i < 200000; ++i)
        depths.push_back(anywhere(rng));
    for (const float units : {1e-3f, 1.6e-3f, 0.37f})
        for (const float d : depths)
            ASSERT_EQ(quantiseDepth(d, units), reference(d, units)) << d << " m in " << units;
    // Every float within 64 steps of each half-step, where rounding decides.
    for (float half = 0.5f; half < 65536.0f;
         half = half < 64.0f ? half + 1.0f : std::floor(half * 1.5f) + 0.5f) {
        float x = half;
        for (int i = 0; i < 64; ++i)
            x = std::nextafter(x, 0.0f);
        for (int i = 0; i < 128; ++i, x = std::nextafter(x, 1e9f))
            ASSERT_EQ(quantiseDepth(x, 1.0f), reference(x, 1.0f)) << x;
    }
    // Halves round away from zero: 0.5 -> 1, 1.5 -> 2, 2.5 -> 3, and just below 0.5 -> 0 (then 1).
    EXPECT_EQ(quantiseDepth(2.5f, 1.0f), 3);
    EXPECT_EQ(quantiseDepth(1.5f, 1.0f), 2);
    EXPECT_EQ(quantiseDepth(2.4999998f, 1.0f), 2);
}

TEST(DepthCamera, RejectsBadParameters) {
    CameraParams p;
    p.hfovRad = M_PI;
    EXPECT_THROW(DepthCamera{p}, std::invalid_argument);
    p = CameraParams{};
    p.width = 0;
    EXPECT_THROW(DepthCamera{p}, std::invalid_argument);
}

}  // namespace
}  // namespace daep::sim
