// Leaving a blocked spot: a drone that finds itself closer to something than its radius (a
// person's imprint mapped below and beside it after it stopped) must still be able to leave.
#include <gtest/gtest.h>

#include "PlanningTestUtil.h"
#include "daep/planning/FlightSpace.h"

namespace daep::planning {
namespace {

/** Hits filling [lo, hi) on the 0.2 m grid, one per cell centre. */
void addBlock(std::vector<Eigen::Vector3f>& points, const Eigen::Vector3d& lo,
              const Eigen::Vector3d& hi) {
    for (double z = lo.z() + 0.1; z < hi.z(); z += 0.2)
        for (double y = lo.y() + 0.1; y < hi.y(); y += 0.2)
            for (double x = lo.x() + 0.1; x < hi.x(); x += 0.2)
                points.emplace_back(float(x), float(y), float(z));
}

struct HemmedIn : ::testing::Test {
    HemmedIn() : map(test::makeMap(room, 10.0)) {
        const Eigen::Vector3d centre(4.0, 3.0, 1.0);
        map->insertPointCloud(
            centre, test::roomScan(test::box(-0.1, -0.1, -0.1, 8.1, 6.1, 2.1), centre, 0.5));
        // An imprint east of the drone and a ledge of it under the drone, reaching west.
        std::vector<Eigen::Vector3f> imprint;
        addBlock(imprint, {4.2, 2.4, 0.6}, {5.0, 3.6, 1.2});
        addBlock(imprint, {3.0, 2.4, 0.6}, {4.2, 3.6, 0.8});
        map->insertPointCloud({4.0, 3.0, 1.9}, imprint);
    }
    const Aabb room = test::box(0, 0, 0, 8, 6, 2);
    std::unique_ptr<mapping::ExplorationMap> map;
    const double radius = 0.3, halfHeight = 0.05;
    const Eigen::Vector3d drone{4.05, 3.0, 0.95};  // 0.15 m from the imprint and the ledge
};

TEST_F(HemmedIn, TheClearanceIsTheDistanceToTheNearestOccupiedCell) {
    ASSERT_TRUE(map->isOccupied({4.3, 3.0, 0.9}));
    ASSERT_TRUE(map->isOccupied({3.5, 3.0, 0.7}));
    ASSERT_FALSE(map->isSegmentFree(drone, drone, radius));
    const double clear = clearanceFromOccupied(*map, drone, radius);
    EXPECT_GT(clear, 0.15 - radius / 64.0 - 1e-9);
    EXPECT_LE(clear, 0.15);
    const Eigen::Vector3d open(2.0, 3.0, 1.0);
    EXPECT_EQ(clearanceFromOccupied(*map, open, radius), radius);
    EXPECT_EQ(clearanceFromOccupied(*map, {4.5, 3.0, 0.9}, radius), -1.0);
}

TEST_F(HemmedIn, ItLeavesByAMoveThatComesNoCloserThanItIs) {
    // West along the ledge at its height: never closer than 0.15 m, and clear at the end. Past
    // its first radius the move still runs 0.15 m above the ledge, so skipping the first
    // radius alone would not let the drone go.
    const Eigen::Vector3d west(2.5, 3.0, 0.95);
    EXPECT_TRUE(segmentFlyable(*map, drone, west, radius, halfHeight, true));
    EXPECT_FALSE(map->isSegmentFreeOrUnknown(drone + Eigen::Vector3d(-radius, 0, 0), west, radius));
    // Not when it is not known to be blocked, and not down towards the ledge.
    EXPECT_FALSE(segmentFlyable(*map, drone, west, radius, halfHeight, false));
    EXPECT_FALSE(segmentFlyable(*map, drone, {2.5, 3.0, 0.75}, radius, halfHeight, true));
    // Nor to an end without its full clearance.
    EXPECT_FALSE(segmentFlyable(*map, drone, {3.3, 3.0, 0.95}, radius, halfHeight, true));
}

/** A drone 0.1 m west of an imprint, in a room mapped all around it, with `more` in it too. */
std::unique_ptr<mapping::ExplorationMap> besideAnImprint(const Eigen::Vector3d& drone,
                                                         const std::vector<Eigen::Vector3f>& more) {
    auto map = test::makeMap(test::box(0, 0, 0, 8, 6, 2), 10.0);
    map->insertPointCloud(drone,
                          test::roomScan(test::box(-0.1, -0.1, -0.1, 8.1, 6.1, 2.1), drone, 0.5));
    std::vector<Eigen::Vector3f> surfaces = more;
    addBlock(surfaces, {4.2, 2.6, 0.6}, {4.6, 3.4, 1.4});
    map->insertPointCloud({3.0, 2.0, 1.0}, surfaces);
    return map;
}

TEST(HemmedInBesideAnImprint, ALegPastTheEndOfAWallKeepsTheRadiusFromIt) {
    // A post stands 0.2 m beside the way west. The clearance the drone has where it is lets it
    // leave the imprint, not pass the post that close (a drone flew so into the end of a wall).
    const Eigen::Vector3d drone(4.1, 3.0, 1.0);
    std::vector<Eigen::Vector3f> post;
    addBlock(post, {2.0, 3.2, 0.0}, {2.4, 3.6, 2.0});
    const auto map = besideAnImprint(drone, post);
    const double radius = 0.3, halfHeight = 0.05;
    const double clear = clearanceFromOccupied(*map, drone, radius);
    ASSERT_NEAR(clear, 0.1, radius / 32.0);
    const Eigen::Vector3d pastThePost(1.0, 3.0, 1.0), wideOfIt(1.0, 2.5, 1.0);
    ASSERT_TRUE(map->isSegmentFreeOrUnknown(drone, pastThePost, clear));
    EXPECT_FALSE(segmentFlyable(*map, drone, pastThePost, radius, halfHeight, true));
    EXPECT_TRUE(segmentFlyable(*map, drone, wideOfIt, radius, halfHeight, true));
}

TEST(HemmedInBesideAnImprint, ALegOverAFloorOfHeadsKeepsItsBodyClearOfThem) {
    // A metre of mapped heads west of the drone, their tops 0.15 m below its way out, more
    // than the 0.1 m it has where it is: a drone 0.1 m tall passes over them (the trap of
    // hovering over mapped heads), one 0.4 m tall does not.
    std::vector<Eigen::Vector3f> heads;
    addBlock(heads, {2.8, 2.6, 0.4}, {3.8, 3.4, 0.8});
    const Eigen::Vector3d drone(4.1, 3.0, 0.95), west(1.5, 3.0, 0.95);
    const auto map = besideAnImprint(drone, heads);
    const double radius = 0.3;
    ASSERT_NEAR(clearanceFromOccupied(*map, drone, radius), 0.1, radius / 32.0);
    ASSERT_FALSE(map->isSegmentFreeOrUnknown(drone + (west - drone).normalized() * 2 * radius, west,
                                             radius));
    EXPECT_TRUE(segmentFlyable(*map, drone, west, radius, 0.05, true));
    EXPECT_FALSE(segmentFlyable(*map, drone, west, radius, 0.2, true));
}

}  // namespace
}  // namespace daep::planning

namespace daep::planning {
namespace {

/**
 * The Exhibition corner (detected people, seed 2): an untracked walker's side mapped as a sheet
 * of cells in the drone's own column, its own cell among them, after it stopped there.
 */
struct InAnImprint : ::testing::Test {
    InAnImprint() : map(test::makeMap(test::box(0, 0, 0, 8, 6, 2), 10.0)) {
        map->insertPointCloud(
            drone, test::roomScan(test::box(-0.1, -0.1, -0.1, 8.1, 6.1, 2.1), drone, 0.5));
        std::vector<Eigen::Vector3f> sheet;
        addBlock(sheet, {4.0, 2.4, 0.6}, {4.2, 3.2, 1.4});  // x column 4.0-4.2, y up to 3.2
        map->insertPointCloud({5.5, 2.8, 1.0}, sheet);
    }
    std::unique_ptr<mapping::ExplorationMap> map;
    const double radius = 0.3, halfHeight = 0.05;
    const Eigen::Vector3d drone{4.1, 3.12, 1.1};  // inside the sheet's top end cell
};

TEST_F(InAnImprint, ItLeavesByALineThatEntersNoFurtherOccupiedCell) {
    ASSERT_TRUE(map->isOccupied(drone));
    ASSERT_EQ(clearanceFromOccupied(*map, drone, radius), -1.0);
    // Away from the sheet, east or north: no further occupied cell on the way.
    EXPECT_TRUE(segmentFlyable(*map, drone, {5.2, 3.12, 1.1}, radius, halfHeight, true));
    EXPECT_TRUE(segmentFlyable(*map, drone, {4.1, 4.2, 1.1}, radius, halfHeight, true));
    // Along the sheet, south through it: the line enters its other cells.
    EXPECT_FALSE(segmentFlyable(*map, drone, {4.1, 1.8, 1.1}, radius, halfHeight, true));
    // Never when the drone is not known to be blocked.
    EXPECT_FALSE(segmentFlyable(*map, drone, {5.2, 3.12, 1.1}, radius, halfHeight, false));
}

TEST_F(InAnImprint, ItsBodyStillMeetsNothingNewOnTheWayOut) {
    // A post 0.08 m beside the way east: the line misses it, the body would not.
    std::vector<Eigen::Vector3f> post;
    addBlock(post, {5.0, 3.2, 0.0}, {5.2, 3.4, 2.0});
    map->insertPointCloud({5.5, 2.8, 1.0}, post);
    const Eigen::Vector3d east(6.0, 3.12, 1.1);
    ASSERT_TRUE(map->isSegmentFreeOrUnknown(drone + Eigen::Vector3d(0.11, 0, 0), east, 0.0));
    EXPECT_FALSE(segmentFlyable(*map, drone, east, radius, halfHeight, true));
    EXPECT_TRUE(segmentFlyable(*map, drone, {5.0, 4.8, 1.1}, radius, halfHeight, true));
}

TEST_F(InAnImprint, ItsLineEntersNoFurtherOccupiedCellWhereItsBodyWouldPass) {
    // The imprint two cells thick at the drone's height: east, the body's box meets no cell it
    // did not meet already, but the line runs on through the imprint's second cell.
    std::vector<Eigen::Vector3f> thicker;
    addBlock(thicker, {4.2, 2.4, 1.0}, {4.4, 3.2, 1.2});
    map->insertPointCloud({5.5, 2.8, 1.0}, thicker);
    ASSERT_TRUE(map->isOccupied({4.3, 3.1, 1.1}));
    ASSERT_TRUE(map->isSweptBoxClearOfNew(drone, {5.2, 3.12, 1.1}, {radius, radius, halfHeight}));
    EXPECT_FALSE(segmentFlyable(*map, drone, {5.2, 3.12, 1.1}, radius, halfHeight, true));
    EXPECT_TRUE(segmentFlyable(*map, drone, {4.1, 4.2, 1.1}, radius, halfHeight, true));
}

TEST(InATableTop, ADroneWhoseCellHoldsASurfaceDoesNotLeaveThroughIt) {
    // A table top mapped in the drone's own cell, 5-15 cm below its centre (outside its body,
    // so the map keeps it): which side of the drone it lies on, the cell cannot tell. Down
    // through it is no way out, though below it all is free and its body meets nothing new.
    auto map = test::makeMap(test::box(0, 0, 0, 8, 6, 2), 10.0);
    const Eigen::Vector3d drone(4.1, 3.1, 1.15);
    map->insertPointCloud(drone,
                          test::roomScan(test::box(-0.1, -0.1, -0.1, 8.1, 6.1, 2.1), drone, 0.5));
    std::vector<Eigen::Vector3f> table;
    addBlock(table, {3.0, 2.0, 1.0}, {5.0, 4.0, 1.2});
    map->insertPointCloud({4.0, 3.0, 1.9}, table);
    ASSERT_TRUE(map->isOccupied(drone));
    ASSERT_EQ(clearanceFromOccupied(*map, drone, 0.3), -1.0);
    const Eigen::Vector3d under(4.1, 3.1, 0.5);
    ASSERT_TRUE(map->isSegmentFree(under, under, 0.3));
    ASSERT_TRUE(map->isSweptBoxClearOfNew(drone, under, {0.3, 0.3, 0.05}));
    EXPECT_FALSE(segmentFlyable(*map, drone, under, 0.3, 0.05, true));
}

}  // namespace
}  // namespace daep::planning
