#include <gtest/gtest.h>

#include <cmath>

#include "PlanningTestUtil.h"
#include "daep/mapping/ExplorationMap.h"
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
    const double keepOut = 1.0;

    void SetUp() override {
        for (int y = 0; y < 10; ++y)
            dfm.add({5.5, y + 0.5});
        params.walkSpeed = 0.5;
        params.range = 10.0;
        watch = BlindWatch(dfm, params);
    }
    /** The camera at (x, y) looks along yaw with a narrow view at time t. */
    void look(double x, double y, double yaw, double t,
              const std::vector<Eigen::Vector2d>& people = {}) {
        watch.see({{x, y, 1.0}, yaw}, 0.2, t, dfm, people);
    }
    /** Looks at the wall behind x = 0, away from everything. */
    void lookAway(double t) { look(0.5, 5.5, M_PI, t); }
    double excess(const Eigen::Vector2d& stop, double now, double until) const {
        return watch.worstThreat(dfm, stop, now, until, keepOut).excess;
    }
};

TEST_F(Walkway, OnlyCellsInsideTheFieldOfViewAndRangeAreSeen) {
    watch.see({{0.5, 5.5, 1.0}, 0.0}, M_PI / 2, 3.0, dfm);  // along +x, 90 degrees wide
    EXPECT_DOUBLE_EQ(watch.lastSeen({5.5, 5.5}), 3.0);
    EXPECT_DOUBLE_EQ(watch.lastSeen({5.5, 9.5}), 3.0);       // 45 degrees off the axis, ~6.4 m
    EXPECT_TRUE(std::isinf(watch.lastSeen({0.5, 9.5})));     // 90 degrees off: outside the view
    watch.see({{0.5, 5.5, 1.0}, M_PI}, M_PI / 2, 4.0, dfm);  // facing the wall behind
    EXPECT_DOUBLE_EQ(watch.lastSeen({5.5, 5.5}), 3.0);
}

TEST_F(Walkway, ACellAWallHidesIsNotSeen) {
    // A wall across x = 3 for y in [4, 7], seen from (0.5, 5.5); the lane lies behind it.
    const std::unique_ptr<mapping::ExplorationMap> map = test::makeMap(box, 10.0);
    const Eigen::Vector3d eye{0.5, 5.5, 1.0};
    std::vector<Eigen::Vector3f> wall;
    for (double y = 4.0; y <= 7.0; y += 0.1)
        for (double z = 0.1; z <= 1.9; z += 0.1)
            wall.emplace_back(3.05f, float(y), float(z));
    map->insertPointCloud(eye, wall);
    watch.see({eye, 0.0}, M_PI / 2, 3.0, dfm, {}, map.get());
    EXPECT_TRUE(std::isinf(watch.lastSeen({5.5, 5.5})));  // straight behind the wall
    EXPECT_DOUBLE_EQ(watch.lastSeen({5.5, 9.5}), 3.0);    // past its end
    EXPECT_DOUBLE_EQ(watch.lastSeen({2.5, 5.5}), 3.0);    // in front of it
    watch.see({eye, 0.0}, M_PI / 2, 4.0, dfm);            // without the map, walls hide nothing
    EXPECT_DOUBLE_EQ(watch.lastSeen({5.5, 5.5}), 4.0);
}

TEST_F(Walkway, AWalkwayNeverSeenMayHoldSomeoneAnywhereNow) {
    // Beside the lane at 0.5 m: an unseen walker there reaches it at once.
    const BlindThreat near = watch.worstThreat(dfm, {5.0, 5.5}, 10.0, 12.0, keepOut);
    EXPECT_TRUE(near.cell.isApprox(Eigen::Vector2d(5.5, 5.5)));
    // Reach: keep-out + speed * 2 s of stop = 2 m.
    EXPECT_NEAR(near.excess, 2.0 - 0.5, 1e-12);
    // 4.5 m away from the lane the same walker cannot arrive before the stop ends.
    EXPECT_LE(excess({1.0, 5.5}, 10.0, 12.0), 0.0);
}

TEST_F(Walkway, AWalkwaySweptWholeStaysClearWhileNobodyCanWalkIn) {
    look(5.5, 0.2, M_PI / 2, 10.0);  // straight up the lane: every cell of it in view
    lookAway(10.2);
    EXPECT_TRUE(std::isinf(watch.unseenFrom({5.5, 5.5})));
    EXPECT_LE(excess({5.0, 5.5}, 10.2, 12.2), 0.0);
    lookAway(60.0);  // nobody was seen and nobody could come: still clear a minute on
    EXPECT_LE(excess({5.0, 5.5}, 60.0, 62.0), 0.0);
}

TEST_F(Walkway, AnUnseenWalkerWalksIntoTheSweptPartAtWalkingSpeed) {
    params.range = 5.0;  // sees cells y = 0.5 ... 4.5 of the lane only
    watch = BlindWatch(dfm, params);
    look(5.5, 0.0, M_PI / 2, 10.0);
    EXPECT_DOUBLE_EQ(watch.lastSeen({5.5, 4.5}), 10.0);
    EXPECT_TRUE(std::isinf(watch.lastSeen({5.5, 5.5})));
    lookAway(10.2);
    // From the unseen half, a cell's width every 2 s: at once next to it, 8 s later at y = 0.5.
    EXPECT_DOUBLE_EQ(watch.unseenFrom({5.5, 4.5}), 10.0);
    EXPECT_DOUBLE_EQ(watch.unseenFrom({5.5, 0.5}), 18.0);
    EXPECT_LE(excess({5.0, 0.5}, 10.2, 12.2), 0.0);
    // At 17 s the walker is at y = 1.5 and can step to the stop's cell by 18 s.
    EXPECT_NEAR(excess({5.0, 0.5}, 17.0, 19.0), keepOut + 0.5 * 1.0 - 0.5, 1e-12);
    // Looking again clears what is in view; the unseen half is a source still.
    look(5.5, 0.0, M_PI / 2, 20.0);
    EXPECT_LE(excess({5.0, 0.5}, 20.0, 22.0), 0.0);
}

TEST_F(Walkway, SomeoneSeenWalksOnFromWhereTheCameraLeftThem) {
    look(5.5, 0.2, M_PI / 2, 10.0);
    look(5.5, 0.2, M_PI / 2, 11.0, {{5.5, 5.5}});  // a walker at the lane's middle
    lookAway(11.2);
    EXPECT_DOUBLE_EQ(watch.unseenFrom({5.5, 5.5}), 11.0);  // may still be there
    EXPECT_DOUBLE_EQ(watch.unseenFrom({5.5, 6.5}), 13.0);  // one cell on, 2 s later
    EXPECT_DOUBLE_EQ(watch.unseenFrom({5.5, 9.5}), 19.0);
    const BlindThreat t = watch.worstThreat(dfm, {5.0, 6.5}, 11.2, 13.2, keepOut);
    EXPECT_TRUE(t.cell.isApprox(Eigen::Vector2d(5.5, 5.5)));
    EXPECT_NEAR(t.excess, keepOut + 0.5 * 2.0 - std::hypot(0.5, 1.0), 1e-12);
    EXPECT_LE(excess({5.0, 9.5}, 11.2, 13.2), 0.0);  // too far to walk before 13.2 s
}

TEST_F(Walkway, SomeoneSeenWalksOnAcrossACellTheCameraNeverSawAnyoneIn) {
    // The lane x = 5.5 with its cell y = 5.5 quiet: nobody was seen there, people were seen
    // on both sides. A walker left at y = 3.5 crosses it as any other cell of the lane.
    DynamicFrequencyMap gap(box, 1.0);
    for (int y = 0; y < 10; ++y)
        if (y != 5)
            gap.add({5.5, y + 0.5});
    watch = BlindWatch(gap, params);
    watch.see({{5.5, 0.2, 1.0}, M_PI / 2}, 0.2, 10.0, gap);
    watch.see({{5.5, 0.2, 1.0}, M_PI / 2}, 0.2, 11.0, gap, {{5.5, 3.5}});
    watch.see({{0.5, 5.5, 1.0}, M_PI}, 0.2, 11.2, gap);
    EXPECT_DOUBLE_EQ(watch.unseenFrom({5.5, 5.5}), 15.0);
    EXPECT_DOUBLE_EQ(watch.unseenFrom({5.5, 6.5}), 17.0);
    EXPECT_GT(watch.worstThreat(gap, {5.0, 6.5}, 16.0, 18.0, keepOut).excess, 0.0);
    // Beside the lane, quiet cells with a busy cell on one side only are no walkway: a stop
    // 2 m off the lane is just out of a walker's reach in 2 s (1 m a walkway at x = 4.5 gives).
    watch = BlindWatch(gap, params);
    EXPECT_NEAR(watch.worstThreat(gap, {3.5, 2.5}, 10.0, 12.0, keepOut).excess, 0.0, 1e-12);
}

TEST_F(Walkway, QuietCellsAreNoWalkway) {
    DynamicFrequencyMap mixed(box, 1.0);
    for (int k = 0; k < 10; ++k)
        mixed.add({5.5, 5.5});
    mixed.add({2.5, 5.5});  // seen once against ten
    for (const double threshold : {0.05, 0.5}) {
        params.busyThreshold = threshold;
        watch = BlindWatch(mixed, params);
        const BlindThreat t = watch.worstThreat(mixed, {2.5, 5.0}, 10.0, 12.0, keepOut);
        if (threshold < 0.1)
            EXPECT_TRUE(t.cell.isApprox(Eigen::Vector2d(2.5, 5.5)));
        else  // the busy cell is 3 m away, beyond a 2 s walk plus the keep-out
            EXPECT_LE(t.excess, 0.0);
    }
}

TEST_F(Walkway, APersonLostIsFollowedOffTheWalkwaysForBlindLostS) {
    // A walker measured 3 m west of the lane, at (2.5, 5.5), then lost as the camera turns
    // away: nobody was ever seen walking there, yet they walk on from where they were.
    for (const double lostTime : {30.0, 0.0}) {
        params.lostTime = lostTime;
        watch = BlindWatch(dfm, params);
        look(2.5, 0.2, M_PI / 2, 11.0, {{2.5, 5.5}});
        lookAway(11.2);
        EXPECT_TRUE(std::isinf(watch.unseenFrom({2.5, 7.5})));  // no walkway
        if (lostTime == 0.0) {
            EXPECT_TRUE(std::isinf(watch.lostFrom({2.5, 7.5}, 12.0)));
            EXPECT_LE(excess({2.0, 7.5}, 15.0, 17.0), 0.0);
            continue;
        }
        EXPECT_DOUBLE_EQ(watch.lostFrom({2.5, 5.5}, 12.0), 11.0);  // may still be there
        EXPECT_DOUBLE_EQ(watch.lostFrom({2.5, 7.5}, 12.0), 15.0);  // 2 m on, 4 s later
        const BlindThreat t = watch.worstThreat(dfm, {2.0, 7.5}, 15.0, 17.0, keepOut);
        EXPECT_TRUE(t.lost);
        EXPECT_NEAR(t.excess, keepOut + 0.5 * 2.0 - 0.5, 1e-12);
        // Looked at, the cell is clear until they could walk in again from where it missed.
        look(2.5, 0.2, M_PI / 2, 16.0);
        EXPECT_TRUE(std::isinf(watch.lostFrom({2.5, 7.5}, 16.0)));
        lookAway(16.2);
        EXPECT_GT(watch.lostFrom({2.5, 7.5}, 16.2), 16.2);
        // Followed for blind_lost_s from their last measurement (11 s), then no longer.
        EXPECT_LE(excess({2.0, 7.5}, 41.5, 43.5), 0.0);
        EXPECT_TRUE(std::isinf(watch.lostFrom({2.5, 7.5}, 41.5)));
    }
}

}  // namespace
}  // namespace daep::planning
