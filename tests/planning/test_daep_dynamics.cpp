#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "PlanningTestUtil.h"
#include "daep/planning/DynamicFrequencyMap.h"
#include "daep/planning/DynamicObstacles.h"
#include "daep/planning/GainEvaluator.h"

namespace daep::planning {
namespace {

using perception::PersonForecast;

/** A person at `p` walking with velocity `v`, known exactly at time t0 (no uncertainty). */
PersonForecast walker(int id, Eigen::Vector2d p, Eigen::Vector2d v, double t0 = 0.0) {
    PersonForecast f;
    f.id = id;
    f.time = t0;
    f.state << p, v;
    return f;
}

SafetyParams exactSafety() {
    SafetyParams s;
    s.clearance = 0.0;
    s.sigmaInflation = 0.0;
    return s;
}

/** Flies from a to b at 0.5 m/s starting at `start`, no turn. */
TimedSegment fly(Eigen::Vector3d a, Eigen::Vector3d b, double start) {
    return timedSegment({a, 0.0}, {b, 0.0}, start, 0.5, 1.0);
}

TEST(TimedSegment, TurnsOnTheSpotThenFliesStraight) {
    const TimedSegment s = timedSegment({{0, 0, 1}, 0.0}, {{2, 0, 1}, M_PI / 2}, 10.0, 0.5, 1.0);
    EXPECT_DOUBLE_EQ(s.turnTime, M_PI / 2);
    EXPECT_DOUBLE_EQ(s.flyTime, 4.0);
    EXPECT_TRUE(s.positionAt(10.0 + 1.0).isApprox(Eigen::Vector3d(0, 0, 1)));
    EXPECT_TRUE(s.positionAt(10.0 + M_PI / 2 + 2.0).isApprox(Eigen::Vector3d(1, 0, 1)));
    EXPECT_TRUE(s.positionAt(100.0).isApprox(Eigen::Vector3d(2, 0, 1)));
}

TEST(TimedSegment, TheRestOfAMoveKeepsItsTimingAndPath) {
    const TimedSegment s = timedSegment({{0, 0, 1}, 0.0}, {{2, 0, 1}, M_PI / 2}, 10.0, 0.5, 1.0);
    const TimedSegment turning = s.after(11.0);  // one second into the quarter turn
    EXPECT_DOUBLE_EQ(turning.start, 11.0);
    EXPECT_DOUBLE_EQ(turning.turnTime, M_PI / 2 - 1.0);
    EXPECT_DOUBLE_EQ(turning.end(), s.end());
    const TimedSegment flying = s.after(10.0 + M_PI / 2 + 2.0);  // half way along
    EXPECT_DOUBLE_EQ(flying.turnTime, 0.0);
    EXPECT_TRUE(flying.from.isApprox(Eigen::Vector3d(1, 0, 1)));
    EXPECT_NEAR(flying.end(), s.end(), 1e-12);
    for (const double t : {14.0, 15.0, 16.0})
        EXPECT_TRUE(flying.positionAt(t).isApprox(s.positionAt(t)));
    EXPECT_DOUBLE_EQ(s.after(0.0).start, s.start);  // clamped to the move
    EXPECT_DOUBLE_EQ(s.after(99.0).start, s.end());
}

TEST(DynamicObstacles, AnEdgeThatCrossesAWalkerMidwayIsUnsafeThoughBothEndsAreClear) {
    // The drone flies 4 m along y in 8 s; a person walks along x and is at the crossing
    // point (0, 0) at t = 4 s, when the drone is there too.
    const DynamicObstacles people(exactSafety(), {walker(0, {-1.4, 0}, {0.35, 0})});
    const TimedSegment crossing = fly({0, -2, 1}, {0, 2, 1}, 0.0);
    EXPECT_FALSE(people.isSafe(crossing));
    // Node-only checks would pass it: at both ends the person is far from the drone.
    EXPECT_TRUE(people.isSafeToHover({0, -2, 1}, 0.0, 0.0));
    EXPECT_TRUE(people.isSafeToHover({0, 2, 1}, 8.0, 8.0));
    // The same edge flown 12 s later: the person has long passed.
    EXPECT_TRUE(people.isSafe(fly({0, -2, 1}, {0, 2, 1}, 12.0)));
    // Above the body (1.8 m plus half the drone's height) nothing touches.
    EXPECT_TRUE(people.isSafe(fly({0, -2, 1.9}, {0, 2, 1.9}, 0.0)));
}

TEST(DynamicObstacles, ClearanceIsTheSmallestGapBetweenGrownBodyAndDrone) {
    // Hovering 3 m from a person standing still: gap = 3 - footprint half diagonal - drone
    // half diagonal.
    SafetyParams s = exactSafety();
    const DynamicObstacles still(s, {walker(0, {3, 0}, {0, 0})});
    TimedSegment hover;
    hover.from = hover.to = {0, 0, 1};
    hover.turnTime = 2.0;
    const double body = 0.5 * std::sqrt(2.0) + 0.5 * std::hypot(0.4, 0.4);
    EXPECT_NEAR(still.clearance(hover), 3.0 - body, 1e-9);
    s.clearance = 0.5;
    EXPECT_NEAR(DynamicObstacles(s, {walker(0, {3, 0}, {0, 0})}).clearance(hover), 3.0 - body - 0.5,
                1e-9);
}

TEST(DynamicObstacles, BelowTheTopClimbingCountsAsAWayOutOnlyWhereTheCeilingAllowsIt) {
    // Just below the top of someone standing at the origin, 0.3 m and 0.6 m from them: the
    // drone is 0.25 m below the top (1.85 m), deeper than that inside the footprint.
    const double body = 0.5 * std::sqrt(2.0) + 0.5 * std::hypot(0.4, 0.4);
    TimedSegment near, far, over;
    near.from = near.to = {0.3, 0, 1.6};
    far.from = far.to = {0.6, 0, 1.6};
    over.from = over.to = {0.3, 0, 1.8 + 0.05 + 0.1};
    // Room above the people: the shorter way out is up, the same for both spots.
    const DynamicObstacles roomy(exactSafety(), {walker(0, {0, 0}, {0, 0})});
    EXPECT_NEAR(roomy.clearance(near), -0.25, 1e-9);
    EXPECT_NEAR(roomy.clearance(far), -0.25, 1e-9);
    // A 2 m box (centres up to 1.7 m): only sideways, and the farther spot has more gap.
    SafetyParams low = exactSafety();
    low.ceiling = 1.7;
    const DynamicObstacles lowRoom(low, {walker(0, {0, 0}, {0, 0})});
    EXPECT_NEAR(lowRoom.clearance(near), 0.3 - body, 1e-9);
    EXPECT_NEAR(lowRoom.clearance(far), 0.6 - body, 1e-9);
    // The sign, and so every safety check, is the same: above the top it is the vertical gap.
    EXPECT_NEAR(roomy.clearance(over), 0.1, 1e-9);
    EXPECT_NEAR(lowRoom.clearance(over), 0.1, 1e-9);
    EXPECT_EQ(roomy.isSafe(near), lowRoom.isSafe(near));
}

TEST(DynamicObstacles, OverTheHeadsTheGapKeptIsTheOverheadClearanceWhenSet) {
    // Flying 1.92 m high over someone standing at the origin: 7 cm over the top of the body
    // (1.8 m) plus half the drone (0.05 m).
    const TimedSegment over = fly({-2, 0, 1.92}, {2, 0, 1.92}, 0.0);
    SafetyParams s = exactSafety();
    s.clearance = 0.2;
    const DynamicObstacles usual(s, {walker(0, {0, 0}, {0, 0})});
    EXPECT_NEAR(usual.clearedHeight(), 1.85 + 0.2, 1e-12);
    EXPECT_FALSE(usual.isSafe(over));
    s.overheadClearance = 0.05;
    const DynamicObstacles low(s, {walker(0, {0, 0}, {0, 0})});
    EXPECT_NEAR(low.clearedHeight(), 1.85 + 0.05, 1e-12);
    EXPECT_NEAR(low.clearance(over), 1.92 - 1.9, 1e-9);
    EXPECT_TRUE(low.isSafe(over));
    // Sideways the clearance is unchanged.
    TimedSegment beside;
    beside.from = beside.to = {3, 0, 1};
    beside.turnTime = 1.0;
    EXPECT_NEAR(low.clearance(beside), usual.clearance(beside), 1e-12);
}

TEST(DynamicObstacles, SampledChecksAreConservativeForFastCrossings) {
    // Drone and person cross head-on between two samples: the slack must still catch it.
    SafetyParams s = exactSafety();
    s.timeStep = 1.0;
    const DynamicObstacles people(s, {walker(0, {2, 0}, {-0.35, 0})});
    EXPECT_FALSE(people.isSafe(fly({-1, 0, 1}, {3, 0, 1}, 0.0)));
}

TEST(DynamicObstacles, BodiesGrowWithThePredictionsSpreadUpToTheCap) {
    PersonForecast f = walker(0, {0, 0}, {0.35, 0});
    f.covariance.diagonal() << 0.01, 0.01, 0.04, 0.04;
    f.accelNoise = 0.02;
    SafetyParams s;
    s.sigmaInflation = 2.0;
    s.maxInflation = 1.0;
    s.clearance = 0.1;
    const DynamicObstacles people(s, {f});
    const double base = 0.5 * std::sqrt(2.0) + 0.5 * std::hypot(0.4, 0.4) + 0.1;
    EXPECT_NEAR(people.keepOutRadius(f, 0.0, 1.0), base + 2.0 * 0.1, 1e-9);
    double previous = 0.0;
    for (double t = 0.0; t <= 2.0; t += 0.5) {  // 2 sigma reaches the 1 m cap at ~2.4 s
        const double r = people.keepOutRadius(f, t, 1.0);
        EXPECT_GT(r, previous);
        previous = r;
    }
    EXPECT_NEAR(people.keepOutRadius(f, 20.0, 1.0), base + 1.0, 1e-9);
    EXPECT_NEAR(people.keepOutRadius(f, 0.0, 0.0), base - 0.1 + 0.2, 1e-9);
}

TEST(DynamicObstacles, PredictionsBeyondTheHorizonAreNotUsed) {
    SafetyParams s = exactSafety();
    s.horizon = 5.0;
    const DynamicObstacles people(s, {walker(0, {-3.5, 0}, {0.35, 0})});
    // The walker reaches x = 0 at t = 10 s: beyond the 5 s horizon, nothing is predicted.
    EXPECT_TRUE(people.isSafeToHover({0, 0, 1}, 9.0, 11.0));
    EXPECT_EQ(people.bodiesAt(10.0).size(), 0u);
    ASSERT_EQ(people.bodiesAt(4.0).size(), 1u);
    EXPECT_TRUE(people.bodiesAt(4.0)[0].center.isApprox(Eigen::Vector2d(-3.5 + 1.4, 0)));
}

/**
 * isSafe takes shortcuts (the largest body first, the last blocking walker first); its answer
 * must stay clearance(move) > 0, the full check of every walker, call after call.
 */
TEST(DynamicObstacles, IsSafeIsTheSignOfTheFullClearanceWhateverTheOrderOfCalls) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> where(-6.0, 6.0), speed(-0.5, 0.5), when(0.0, 12.0);
    std::vector<PersonForecast> people;
    for (int i = 0; i < 12; ++i) {
        PersonForecast f = walker(i, {where(rng), where(rng)}, {speed(rng), speed(rng)},
                                  i % 3 == 0 ? when(rng) : 0.0);
        f.covariance.diagonal() << 0.02 * i, 0.01 * i, 0.03, 0.05;
        f.covariance(0, 2) = f.covariance(2, 0) = -0.004 * i;  // position-velocity correlation
        f.accelNoise = 0.02;
        people.push_back(f);
    }
    for (const double cap : {1.0, 0.0, std::numeric_limits<double>::infinity()}) {
        SafetyParams s;
        s.maxInflation = cap;
        s.ceiling = 2.5;
        const DynamicObstacles bodies(s, people);
        int unsafe = 0;
        for (int i = 0; i < 4000; ++i) {
            const FlatPose a{{where(rng), where(rng), 0.5 + 0.5 * std::abs(speed(rng)) * 6}, 0.0};
            const FlatPose b{a.position + Eigen::Vector3d(speed(rng), speed(rng), 0) * 4, 1.0};
            const TimedSegment move = timedSegment(a, b, when(rng), 0.5, 1.0);
            for (const double scale : {1.0, 0.5}) {
                const bool safe = bodies.isSafe(move, scale);
                ASSERT_EQ(safe, bodies.clearance(move, scale) > 0.0) << i;
                unsafe += !safe;
            }
        }
        EXPECT_GT(unsafe, 400);  // both answers are exercised
        EXPECT_LT(unsafe, 7600);
    }
}

TEST(RayEntry, MeetsTheCylinderWhereGeometrySaysItShould) {
    const BodyOccluder body{{3, 0}, 0.5, 1.8};
    EXPECT_NEAR(rayEntry(body, {0, 0, 1}, {1, 0, 0}), 2.5, 1e-12);
    EXPECT_TRUE(std::isinf(rayEntry(body, {0, 0, 1}, {-1, 0, 0})));
    EXPECT_TRUE(std::isinf(rayEntry(body, {0, 0, 2.0}, {1, 0, 0})));  // passes above
    EXPECT_EQ(rayEntry(body, {3.1, 0, 1}, {1, 0, 0}), 0.0);           // starts inside
    // Down onto the top face: from (3, 0, 3) straight down enters at z = 1.8.
    EXPECT_NEAR(rayEntry(body, {3, 0, 3}, {0, 0, -1}), 1.2, 1e-12);
    const Eigen::Vector3d diag = Eigen::Vector3d(1, 0, 1).normalized();
    // From (0, 0, 0) rising at 45 deg: at the disc (x = 2.5) z = 2.5 > 1.8, no hit.
    EXPECT_TRUE(std::isinf(rayEntry(body, {0, 0, 0}, diag)));
}

/** Expected gain of one column with rays cut at `cut(dir)`, all space unknown. */
template <class Cut>
double unknownColumnGain(const GainEvaluator& g, int column, const Eigen::Vector3d& p,
                         const Aabb& box, const Cut& cut) {
    const GainParams& gp = g.params();
    std::vector<double> centres;
    for (int i = 0; i < g.columnCount(); ++i)
        centres.push_back((i + 0.5) * g.columnWidth());
    const RayCubature c(gp, centres);
    double gain = 0.0;
    for (int j = 0; j < c.rings; ++j) {
        const Eigen::Vector3d& dir = c.directions[column * c.rings + j];
        const double end = std::min(test::distanceToWall(box, p, dir), cut(dir));
        for (std::size_t k = 0; k < c.radii.size(); ++k)
            if (c.radii[k] <= end)
                gain += c.ringWeights[j] * c.shellWeights[k];
    }
    return gain;
}

TEST(DynamicGain, DropsExactlyByTheRaysABodyOccludes) {
    const Aabb room = test::box(0, 0, 0, 20, 20, 3);
    const auto map = test::makeMap(room);
    const Eigen::Vector3d p(10, 10, 1);
    const GainEvaluator g(GainParams{});
    const std::vector<BodyOccluder> bodies{{{12.5, 10.0}, 0.5, 1.8}};
    const std::vector<double> open = g.columns(*map, p);
    const std::vector<double> blocked = g.columns(*map, p, &bodies);
    int changed = 0;
    for (int i = 0; i < g.columnCount(); ++i) {
        const double expected = unknownColumnGain(
            g, i, p, room, [&](const Eigen::Vector3d& d) { return rayEntry(bodies[0], p, d); });
        EXPECT_NEAR(blocked[i], expected, 1e-9) << "column " << i;
        EXPECT_LE(blocked[i], open[i] + 1e-12);
        changed += blocked[i] < open[i] - 1e-9;
    }
    // Only the columns facing the body (+x, about +-12 deg) lose gain.
    EXPECT_GE(changed, 2);
    EXPECT_LE(changed, 4);
    EXPECT_LT(g.bestYaw(*map, p, &bodies).gain, g.bestYaw(*map, p).gain + 1e-9);
}

TEST(DynamicGain, OneMarchGivesBothViewsBitForBit) {
    // Walls the rays stop at, and bodies in front of and behind them.
    auto map = test::makeMap(test::box(-8, -8, -1, 8, 8, 3));
    const Aabb room = test::box(-3, -2, -1, 4, 3, 2);
    map->insertPointCloud({0.5, 0.5, 0.5}, test::roomScan(room, {0.5, 0.5, 0.5}, 2.0, 40.0));
    GainEvaluator g(GainParams{});
    g.setYawAngleBooster(2.0, 1.5);
    const Eigen::Vector3d p(1.3, -0.4, 0.2);
    const std::vector<BodyOccluder> bodies{
        {{2.3, -0.4}, 0.3, 1.8}, {{-1.0, 1.5}, 0.3, 1.8}, {{7.0, 6.0}, 0.3, 1.8}};
    const GainEvaluator::ColumnViews views = g.columnsOpenAndOccluded(*map, p, bodies);
    const std::vector<double> open = g.columns(*map, p);
    const std::vector<double> occluded = g.columns(*map, p, &bodies);
    EXPECT_EQ(views.open, open);
    EXPECT_EQ(views.occluded, occluded);
    EXPECT_NE(open, occluded);  // the near bodies hide something
}

TEST(GainEvaluator, BestYawIsTheFirstMaximumOfTheDegreeSweep) {
    auto map = test::makeMap(test::box(-8, -8, -1, 8, 8, 3));
    const Aabb room = test::box(-3, -2, -1, 4, 3, 2);
    map->insertPointCloud({0.5, 0.5, 0.5}, test::roomScan(room, {0.5, 0.5, 0.5}, 2.0, 40.0));
    const GainEvaluator g(GainParams{});
    for (const Eigen::Vector3d& p :
         {Eigen::Vector3d(1.3, -0.4, 0.2), Eigen::Vector3d(3.5, 2.5, 1.0)}) {
        const std::vector<double> cols = g.columns(*map, p);
        YawGain sweep{0.0, -1.0};
        for (int deg = -179; deg <= 180; ++deg) {
            const double gain = g.windowGain(cols, deg * M_PI / 180.0);
            if (gain > sweep.gain)
                sweep = {deg * M_PI / 180.0, gain};
        }
        const YawGain best = g.bestYaw(cols);
        EXPECT_EQ(best.yaw, sweep.yaw);
        EXPECT_EQ(best.gain, sweep.gain);
    }
}

TEST(BorderBoost, WeighsOnlySamplesNearTheBoxsSideFaces) {
    const Aabb room = test::box(0, 0, 0, 30, 30, 2);
    const auto map = test::makeMap(room);
    GainEvaluator plain(GainParams{});
    GainEvaluator boosted(GainParams{});
    boosted.setYawAngleBooster(6.0, 1.0);
    // Far from every side face: no change (the floor and ceiling do not count).
    const Eigen::Vector3d middle(15, 15, 1);
    EXPECT_NEAR(boosted.gainAtYaw(*map, middle, 0.0), plain.gainAtYaw(*map, middle, 0.0), 1e-9);
    // 3 m from the east face, looking at it: the last metre of every ray counts six times.
    const Eigen::Vector3d nearEast(27, 15, 1);
    const double p = plain.gainAtYaw(*map, nearEast, 0.0);
    const double b = boosted.gainAtYaw(*map, nearEast, 0.0);
    EXPECT_GT(b, 1.5 * p);
    EXPECT_LT(b, 6.0 * p);
}

TEST(DynamicFrequencyMap, CountsObservationsPerCellNormalisedByTheBusiest) {
    DynamicFrequencyMap dfm(test::box(-2, -2, 0, 2, 2, 2), 1.0);
    EXPECT_EQ(dfm.width(), 4);
    EXPECT_EQ(dfm.height(), 4);
    EXPECT_EQ(dfm.value({0.5, 0.5}), 0.0);  // nothing seen yet
    for (int k = 0; k < 4; ++k)
        dfm.add({0.5, 0.5});
    dfm.add({-1.5, 1.2});
    dfm.add({10, 10});  // outside: ignored
    EXPECT_DOUBLE_EQ(dfm.value({0.1, 0.9}), 1.0);
    EXPECT_DOUBLE_EQ(dfm.value({-1.9, 1.0}), 0.25);
    EXPECT_DOUBLE_EQ(dfm.value({1.5, -1.5}), 0.0);
    EXPECT_DOUBLE_EQ(dfm.value({10, 10}), 0.0);
    EXPECT_EQ(dfm.maxCount(), 4);
}

}  // namespace
}  // namespace daep::planning
