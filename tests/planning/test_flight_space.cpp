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
    const double radius = 0.3;
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
    EXPECT_TRUE(segmentFlyable(*map, drone, west, radius, true));
    EXPECT_FALSE(map->isSegmentFreeOrUnknown(drone + Eigen::Vector3d(-radius, 0, 0), west, radius));
    // Not when it is not known to be blocked, and not down towards the ledge.
    EXPECT_FALSE(segmentFlyable(*map, drone, west, radius, false));
    EXPECT_FALSE(segmentFlyable(*map, drone, {2.5, 3.0, 0.75}, radius, true));
    // Nor to an end without its full clearance.
    EXPECT_FALSE(segmentFlyable(*map, drone, {3.3, 3.0, 0.95}, radius, true));
}

}  // namespace
}  // namespace daep::planning
