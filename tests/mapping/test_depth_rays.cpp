// DepthRays: the one pinhole geometry of a depth image (pixel -> ray, point -> pixel).
#include <gtest/gtest.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3D.h>

#include <cmath>

#include "daep/mapping/DepthRays.h"
#include "daep/mapping/DepthUnprojection.h"

namespace {

using daep::mapping::DepthRays;

/** A 64 x 48 range image (not depth) with a 90 degree field of view, every pixel 4 m away. */
mrpt::obs::CObservation3DRangeScan rangeFrame() {
    mrpt::obs::CObservation3DRangeScan obs;
    obs.hasRangeImage = true;
    obs.range_is_depth = false;
    obs.rangeUnits = 0.001f;
    obs.rangeImage_setSize(48, 64);
    obs.rangeImage.fill(4000);
    obs.cameraParams.ncols = 64;
    obs.cameraParams.nrows = 48;
    obs.cameraParams.setIntrinsicParamsFromValues(32.0, 32.0, 31.5, 23.5);
    obs.sensorPose = mrpt::poses::CPose3D(0.1, 0.0, 0.2, 0.3, 0.2, -0.1);
    return obs;
}

TEST(DepthRays, PixelRaysFollowMrptsPinholeModel) {
    const auto obs = rangeFrame();
    const DepthRays rays(obs);
    EXPECT_EQ(rays.cols(), 64);
    EXPECT_EQ(rays.rows(), 48);
    EXPECT_FLOAT_EQ(rays.left(0), 31.5f / 32.0f);  // the leftmost column looks left
    EXPECT_FLOAT_EQ(rays.left(63), -31.5f / 32.0f);
    EXPECT_FLOAT_EQ(rays.up(0), 23.5f / 32.0f);           // the top row looks up
    EXPECT_FLOAT_EQ(rays.leftAt(-10.0f), 41.5f / 32.0f);  // beyond the image, the same formula
    // A range is measured along the ray: 4 m at a corner is less depth than 4 m in the middle.
    const float corner = rays.depth(0, 0);
    EXPECT_NEAR(corner, 4.0 / std::sqrt(1.0 + std::pow(31.5 / 32, 2) + std::pow(23.5 / 32, 2)),
                1e-5);
    EXPECT_LT(corner, rays.depth(24, 32));
}

TEST(DepthRays, AProjectedPointFallsOnThePixelWhoseRayItIsOn) {
    const auto obs = rangeFrame();
    const DepthRays rays(obs);
    daep::FlatPose robot;
    robot.position = {1.0, -2.0, 1.2};
    robot.yaw = 0.7;
    const auto frame = daep::mapping::sensorFrameInWorld(obs, robot);
    for (const auto& [row, col] : {std::pair{0, 0}, {47, 63}, {10, 50}, {30, 5}}) {
        const Eigen::Vector3f point = frame.origin + 2.5f * rays.ray(frame, row, col);
        const auto p = rays.project(frame, point);
        ASSERT_TRUE(p);
        EXPECT_NEAR(p->col, col, 1e-3);
        EXPECT_NEAR(p->row, row, 1e-3);
        EXPECT_NEAR(p->depth, 2.5f, 1e-5);
        EXPECT_NEAR(p->left, rays.left(col), 1e-6);
    }
    // Behind the camera: no pixel.
    EXPECT_FALSE(rays.project(frame, frame.origin - frame.forward));
    // A point 1 m in front of a 4 m return is seen past; one behind it is not.
    const Eigen::Vector3f near = frame.origin + 1.0f * rays.ray(frame, 24, 32);
    const Eigen::Vector3f far = frame.origin + 5.0f * rays.ray(frame, 24, 32);
    EXPECT_TRUE(daep::mapping::seesPast(obs, frame, near, 0.1f));
    EXPECT_FALSE(daep::mapping::seesPast(obs, frame, far, 0.1f));
}

}  // namespace
