#include <gtest/gtest.h>

#include <cmath>

#include "daep/sim/Drone.h"

namespace daep::sim {
namespace {

FlatPose pose(double x, double y, double z, double yaw) {
    FlatPose p;
    p.position = Eigen::Vector3d(x, y, z);
    p.yaw = yaw;
    return p;
}

DroneParams params() {
    DroneParams p;
    p.speed = 0.5;
    p.yawRate = 1.0;
    return p;
}

TEST(Drone, TurnsFirstThenFliesStraight) {
    Drone drone(params(), pose(0, 0, 1, 0));
    drone.setGoal(pose(2, 0, 1, M_PI / 2));  // turn pi/2 (1.5708 s), then 2 m (4 s)

    EXPECT_DOUBLE_EQ(drone.advance(1.0), 1.0);
    EXPECT_NEAR(drone.pose().yaw, 1.0, 1e-12);
    EXPECT_TRUE(drone.pose().position.isApprox(Eigen::Vector3d(0, 0, 1)));

    EXPECT_DOUBLE_EQ(drone.advance(1.0), 1.0);  // 0.5708 s turning, 0.4292 s flying
    EXPECT_DOUBLE_EQ(drone.pose().yaw, M_PI / 2);
    EXPECT_NEAR(drone.pose().position.x(), 0.5 * (2.0 - M_PI / 2), 1e-12);
    EXPECT_DOUBLE_EQ(drone.pose().position.y(), 0.0);
    EXPECT_TRUE(drone.hasGoal());
}

TEST(Drone, ReachesGoalExactlyAndReportsTimeUsed) {
    Drone drone(params(), pose(1, 1, 1, 0.2));
    const FlatPose goal = pose(1, 4, 2, 0.2);
    drone.setGoal(goal);
    const double expected = std::sqrt(10.0) / 0.5;

    const double used = drone.advance(100.0);
    EXPECT_NEAR(used, expected, 1e-12);
    EXPECT_FALSE(drone.hasGoal());
    EXPECT_EQ(drone.pose().position, goal.position);
    EXPECT_EQ(drone.pose().yaw, goal.yaw);
    EXPECT_EQ(drone.advance(1.0), 0.0);  // no goal: no motion, no time used
    EXPECT_EQ(drone.pose().position, goal.position);
}

TEST(Drone, TurnsTheShortWayAcrossPi) {
    Drone drone(params(), pose(0, 0, 1, 3.0));
    drone.setGoal(pose(0, 0, 1, -3.0));  // 0.283 rad counter-clockwise through pi
    drone.advance(0.1);
    EXPECT_NEAR(drone.pose().yaw, 3.1, 1e-12);
    drone.advance(0.1);
    EXPECT_NEAR(drone.pose().yaw, wrapAngle(3.2), 1e-12);
    const double used = drone.advance(1.0);
    EXPECT_NEAR(used, 2.0 * M_PI - 6.0 - 0.2, 1e-12);
    EXPECT_FALSE(drone.hasGoal());
    EXPECT_EQ(drone.pose().yaw, -3.0);
}

TEST(Drone, SmallStepsMatchOneBigStep) {
    const FlatPose start = pose(-1, 2, 1.5, -2.5);
    const FlatPose goal = pose(3, -1, 0.5, 1.9);
    Drone big(params(), start);
    Drone small(params(), start);
    big.setGoal(goal);
    small.setGoal(goal);

    const double horizon = 7.3;  // mid-flight
    big.advance(horizon);
    double total = 0.0;
    for (int i = 0; i < 730; ++i) {
        total += small.advance(0.01);
    }
    EXPECT_NEAR(total, horizon, 1e-9);
    EXPECT_NEAR(small.pose().yaw, big.pose().yaw, 1e-9);
    EXPECT_LT((small.pose().position - big.pose().position).norm(), 1e-9);

    double smallTotal = total;
    while (small.hasGoal()) {
        smallTotal += small.advance(0.01);
    }
    const double bigTotal = horizon + big.advance(100.0);
    EXPECT_NEAR(smallTotal, Drone::travelTime(start, goal, params()), 1e-9);
    EXPECT_NEAR(bigTotal, Drone::travelTime(start, goal, params()), 1e-9);
    EXPECT_EQ(small.pose().position, goal.position);
}

TEST(Drone, TravelTimeIsTurnPlusFlight) {
    const DroneParams p = params();
    EXPECT_NEAR(Drone::travelTime(pose(0, 0, 0, 3.0), pose(3, 4, 0, -3.0), p),
                (2.0 * M_PI - 6.0) / 1.0 + 5.0 / 0.5, 1e-12);
    EXPECT_EQ(Drone::travelTime(pose(1, 1, 1, 0.5), pose(1, 1, 1, 0.5), p), 0.0);
}

TEST(Drone, RejectsNonPositiveRates) {
    DroneParams p = params();
    p.speed = 0.0;
    EXPECT_THROW(Drone(p, FlatPose{}), std::invalid_argument);
}

}  // namespace
}  // namespace daep::sim
