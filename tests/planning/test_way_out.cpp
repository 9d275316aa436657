// The way out of a corner: when a walker comes at the drone, the search finds the way that
// spends the least time inside the walker's predicted body.
#include <gtest/gtest.h>

#include "PlanningTestUtil.h"
#include "daep/common/Geometry.h"
#include "daep/perception/PersonTrack.h"
#include "daep/planning/DynamicObstacles.h"
#include "daep/planning/FlightSpace.h"
#include "daep/planning/WayOut.h"

namespace daep::planning {
namespace {

using perception::PersonForecast;

PersonForecast walker(Eigen::Vector2d p, Eigen::Vector2d v) {
    PersonForecast f;
    f.id = 0;
    f.time = 0.0;
    f.state << p, v;
    f.covariance.diagonal() << 1e-4, 1e-4, 1e-3, 1e-3;
    f.accelNoise = 0.02;
    return f;
}

struct WayOutRoom : ::testing::Test {
    WayOutRoom() : map(test::makeMap(room, 10.0)) {
        const Eigen::Vector3d centre(4.0, 3.0, 1.0);
        map->insertPointCloud(
            centre, test::roomScan(test::box(-0.1, -0.1, -0.1, 8.1, 6.1, 2.1), centre, 0.5));
        motion.speed = 0.5;
        motion.yawRate = 1.0;
    }
    const Aabb room = test::box(0, 0, 0, 8, 6, 2);
    std::unique_ptr<mapping::ExplorationMap> map;
    MotionLimits motion;
    const FlatPose drone{{1.0, 3.0, 1.0}, 0.0};  // by the west wall, facing east
    const double hoverUntil = 6.0;
};

TEST_F(WayOutRoom, ItStepsOutOfTheWayOfAWalkerComingAtTheDrone) {
    const DynamicObstacles bodies(SafetyParams{}, {walker({4.0, 3.0}, {-0.35, 0.0})});
    const std::optional<WayOut> way =
        findWayOut(*map, room, bodies, drone, 0.0, motion, hoverUntil, WayOutParams{});
    ASSERT_TRUE(way.has_value());
    // Staying, or backing off to the wall, the walker's body reaches the drone...
    const WayOut stay = judgeWay(bodies, drone.position, 0.0, {}, motion, hoverUntil);
    const WayOut back =
        judgeWay(bodies, drone.position, 0.0, {{0.6, 3.0, 1.0}}, motion, hoverUntil);
    EXPECT_GT(stay.exposure, 0.5);
    EXPECT_GT(back.exposure, 0.5);
    // ...the way out leaves its line in time, through free space.
    EXPECT_EQ(way->exposure, 0.0);
    EXPECT_GT(way->gap, 0.0);
    ASSERT_FALSE(way->path.empty());
    EXPECT_GT(std::abs(way->path.back().y() - 3.0), bodies.bodyKeepOut());
    Eigen::Vector3d at = drone.position;
    for (const Eigen::Vector3d& p : way->path) {
        EXPECT_TRUE(segmentFlyable(*map, at, p, WayOutParams{}.robotRadius,
                                   WayOutParams{}.bodyHalfHeight, false))
            << at.transpose() << " -> " << p.transpose();
        EXPECT_NEAR((p - at).norm(), 0.4, 0.4 * std::sqrt(3.0) - 0.4 + 1e-9);  // lattice steps
        at = p;
    }
    // The judgement of the way found agrees with the search's own.
    const WayOut again = judgeWay(bodies, drone.position, 0.0, way->path, motion, hoverUntil);
    EXPECT_DOUBLE_EQ(again.exposure, way->exposure);
    EXPECT_NEAR(again.length, way->length, 1e-9);
}

TEST_F(WayOutRoom, WithNobodyComingTheShortestWayIsOneStep) {
    const DynamicObstacles nobody(SafetyParams{}, {});
    const std::optional<WayOut> way =
        findWayOut(*map, room, nobody, drone, 0.0, motion, hoverUntil, WayOutParams{});
    ASSERT_TRUE(way.has_value());
    EXPECT_EQ(way->exposure, 0.0);
    EXPECT_EQ(way->path.size(), 1u);
    EXPECT_NEAR(way->length, 0.4, 1e-9);
}

}  // namespace
}  // namespace daep::planning
