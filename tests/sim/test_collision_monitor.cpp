#include <gtest/gtest.h>

#include <cmath>

#include "SimTestWorlds.h"
#include "daep/sim/CollisionMonitor.h"
#include "daep/world/RayCaster.h"

namespace daep::sim {
namespace {

const Eigen::Vector3d kDroneSize(0.4, 0.4, 0.1);
const Eigen::Vector3d kPersonSize(1.0, 1.0, 1.8);

FlatPose dronePose(double x, double y, double z, double yaw = 0.0) {
    FlatPose p;
    p.position = Eigen::Vector3d(x, y, z);
    p.yaw = yaw;
    return p;
}

world::PersonState person(double x, double y, double heading = 0.0) {
    world::PersonState p;
    p.position = Eigen::Vector2d(x, y);
    p.heading = heading;
    return p;
}

bool touches(const FlatPose& drone, const world::PersonState& p) {
    return CollisionMonitor::droneTouchesPerson(drone, kDroneSize, p, kPersonSize);
}

TEST(CollisionMonitor, AxisAlignedBoxes) {
    // Centres 0.7 apart along x: half sizes sum to 0.2 + 0.5.
    EXPECT_TRUE(touches(dronePose(0.69, 0, 1), person(0, 0)));
    EXPECT_FALSE(touches(dronePose(0.71, 0, 1), person(0, 0)));
    EXPECT_FALSE(touches(dronePose(0.5, 0.71, 1), person(0, 0)));
}

TEST(CollisionMonitor, HeightIntervals) {
    EXPECT_TRUE(touches(dronePose(0, 0, 1.84), person(0, 0)));   // bottom at 1.79
    EXPECT_FALSE(touches(dronePose(0, 0, 1.86), person(0, 0)));  // bottom at 1.81
    EXPECT_TRUE(touches(dronePose(0, 0, -0.04), person(0, 0)));
    EXPECT_FALSE(touches(dronePose(0, 0, -0.06), person(0, 0)));
}

TEST(CollisionMonitor, RotatedDroneReachesFurtherAlongItsDiagonal) {
    // A drone turned 45 deg reaches 0.2*sqrt(2) = 0.283 along x instead of 0.2.
    EXPECT_FALSE(touches(dronePose(0.75, 0, 1, 0.0), person(0, 0)));
    EXPECT_TRUE(touches(dronePose(0.75, 0, 1, M_PI / 4), person(0, 0)));
    EXPECT_FALSE(touches(dronePose(0.79, 0, 1, M_PI / 4), person(0, 0)));
}

TEST(CollisionMonitor, RotatedPersonReachesFurtherAlongItsDiagonal) {
    // Person turned 45 deg reaches 0.5*sqrt(2) = 0.707 along x; with the drone's 0.2: 0.907.
    EXPECT_TRUE(touches(dronePose(0.89, 0, 1), person(0, 0, M_PI / 4)));
    EXPECT_FALSE(touches(dronePose(0.92, 0, 1), person(0, 0, M_PI / 4)));
    EXPECT_FALSE(touches(dronePose(0.89, 0, 1), person(0, 0, 0.0)));
}

TEST(CollisionMonitor, SeparatingAxisFromTheRotatedBoxOnly) {
    // Person turned 45 deg is the diamond |x| + |y| <= 0.707. At (0.6, 0.6) the drone's nearest
    // corner (0.4, 0.4) is outside it although the world-axis projections still overlap.
    const auto p = person(0, 0, M_PI / 4);
    EXPECT_FALSE(touches(dronePose(0.6, 0.6, 1), p));
    EXPECT_TRUE(touches(dronePose(0.5, 0.5, 1), p));  // corner (0.3, 0.3): 0.6 < 0.707
}

TEST(CollisionMonitor, CountsOncePerContactEpisode) {
    CollisionMonitor monitor(kDroneSize, kPersonSize, nullptr);
    const std::vector<world::PersonState> people{person(0, 0)};
    monitor.update(0.0, dronePose(2, 0, 1), people);
    monitor.update(0.1, dronePose(0.6, 0, 1), people);
    monitor.update(0.2, dronePose(0.5, 0, 1), people);
    monitor.update(0.3, dronePose(0.6, 0, 1), people);
    EXPECT_EQ(monitor.personCollisions(), 1);
    ASSERT_EQ(monitor.events().size(), 1u);
    EXPECT_EQ(monitor.events()[0].personIndex, 0);
    EXPECT_DOUBLE_EQ(monitor.events()[0].start, 0.1);
    EXPECT_DOUBLE_EQ(monitor.events()[0].end, -1.0);

    monitor.update(0.4, dronePose(2, 0, 1), people);
    EXPECT_DOUBLE_EQ(monitor.events()[0].end, 0.4);
    monitor.update(0.5, dronePose(2, 0, 1), people);
    EXPECT_EQ(monitor.personCollisions(), 1);

    monitor.update(0.6, dronePose(0, 0.6, 1), people);
    EXPECT_EQ(monitor.personCollisions(), 2);
    ASSERT_EQ(monitor.events().size(), 2u);
    EXPECT_DOUBLE_EQ(monitor.events()[1].start, 0.6);
    EXPECT_DOUBLE_EQ(monitor.events()[1].end, -1.0);
    EXPECT_EQ(monitor.staticCollisions(), 0);
}

TEST(CollisionMonitor, TwoPeopleAtOnceCountTwice) {
    CollisionMonitor monitor(kDroneSize, kPersonSize, nullptr);
    // People 1.3 apart in x, drone between them touching both.
    std::vector<world::PersonState> people{person(-0.65, 0), person(5, 5), person(0.65, 0)};
    monitor.update(1.0, dronePose(0, 0, 1), people);
    EXPECT_EQ(monitor.personCollisions(), 2);
    ASSERT_EQ(monitor.events().size(), 2u);
    EXPECT_EQ(monitor.events()[0].personIndex, 0);
    EXPECT_EQ(monitor.events()[1].personIndex, 2);

    people[0].position.x() = -2.0;  // person 0 walks away, person 2 still in contact
    monitor.update(1.5, dronePose(0, 0, 1), people);
    EXPECT_DOUBLE_EQ(monitor.events()[0].end, 1.5);
    EXPECT_DOUBLE_EQ(monitor.events()[1].end, -1.0);
    EXPECT_EQ(monitor.personCollisions(), 2);
}

TEST(CollisionMonitor, StaticContactEpisodesAreCountedApart) {
    world::WorldSpec world;
    world.boxes = {test::box("wall", {2.5, 0, 1.5}, {1, 10, 3})};  // face at x = 2
    const world::StaticCollisionChecker checker(world);
    CollisionMonitor monitor(kDroneSize, kPersonSize, &checker);
    const std::vector<world::PersonState> nobody;

    monitor.update(0.0, dronePose(1.0, 0, 1), nobody);
    monitor.update(1.0, dronePose(1.85, 0, 1), nobody);
    monitor.update(2.0, dronePose(1.9, 0, 1), nobody);
    monitor.update(3.0, dronePose(1.7, 0, 1), nobody);
    monitor.update(4.0, dronePose(1.76, 0, 1, M_PI / 4), nobody);  // corner reaches 2.04
    EXPECT_EQ(monitor.staticCollisions(), 2);
    EXPECT_EQ(monitor.personCollisions(), 0);
    ASSERT_EQ(monitor.events().size(), 2u);
    EXPECT_EQ(monitor.events()[0].personIndex, -1);
    EXPECT_DOUBLE_EQ(monitor.events()[0].start, 1.0);
    EXPECT_DOUBLE_EQ(monitor.events()[0].end, 3.0);
    EXPECT_DOUBLE_EQ(monitor.events()[1].start, 4.0);
    EXPECT_DOUBLE_EQ(monitor.events()[1].end, -1.0);
}

TEST(CollisionMonitor, PeopleAndStaticContactsTogether) {
    world::WorldSpec world;
    world.boxes = {test::box("wall", {2.5, 0, 1.5}, {1, 10, 3})};
    const world::StaticCollisionChecker checker(world);
    CollisionMonitor monitor(kDroneSize, kPersonSize, &checker);
    const std::vector<world::PersonState> people{person(1.3, 0)};  // reaches x = 1.8
    monitor.update(0.5, dronePose(1.9, 0, 1), people);
    EXPECT_EQ(monitor.staticCollisions(), 1);
    EXPECT_EQ(monitor.personCollisions(), 1);
    EXPECT_EQ(monitor.events().size(), 2u);
}

}  // namespace
}  // namespace daep::sim
