#include <gtest/gtest.h>

#include <cmath>

#include "daep/planning/BlindWatch.h"
#include "daep/planning/DynamicFrequencyMap.h"

namespace daep::planning {
namespace {

/** A 10 x 10 m box of 1 m cells with people seen walking along the lane x = 5.5. */
struct Walkway : ::testing::Test {
    Aabb box{{0, 0, 0}, {10, 10, 2}};
    DynamicFrequencyMap dfm{box, 1.0};
    BlindWatchParams params;
    BlindWatch watch;

    void SetUp() override {
        for (int y = 0; y < 10; ++y)
            dfm.add({5.5, y + 0.5});
        params.walkSpeed = 0.5;
        params.freshness = 1.0;
        params.maxAge = 4.0;
        params.range = 10.0;
        watch = BlindWatch(dfm, params);
    }
};

TEST_F(Walkway, OnlyCellsInsideTheFieldOfViewAndRangeAreSeen) {
    watch.see({{0.5, 5.5, 1.0}, 0.0}, M_PI / 2, 3.0);  // looking along +x, 90 degrees wide
    EXPECT_DOUBLE_EQ(watch.lastSeen({5.5, 5.5}), 3.0);
    EXPECT_DOUBLE_EQ(watch.lastSeen({5.5, 9.5}), 3.0);    // 45 degrees off the axis, ~6.4 m
    EXPECT_TRUE(std::isinf(watch.lastSeen({0.5, 9.5})));  // 90 degrees off: outside the view
    watch.see({{0.5, 5.5, 1.0}, M_PI}, M_PI / 2, 4.0);    // facing the wall behind
    EXPECT_DOUBLE_EQ(watch.lastSeen({5.5, 5.5}), 3.0);
}

TEST_F(Walkway, AStopBesideAWalkwayNeverSeenIsThreatenedFromItsNearestCell) {
    const double keepOut = 1.0;
    // Beside the lane at 0.5 m: an unseen walker there reaches it at once.
    const BlindThreat near = watch.worstThreat(dfm, {5.0, 5.5}, 10.0, 12.0, keepOut);
    EXPECT_TRUE(near.cell.isApprox(Eigen::Vector2d(5.5, 5.5)));
    // Reach: keep-out + speed * (age capped at 4 s + 2 s of stop) = 1 + 0.5 * 6 = 4 m.
    EXPECT_NEAR(near.excess, 4.0 - 0.5, 1e-12);
    // 4.5 m away from the lane the same walker cannot arrive before the stop ends.
    EXPECT_LE(watch.worstThreat(dfm, {1.0, 5.5}, 10.0, 12.0, keepOut).excess, 0.0);
}

TEST_F(Walkway, CellsSeenJustNowAreNoThreatButAgeAgain) {
    const double keepOut = 1.0;
    watch.see({{5.5, 0.2, 1.0}, M_PI / 2}, 0.2, 10.0);  // a narrow look straight up the lane
    EXPECT_LE(watch.worstThreat(dfm, {5.0, 5.5}, 10.5, 11.0, keepOut).excess, 0.0);
    // Two seconds later the lane is unseen again: 1 + 0.5 * (2 + 1) - 0.5.
    EXPECT_NEAR(watch.worstThreat(dfm, {5.0, 5.5}, 12.0, 13.0, keepOut).excess, 2.0, 1e-12);
}

TEST_F(Walkway, QuietCellsAreNoWalkway) {
    params.busyThreshold = 0.5;
    DynamicFrequencyMap mixed(box, 1.0);
    for (int k = 0; k < 10; ++k)
        mixed.add({5.5, 5.5});
    mixed.add({2.5, 5.5});  // seen once against ten: below the threshold
    watch = BlindWatch(mixed, params);
    const BlindThreat t = watch.worstThreat(mixed, {2.5, 5.0}, 10.0, 12.0, 1.0);
    EXPECT_TRUE(t.cell.isApprox(Eigen::Vector2d(5.5, 5.5)));
}

}  // namespace
}  // namespace daep::planning
