#include <gtest/gtest.h>

#include "PlanningTestUtil.h"
#include "daep/planning/FlightSpace.h"
#include "daep/planning/OverHeads.h"

namespace daep::planning {
namespace {

/** An 8 x 4 x 2.5 m box under a 2.7 m ceiling, seen from (2, 2, 1); 2.1 m clears the heads. */
struct OverHeads : test::HalfKnownRoomMap {
    void SetUp() override {
        map = test::halfSeenRoom(2.5, 2.7);
        space.map = map.get();
        space.radius = 0.3;
        space.height = 2.1;
    }
    static Waypoint stop(double x, double y, double z, double yaw = 0.0) {
        return {{{x, y, z}, yaw}, 0.0};
    }
    OverHeadsSpace space;
};

TEST_F(OverHeads, StopsAreRaisedWhereTheirLegsStayInKnownFreeSpace) {
    // The first two stops can go up; the third lies in the unseen east half, so it stays, and
    // so does the second, whose leg to the third would cross unknown space from up there.
    std::vector<Waypoint> stops{stop(2.5, 2.0, 1.0), stop(3.0, 2.0, 1.2), stop(6.5, 2.0, 1.0)};
    ASSERT_FALSE(segmentFlyable(*map, {3.0, 2.0, 2.1}, {6.5, 2.0, 1.0}, 0.3, 0.05, false));
    ASSERT_TRUE(raiseStops(space, root, stops));
    EXPECT_TRUE(stops[0].pose.position.isApprox(Eigen::Vector3d(2.5, 2.0, 2.1)));
    EXPECT_DOUBLE_EQ(stops[1].pose.position.z(), 1.2);
    EXPECT_DOUBLE_EQ(stops[2].pose.position.z(), 1.0);
    // Already high, or no room: nothing to raise.
    std::vector<Waypoint> high{stop(2.5, 2.0, 2.1)};
    EXPECT_FALSE(raiseStops(space, root, high));
    space.height = 2.45;  // the drone's ball would reach the ceiling
    std::vector<Waypoint> low{stop(2.5, 2.0, 1.0)};
    EXPECT_FALSE(raiseStops(space, root, low));
    EXPECT_DOUBLE_EQ(low[0].pose.position.z(), 1.0);
}

TEST_F(OverHeads, BetweenAHighAndALowStopTheDroneStaysHighAsLongAsItCan) {
    // Up from the drone (low) to a high stop: climb at once. Down to a low one: drop at its end.
    const std::vector<Waypoint> stops{stop(3.0, 2.5, 2.1, 0.5), stop(3.5, 1.5, 1.0, -1.1)};
    const std::vector<Waypoint> way = stayHigh(space, root, stops);
    ASSERT_EQ(way.size(), 4u);
    EXPECT_TRUE(way[0].pose.position.isApprox(Eigen::Vector3d(2.0, 2.0, 2.1)));
    EXPECT_DOUBLE_EQ(way[0].pose.yaw, 0.5);  // the leg's heading: no extra turn
    EXPECT_TRUE(way[1].pose.position.isApprox(stops[0].pose.position));
    EXPECT_TRUE(way[2].pose.position.isApprox(Eigen::Vector3d(3.5, 1.5, 2.1)));
    EXPECT_DOUBLE_EQ(way[2].pose.yaw, -1.1);
    EXPECT_TRUE(way[3].pose.position.isApprox(stops[1].pose.position));
    // Level legs, and climbs on the spot, are flown as they are.
    const std::vector<Waypoint> level{stop(2.0, 2.0, 2.1), stop(3.0, 2.0, 2.1)};
    EXPECT_EQ(stayHigh(space, root, level).size(), 2u);
}

TEST_F(OverHeads, WhereTheLegsEndCannotBeFlownHighTheDropComesEarlier) {
    // A low stop under a small shelf at 2 m: the drone cannot fly over it, nor over the point
    // three quarters along the leg (its ball would touch the shelf), so it drops half way.
    std::vector<Eigen::Vector3f> shelf;
    for (double x = 3.45; x <= 3.8; x += 0.1)
        for (double y = 1.8; y <= 2.2; y += 0.1)
            shelf.emplace_back(float(x), float(y), 2.0f);
    map->insertPointCloud({2.0, 2.0, 1.0}, shelf);
    const Eigen::Vector3d high(2.0, 2.0, 2.1);
    ASSERT_FALSE(segmentFlyable(*map, high, {3.6, 2.0, 2.1}, 0.3, 0.05, false));
    ASSERT_FALSE(segmentFlyable(*map, high, {3.2, 2.0, 2.1}, 0.3, 0.05, false));
    const std::vector<Waypoint> way = stayHigh(space, high, {stop(3.6, 2.0, 1.0)});
    ASSERT_EQ(way.size(), 2u);
    EXPECT_TRUE(way[0].pose.position.isApprox(Eigen::Vector3d(2.8, 2.0, 2.1)));
    EXPECT_TRUE(segmentFlyable(*map, way[0].pose.position, way[1].pose.position, 0.3, 0.05, false));
}

TEST_F(OverHeads, AWayOverTheHeadsEndsBeforeItGoesDownAmongThePeopleAfterALongFlight) {
    const Eigen::Vector3d high(2.0, 2.0, 2.1), low(2.0, 2.0, 1.0);
    // 2.5 m flown over the heads, then down: it ends where it would go down.
    EXPECT_EQ(beforeDescent(space, high, {stop(4.5, 2.0, 2.1), stop(5.0, 2.0, 1.0)}), 1u);
    EXPECT_EQ(beforeDescent(space, low,
                            {stop(2.0, 2.0, 2.1), stop(3.5, 2.0, 2.1), stop(4.5, 2.0, 2.1),
                             stop(4.5, 2.0, 1.0), stop(5.0, 2.0, 2.1)}),
              3u);
    // A short flight up there (1 m), going down from where the drone is, staying up or low:
    // as planned.
    EXPECT_EQ(beforeDescent(space, high, {stop(3.0, 2.0, 2.1), stop(3.5, 2.0, 1.0)}), 2u);
    EXPECT_EQ(beforeDescent(space, high, {stop(2.0, 2.0, 1.0), stop(5.0, 2.0, 1.0)}), 2u);
    EXPECT_EQ(beforeDescent(space, low, {stop(3.0, 2.0, 2.1), stop(6.0, 2.0, 2.1)}), 2u);
    EXPECT_EQ(beforeDescent(space, low, {stop(5.0, 2.0, 1.0)}), 1u);
    // Only the flight since the drone was last down counts.
    EXPECT_EQ(beforeDescent(space, high,
                            {stop(4.5, 2.0, 2.1), stop(4.5, 2.0, 1.0), stop(5.0, 2.0, 2.1),
                             stop(5.5, 2.0, 1.0)}),
              1u);
    EXPECT_EQ(beforeDescent(space, low,
                            {stop(3.0, 2.0, 1.0), stop(3.0, 2.0, 2.1), stop(4.0, 2.0, 2.1),
                             stop(4.0, 2.0, 1.0)}),
              4u);
}

TEST_F(OverHeads, AClimbOnTheSpotIsFlownBeforeTheTurnItComesWith) {
    // A move turns first, then flies: turning 3 rad below the heads would leave the drone
    // there 3 s longer. Climb with the heading it has, then turn up there.
    const FlatPose low{{2.0, 2.0, 1.0}, -1.4};
    const std::vector<Waypoint> way =
        climbBeforeTurning(space, low, {stop(2.0, 2.0, 2.1, 1.6), stop(3.0, 2.0, 2.1, 1.6)});
    ASSERT_EQ(way.size(), 3u);
    EXPECT_TRUE(way[0].pose.position.isApprox(Eigen::Vector3d(2.0, 2.0, 2.1)));
    EXPECT_DOUBLE_EQ(way[0].pose.yaw, -1.4);
    EXPECT_DOUBLE_EQ(way[1].pose.yaw, 1.6);
    EXPECT_TRUE(way[1].pose.position.isApprox(way[0].pose.position));
    // The same further on: a low stop, then up from it.
    EXPECT_EQ(climbBeforeTurning(space, {{2.0, 2.0, 2.1}, 0.0},
                                 {stop(3.0, 2.0, 1.0, 0.0), stop(3.0, 2.0, 2.1, 1.0)})
                  .size(),
              3u);
    // No turn, a leg across (the drone faces where it flies), a drop, or already up there:
    // flown as planned.
    for (const auto& [from, to] : {std::pair{low, stop(2.0, 2.0, 2.1, -1.4)},
                                   {low, stop(3.0, 2.0, 2.1, 1.6)},
                                   {FlatPose{{2.0, 2.0, 2.1}, 0.0}, stop(2.0, 2.0, 1.0, 1.6)},
                                   {FlatPose{{2.0, 2.0, 2.1}, 0.0}, stop(2.0, 2.0, 2.1, 1.6)}})
        EXPECT_EQ(climbBeforeTurning(space, from, {to}).size(), 1u);
}

}  // namespace
}  // namespace daep::planning
