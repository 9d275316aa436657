#include <gtest/gtest.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3D.h>

#include <cmath>
#include <random>

#include "DepthFrames.h"
#include "daep/mapping/DepthUnprojection.h"
#include "daep/mapping/ExplorationMap.h"

namespace daep::mapping {
namespace {

FlatPose makePose(double x, double y, double z, double yaw) {
    FlatPose p;
    p.position = {x, y, z};
    p.yaw = yaw;
    return p;
}

TEST(DepthUnprojection, MatchesMrptUnprojectInto) {
    const mrpt::poses::CPose3D sensorPose(0.12, -0.05, 0.2, 0.3, 0.25, -0.1);
    auto obs = test::depthFrame(64, 48, 3.0, sensorPose);
    std::mt19937 rng(5);
    std::uniform_int_distribution<int> depthMm(0, 9000);
    for (int r = 0; r < 48; ++r) {
        for (int c = 0; c < 64; ++c) {
            const int d = depthMm(rng);
            obs.rangeImage(r, c) = std::uint16_t(d < 500 ? 0 : d);  // some pixels: no return
        }
    }
    const FlatPose robot = makePose(1.5, -2.0, 1.2, 2.4);
    const auto mine = unprojectDepthImage(obs, robot);

    mrpt::maps::CSimplePointsMap theirs;
    mrpt::obs::T3DPointsProjectionParams pp;
    pp.takeIntoAccountSensorPoseOnRobot = true;
    pp.robotPoseInTheWorld = mrpt::poses::CPose3D(1.5, -2.0, 1.2, 2.4, 0.0, 0.0);
    obs.unprojectInto(theirs, pp);

    ASSERT_EQ(mine.size(), theirs.size());
    ASSERT_GT(mine.size(), 64u * 48u * 3u / 4u);
    for (std::size_t i = 0; i < mine.size(); ++i) {
        float x, y, z;
        theirs.getPoint(i, x, y, z);
        ASSERT_NEAR(mine[i].x(), x, 1e-4) << i;
        ASSERT_NEAR(mine[i].y(), y, 1e-4) << i;
        ASSERT_NEAR(mine[i].z(), z, 1e-4) << i;
    }
}

TEST(DepthUnprojection, AxesAreXForwardYLeftZUp) {
    // Odd size so that the principal point is a pixel centre.
    const auto obs = test::depthFrame(5, 3, 2.0, mrpt::poses::CPose3D());
    const auto pts = unprojectDepthImage(obs, FlatPose{});
    ASSERT_EQ(pts.size(), 15u);
    // Row 1, column 2 is the principal point.
    EXPECT_NEAR((pts[7] - Eigen::Vector3f(2, 0, 0)).norm(), 0.0f, 1e-5f);
    // Column 0 (image left) is +y, row 0 (image top) is +z.
    EXPECT_GT(pts[0].y(), 1.0f);
    EXPECT_GT(pts[0].z(), 0.5f);
    EXPECT_NEAR(pts[0].x(), 2.0f, 1e-5f);
}

/**
 * A camera looking along the robot's heading at a wall `depth` metres ahead of the sensor:
 * the wall cells are occupied, the space in front is free and the space behind unknown.
 */
void checkWall(const FlatPose& robot, const mrpt::poses::CPose3D& sensorPose, double depth) {
    Aabb box;
    box.min = {-10, -10, -2};
    box.max = {10, 10, 5};
    ExplorationMap map(MapParams{}, box);
    const auto obs = test::depthFrame(160, 120, depth, sensorPose);
    map.insertObservation(obs, robot);
    EXPECT_EQ(map.revision(), 1u);

    const Eigen::Vector3d forward(std::cos(robot.yaw), std::sin(robot.yaw), 0.0);
    const Eigen::Vector3d left(-std::sin(robot.yaw), std::cos(robot.yaw), 0.0);
    const Eigen::Vector3d up(0, 0, 1);
    const Eigen::Vector3d t(sensorPose.x(), sensorPose.y(), sensorPose.z());
    const Eigen::Vector3d sensor = robot.position + t.x() * forward + t.y() * left + t.z() * up;
    // The wall spans +-depth laterally (90 degree FOV) and +-0.75 depth vertically; stay
    // within maxRange (5 m) of the sensor.
    for (double lateral : {-0.5, 0.0, 0.5}) {
        for (double vertical : {-0.35, 0.0, 0.35}) {
            const Eigen::Vector3d wall =
                sensor + depth * forward + lateral * depth * left + vertical * depth * up;
            EXPECT_TRUE(map.isOccupied(wall)) << wall.transpose();
            EXPECT_TRUE(map.isFree(sensor + 0.8 * (wall - sensor))) << wall.transpose();
            EXPECT_TRUE(map.isUnknown(wall + 0.5 * forward)) << wall.transpose();
        }
    }
    EXPECT_TRUE(map.isFree(sensor));
    EXPECT_TRUE(map.isUnknown(sensor - 0.5 * forward));  // behind the camera
    EXPECT_GT(map.knownCellsInBox(), 1000u);
}

TEST(InsertObservation, WallAtIdentityPose) {
    checkWall(FlatPose{}, mrpt::poses::CPose3D(), 3.0);
}

TEST(InsertObservation, WallWithRobotPoseYawAndSensorOffset) {
    checkWall(makePose(1.3, -2.1, 1.5, 0.7), mrpt::poses::CPose3D(0.15, 0.1, 0.2, 0, 0, 0), 2.7);
    checkWall(makePose(-3.0, 4.0, 0.5, -2.5), mrpt::poses::CPose3D(0.15, 0.1, 0.2, 0, 0, 0), 4.1);
}

TEST(InsertObservation, PitchedSensorSeesTheFloor) {
    // Camera 2 m up, pitched down 45 degrees (positive pitch looks down in MRPT), facing +x:
    // a depth of sqrt(2)*... put the "floor" where the optical axis meets z = 0.
    const mrpt::poses::CPose3D sensorPose(0, 0, 0, 0, M_PI / 4, 0);
    const double depth = 2.0 * std::sqrt(2.0);
    Aabb box;
    box.min = {-5, -5, -2};
    box.max = {5, 5, 4};
    ExplorationMap map(MapParams{}, box);
    auto obs = test::depthFrame(160, 120, depth, sensorPose);
    map.insertObservation(obs, makePose(0.0, 0.0, 2.0, 0.0));
    EXPECT_TRUE(map.isOccupied({2.0, 0.0, 0.0}));
    EXPECT_TRUE(map.isFree({1.0, 0.0, 1.0}));
    EXPECT_TRUE(map.isUnknown({1.0, 0.0, 3.0}));
}

TEST(InsertObservation, FarWallOnlyClearsUpToMaxRange) {
    Aabb box;
    box.min = {-1, -8, -4};
    box.max = {10, 8, 4};
    ExplorationMap map(MapParams{}, box);  // maxRange 5
    map.insertObservation(test::depthFrame(80, 60, 8.0, mrpt::poses::CPose3D()), FlatPose{});
    EXPECT_TRUE(map.isFree({4.5, 0.0, 0.0}));
    EXPECT_TRUE(map.isUnknown({5.5, 0.0, 0.0}));
    EXPECT_TRUE(map.isUnknown({8.1, 0.0, 0.0}));
}

TEST(InsertObservation, ReturnsOnAPersonClearUpToThemAndMarkNothing) {
    Aabb box;
    box.min = {-1, -8, -4};
    box.max = {10, 8, 4};
    // A wall 3 m ahead; a person stands in it around y = 0 (their footprint reaches it).
    const auto wall = test::depthFrame(80, 60, 3.0, mrpt::poses::CPose3D());
    PersonFootprint person;
    person.centre = {3.2f, 0.0f};
    person.radius = 0.6f;
    person.top = 1.0f;
    ExplorationMap map(MapParams{}, box);
    map.insertObservation(wall, FlatPose{}, {person});
    EXPECT_FALSE(map.isOccupied({3.0, 0.0, 0.0}));  // the person is not a wall
    EXPECT_TRUE(map.isFree({2.5, 0.0, 0.0}));       // the ray to them is cleared
    EXPECT_TRUE(map.isOccupied({3.0, 1.5, 0.0}));   // beside them the wall is a wall
    EXPECT_TRUE(map.isOccupied({3.0, 0.0, 1.5}));   // and above their head
    // Without people the same frame maps the wall everywhere.
    ExplorationMap plain(MapParams{}, box);
    plain.insertObservation(wall, FlatPose{}, {});
    EXPECT_TRUE(plain.isOccupied({3.0, 0.0, 0.0}));
}

TEST(InsertObservation, ReturnsInsideTheDronesOwnBodyMarkNothing) {
    // Something 0.05 m in front of the camera: inside the drone's 0.4 x 0.4 x 0.1 m box (a
    // person's box the drone is in), it is no wall; 0.3 m away it is.
    Aabb box;
    box.min = {-2, -2, -1};
    box.max = {2, 2, 2};
    const MapParams params;  // the default body: [drone] box of defaults.ini
    ASSERT_EQ(params.bodyHalfExtents, Eigen::Vector3d(0.2, 0.2, 0.05));
    const FlatPose drone = makePose(0.1, 0.1, 0.5, 0.3);
    // Where pixel (2, 2) of a 4 x 4 frame at `depth` returns: half a pixel right of and below
    // the optical axis (f = 2 pixels).
    const auto returnOf = [&drone](double depth) {
        const Eigen::Vector3d ahead(std::cos(drone.yaw), std::sin(drone.yaw), 0.0);
        const Eigen::Vector3d left(-std::sin(drone.yaw), std::cos(drone.yaw), 0.0);
        return Eigen::Vector3d(drone.position +
                               depth * (ahead - 0.25 * left - Eigen::Vector3d(0, 0, 0.25)));
    };
    const auto near = test::depthFrame(4, 4, 0.05, mrpt::poses::CPose3D());
    ExplorationMap map(params, box);
    map.insertObservation(near, drone);
    EXPECT_FALSE(map.isOccupied(returnOf(0.05)));
    MapParams noBody;
    noBody.bodyHalfExtents.setZero();
    ExplorationMap bodiless(noBody, box);
    bodiless.insertObservation(near, drone);
    EXPECT_TRUE(bodiless.isOccupied(returnOf(0.05)));
    map.insertObservation(test::depthFrame(4, 4, 0.3, mrpt::poses::CPose3D()), drone);
    EXPECT_TRUE(map.isOccupied(returnOf(0.3)));
}

TEST(InsertObservation, NoReturnPixelsClearTheirRaysOnlyWhenAskedTo) {
    Aabb box;
    box.min = {-1, -8, -4};
    box.max = {10, 8, 4};
    const auto sky = test::depthFrame(80, 60, 0.0, mrpt::poses::CPose3D());  // nothing returns
    MapParams params;
    params.noReturnIsFree = false;
    ExplorationMap indoor(params, box);
    indoor.insertObservation(sky, FlatPose{});
    EXPECT_EQ(indoor.knownVolumeInBox(), 0.0);
    params.noReturnIsFree = true;  // the default
    ExplorationMap outdoor(params, box);
    outdoor.insertObservation(sky, FlatPose{});
    for (const double x : {1.0, 3.0, 4.7})
        EXPECT_TRUE(outdoor.isFree({x, 0.0, 0.0})) << x;
    for (const double x : {1.0, 2.0, 3.3})  // towards a corner, up to 4.7 m away
        EXPECT_TRUE(outdoor.isFree({x, 0.8 * x, -0.6 * x})) << x;
    EXPECT_TRUE(outdoor.isUnknown({5.6, 0.0, 0.0}));   // beyond max_range
    EXPECT_TRUE(outdoor.isUnknown({-0.8, 0.0, 0.0}));  // behind the camera
    // Free only: nothing is marked occupied at the rays' ends.
    for (double x = 4.8; x < 6.0; x += 0.2)
        EXPECT_FALSE(outdoor.isOccupied({x, 0.0, 0.0})) << x;
    // Where a pixel does return, its wall is kept as it is.
    ExplorationMap mixed(params, box);
    mixed.insertObservation(test::depthFrame(80, 60, 3.0, mrpt::poses::CPose3D()), FlatPose{});
    EXPECT_TRUE(mixed.isOccupied({3.0, 0.0, 0.0}));
    EXPECT_TRUE(mixed.isUnknown({4.0, 0.0, 0.0}));
}

/** The per-row pixel pass against the cloud unprojectDepthImage gives, depth and range images. */
TEST(InsertObservation, EqualsInsertingTheUnprojectedCloud) {
    for (const bool rangeIsDepth : {true, false}) {
        auto obs = test::depthFrame(96, 72, 3.0, mrpt::poses::CPose3D(0.1, 0, 0.1, 0, 0.1, 0));
        obs.range_is_depth = rangeIsDepth;
        std::mt19937 rng(77);
        std::uniform_int_distribution<int> depthMm(0, 7000);
        for (int r = 0; r < 72; ++r) {
            for (int c = 0; c < 96; ++c) {
                const int d = depthMm(rng);
                obs.rangeImage(r, c) = std::uint16_t(d < 400 ? 0 : (r / 8) * 300 + d / 10 + 1500);
            }
        }
        Aabb box;
        box.min = {-6, -6, -3};
        box.max = {6, 6, 4};
        const FlatPose robot = makePose(0.4, 0.3, 1.0, 0.5);
        MapParams returnsOnly;  // the cloud holds the pixels with a return only
        returnsOnly.noReturnIsFree = false;
        ExplorationMap a(returnsOnly, box), b(returnsOnly, box);
        a.insertObservation(obs, robot);
        const mrpt::poses::CPose3D sensor =
            mrpt::poses::CPose3D(0.4, 0.3, 1.0, 0.5, 0, 0) + obs.sensorPose;
        b.insertPointCloud({sensor.x(), sensor.y(), sensor.z()}, unprojectDepthImage(obs, robot));
        EXPECT_EQ(a.knownCellsInBox(), b.knownCellsInBox());
        EXPECT_GT(a.knownCellsInBox(), 1000u);
        std::uniform_real_distribution<double> u(-6.0, 6.0);
        for (int i = 0; i < 100000; ++i) {
            const Eigen::Vector3d p(u(rng), u(rng), 0.5 * u(rng));
            ASSERT_EQ(a.state(p), b.state(p))
                << p.transpose() << " range is depth " << rangeIsDepth;
        }
    }
}

}  // namespace
}  // namespace daep::mapping
