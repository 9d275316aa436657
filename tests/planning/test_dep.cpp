#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "PlanningTestUtil.h"
#include "daep/common/Error.h"
#include "daep/planning/DepPlanner.h"
#include "daep/planning/Planner.h"
#include "daep/planning/PlannerRegistry.h"
#include "daep/planning/Roadmap.h"
#include "daep/planning/YawBinnedGain.h"

namespace daep::planning {
namespace {

using test::box;
using test::contextFor;

DepParams depParams(bool replan = true) {
    const auto cfg = test::configFromText(test::defaultsText());
    DepParams p = DepParams::fromConfig(*cfg);
    p.replan = replan;
    return p;
}

GainParams gainParams() {
    return GainParams::fromConfig(*test::configFromText(test::defaultsText()));
}

class DepHalfKnownRoom : public test::HalfKnownRoomMap {};

TEST(DepConfig, RegisteredAndReadsItsSection) {
    const auto cfg = test::configFromText(test::defaultsText());
    const auto names = plannerNames();
    EXPECT_NE(std::find(names.begin(), names.end(), "dep"), names.end());
    EXPECT_EQ(createPlanner("dep", *cfg, 1)->name(), "dep");
    const DepParams p = DepParams::fromConfig(*cfg);
    EXPECT_DOUBLE_EQ(p.edgeLength, 1.5);
    EXPECT_EQ(p.neighbours, 15);
    EXPECT_DOUBLE_EQ(p.nodeSpacing, 0.8);
    EXPECT_EQ(p.yawBins, 32);
    const auto missing = test::configFromText(test::editKey(test::defaultsText(), "dep", "replan"));
    EXPECT_THROW(DepParams::fromConfig(*missing), InputError);
    const std::string big = "2.0";
    const auto bad =
        test::configFromText(test::editKey(test::defaultsText(), "dep", "node_spacing", &big));
    EXPECT_THROW(DepParams::fromConfig(*bad), InputError);
}

TEST_F(DepHalfKnownRoom, RoadmapGrowsIncrementallyWithValidNodesAndEdges) {
    DepPlanner planner(depParams(), gainParams(), 5);
    const PlanningContext c = contextFor(*map, root);
    planner.plan(c);
    const int first = planner.roadmap().size();
    ASSERT_GT(first, 5);
    planner.plan(c);  // same map, same pose: the roadmap is kept and grows
    const Roadmap& rm = planner.roadmap();
    EXPECT_GE(rm.size(), first);
    const DepParams& p = planner.params();
    for (int i = 0; i < rm.size(); ++i) {
        const RoadmapNode& n = rm.node(i);
        if (n.anchor)
            continue;
        EXPECT_TRUE(map->isSegmentFree(n.position, n.position, p.robotRadius)) << i;
        for (int j = 0; j < i; ++j)
            EXPECT_GE((rm.node(j).position - n.position).norm(), p.nodeSpacing - 1e-9);
        EXPECT_FALSE(rm.links(i).empty()) << "node " << i << " is isolated";
    }
    for (int e = 0; e < rm.edgeCount(); ++e) {
        const RoadmapEdge& edge = rm.edge(e);
        const Eigen::Vector3d a = rm.node(edge.a).position, b = rm.node(edge.b).position;
        EXPECT_LE(edge.length, p.edgeLength + 1e-9);
        if (rm.node(edge.a).anchor || rm.node(edge.b).anchor)
            continue;
        EXPECT_TRUE(planner.insideCone(a, b)) << e;
        EXPECT_TRUE(map->isSegmentFree(a, b, p.robotRadius)) << e;
    }
    for (int i = 0; i < rm.size(); ++i)
        EXPECT_LE(int(rm.links(i).size()), 2 * p.neighbours);
}

TEST(DepCone, RejectsEdgesSteeperThanHalfTheVerticalFov) {
    DepPlanner planner(depParams(), gainParams(), 1);
    const double half = 0.5 * gainParams().vfov;
    const Eigen::Vector3d a(0, 0, 1);
    const auto at = [&](double elevation) {
        return Eigen::Vector3d(a + Eigen::Vector3d(std::cos(elevation), 0, std::sin(elevation)));
    };
    EXPECT_TRUE(planner.insideCone(a, at(half - 0.01)));
    EXPECT_TRUE(planner.insideCone(a, at(-(half - 0.01))));
    EXPECT_FALSE(planner.insideCone(a, at(half + 0.01)));
    EXPECT_FALSE(planner.insideCone(a, at(-(half + 0.01))));
}

TEST(YawBinnedGainTest, AllUnknownGivesTheExactFrustumVolumeInEveryBin) {
    const auto map = test::makeMap(box(-10, -10, -10, 10, 10, 10));
    const GainParams g = gainParams();
    const YawBinnedGain gain(g, 32, CellWeights{});
    const std::vector<double> bins = gain.evaluate(*map, Eigen::Vector3d(0.1, 0.1, 0.1));
    ASSERT_EQ(bins.size(), 32u);
    const double phiMin = 0.5 * (M_PI - g.vfov), phiMax = phiMin + g.vfov;
    const double volume =
        std::pow(g.range, 3) / 3.0 * g.hfov * (std::cos(phiMin) - std::cos(phiMax));
    for (double b : bins)
        EXPECT_NEAR(b, volume, 1e-6 * volume);
}

TEST(YawBinnedGainTest, IgnoredColumnsRemoveTheSectorsSeenFromABin) {
    const auto map = test::makeMap(box(-10, -10, -10, 10, 10, 10));
    const YawBinnedGain gain(gainParams(), 32, CellWeights{});
    const Eigen::Vector3d p(0.1, 0.1, 0.1);
    const std::uint64_t seen = gain.columnsSeenFrom(0);
    // 103.2 deg / 11.25 deg = 9.2 columns: the 9 columns centred within +-50.6 deg of bin 0.
    EXPECT_EQ(seen, 0x1Full | (0xFull << 28));
    const std::vector<double> all = gain.evaluate(*map, p);
    const std::vector<double> masked = gain.evaluate(*map, p, seen);
    EXPECT_LT(masked[0], 0.05 * all[0]);
    EXPECT_GT(masked[0], 0.0);  // the two edge columns are partly in view
    EXPECT_DOUBLE_EQ(masked[16], all[16]);
}

TEST(YawBinnedGainTest, WeightsFrontierAndSurfaceCells) {
    const auto map = test::makeMap(box(0, 0, 0, 4, 4, 2), 5.0);
    // A wall at x = 2.1 seen from the west: free cells up to it, the wall occupied.
    std::vector<Eigen::Vector3f> wall;
    for (double y = 1.0; y <= 3.0; y += 0.05)
        for (double z = 0.5; z <= 1.5; z += 0.05)
            wall.emplace_back(2.1f, float(y), float(z));
    map->insertPointCloud({0.5, 2.0, 1.0}, wall);
    // Rays over the wall's top clear the cells just above its occupied rim.
    std::vector<Eigen::Vector3f> over;
    for (double y = 1.0; y <= 3.0; y += 0.05)
        over.emplace_back(3.9f, float(y), 1.9f);
    map->insertPointCloud({0.5, 2.0, 1.9}, over);
    const CellWeights w{1.0, 2.0, 4.0};
    const YawBinnedGain gain(gainParams(), 32, w);
    ASSERT_TRUE(map->isOccupied({2.1, 2.0, 1.0}));
    ASSERT_TRUE(map->isFree({1.9, 2.0, 1.0}));
    ASSERT_TRUE(map->isUnknown({2.1, 2.0, 1.7}));
    EXPECT_DOUBLE_EQ(gain.cellWeight(*map, {2.1, 2.0, 1.7}), w.surface);
    EXPECT_DOUBLE_EQ(gain.cellWeight(*map, {1.9, 2.0, 1.0}), 0.0);  // known
    EXPECT_DOUBLE_EQ(gain.cellWeight(*map, {3.5, 0.3, 0.3}), w.unknown);
    // Every unknown cell of the box, classified by its 6 neighbours; each class must occur.
    int counts[3] = {0, 0, 0};
    for (double x = 0.1; x < 4.0; x += 0.2) {
        for (double y = 0.1; y < 4.0; y += 0.2) {
            for (double z = 0.1; z < 2.0; z += 0.2) {
                const Eigen::Vector3d q(x, y, z);
                if (!map->isUnknown(q))
                    continue;
                bool free = false, occupied = false;
                for (const Eigen::Vector3d& d :
                     {Eigen::Vector3d(0.2, 0, 0), Eigen::Vector3d(0, 0.2, 0),
                      Eigen::Vector3d(0, 0, 0.2)}) {
                    for (const Eigen::Vector3d& n :
                         {Eigen::Vector3d(q + d), Eigen::Vector3d(q - d)}) {
                        free = free || map->isFree(n);
                        occupied = occupied || map->isOccupied(n);
                    }
                }
                const int cls = free && occupied ? 2 : (free ? 1 : 0);
                ++counts[cls];
                const double expected = cls == 2 ? w.surface : (cls == 1 ? w.frontier : w.unknown);
                ASSERT_DOUBLE_EQ(gain.cellWeight(*map, q), expected) << q.transpose();
            }
        }
    }
    EXPECT_GT(counts[0], 0);
    EXPECT_GT(counts[1], 0);
    EXPECT_GT(counts[2], 0);
    // Headings: the gain facing the unexplored east beats the one facing the seen wall region.
    const std::vector<double> bins = gain.evaluate(*map, {1.0, 2.0, 1.0});
    EXPECT_EQ(gain.binOf(0.0), 0);
    EXPECT_EQ(gain.binOf(M_PI), 16);
    EXPECT_EQ(gain.binOf(-M_PI / 2), 24);
    EXPECT_NEAR(gain.binYaw(8), M_PI / 2, 1e-12);
    EXPECT_GT(bins[gain.binOf(M_PI)], 0.0);
}

TEST(YawBinnedGainTest, BinFacingUnknownBeatsBinFacingKnown) {
    const auto map = test::makeMap(box(0, 0, 0, 8, 4, 2), 2.5);
    const Eigen::Vector3d root(2.0, 2.0, 1.0);
    map->insertPointCloud(root, test::roomScan(box(-0.1, -0.1, -0.1, 8.1, 4.1, 2.1), root, 0.5));
    const YawBinnedGain gain(gainParams(), 32, CellWeights{});
    const std::vector<double> bins = gain.evaluate(*map, {4.0, 2.0, 1.0});
    EXPECT_GT(bins[gain.binOf(0.0)], 5.0 * bins[gain.binOf(M_PI)] + 1e-9);
}

/**
 * A ladder: 0 - 1 - 2 along y = 0 (short) and 0 - 3 - 4 - 2 around (long).
 */
Roadmap ladder() {
    Roadmap rm(1.5);
    rm.addNode({0, 0, 1});
    rm.addNode({1, 0, 1});
    rm.addNode({2, 0, 1});
    rm.addNode({0, 1, 1});
    rm.addNode({2, 1, 1});
    rm.addEdge(0, 1, 1);
    rm.addEdge(1, 2, 1);
    rm.addEdge(0, 3, 1);
    rm.addEdge(3, 4, 1);
    rm.addEdge(4, 2, 1);
    return rm;
}

TEST(RoadmapTest, RadiusQueriesAreSortedAndComplete) {
    Roadmap rm = ladder();
    EXPECT_EQ(rm.within({0.1, 0, 1}, 1.0), (std::vector<int>{0, 1}));
    EXPECT_EQ(rm.within({0.1, 0, 1}, 1.1), (std::vector<int>{0, 1, 3}));
    EXPECT_EQ(rm.nearest({1.9, 0.9, 1}), 4);
    EXPECT_EQ(rm.addEdge(1, 0, 2) >= 0, true);
    EXPECT_EQ(rm.edgeCount(), 5);  // a duplicate edge is not added
}

TEST(RoadmapTest, AStarFindsTheShortestPath) {
    const Roadmap rm = ladder();
    EXPECT_EQ(rm.aStar(0, 2, 2), (std::vector<int>{0, 1, 2}));
    const Roadmap::Paths paths = rm.shortestPaths(0, 2);
    EXPECT_DOUBLE_EQ(paths.cost[2], 2.0);
    EXPECT_EQ(Roadmap::pathTo(paths, 0, 4), (std::vector<int>{0, 3, 4}));
}

TEST(RoadmapTest, LazyPathChecksOnlyPathEdgesAndRoutesAroundBlockedOnes) {
    Roadmap rm = ladder();
    const int blockedEdge = rm.findEdge(1, 2);
    std::vector<std::pair<int, int>> checked;
    const auto check = [&](int a, int b) {
        checked.emplace_back(std::min(a, b), std::max(a, b));
        return !(std::min(a, b) == 1 && std::max(a, b) == 2);
    };
    int checks = 0;
    const std::vector<int> path = rm.lazyPath(0, 2, 7, check, &checks);
    EXPECT_EQ(path, (std::vector<int>{0, 3, 4, 2}));
    EXPECT_TRUE(rm.edge(blockedEdge).blocked);
    EXPECT_EQ(rm.edge(blockedEdge).checkedRevision, 7u);
    // 0-1 and 1-2 on the first try, then 0-3, 3-4, 4-2 (0-1 is not re-checked).
    EXPECT_EQ(checks, 5);
    EXPECT_EQ(int(checked.size()), 5);
    // Same revision: nothing left to check. A newer map revision re-checks the edges lazily.
    checks = 0;
    EXPECT_EQ(rm.lazyPath(0, 2, 7, check, &checks), path);
    EXPECT_EQ(checks, 0);
    EXPECT_EQ(rm.lazyPath(
                  0, 2, 8, [](int, int) { return true; }, &checks),
              (std::vector<int>{0, 1, 2}));
    EXPECT_FALSE(rm.edge(blockedEdge).blocked);
    // Everything blocked: no path.
    EXPECT_TRUE(rm.lazyPath(0, 2, 9, [](int, int) { return false; }).empty());
}

TEST_F(DepHalfKnownRoom, PlanFliesAlongCheckedRoadmapEdgesTowardsTheUnknown) {
    DepPlanner planner(depParams(), gainParams(), 3);
    const PlanningContext c = contextFor(*map, root);
    const Plan plan = planner.plan(c);
    ASSERT_EQ(plan.status, Plan::Status::Path);
    ASSERT_FALSE(plan.waypoints.empty());
    EXPECT_GT(plan.gain, 0.0);
    EXPECT_EQ(int(plan.tree.size()), planner.roadmap().edgeCount());
    Eigen::Vector3d from = root;
    double t = c.time;
    for (const Waypoint& w : plan.waypoints) {
        EXPECT_TRUE(map->isSegmentFreeOrUnknown(from, w.pose.position, 0.3));
        EXPECT_GE(w.arrivalTime, t);
        t = w.arrivalTime;
        from = w.pose.position;
    }
    // The goal is nearer the unexplored east than the start.
    EXPECT_GT(plan.waypoints.back().pose.position.x(), root.x() - 1e-9);
}

TEST_F(DepHalfKnownRoom, DeterministicForASeed) {
    DepPlanner a(depParams(), gainParams(), 11), b(depParams(), gainParams(), 11);
    const Plan pa = a.plan(contextFor(*map, root)), pb = b.plan(contextFor(*map, root));
    ASSERT_EQ(pa.waypoints.size(), pb.waypoints.size());
    for (std::size_t i = 0; i < pa.waypoints.size(); ++i)
        EXPECT_EQ(pa.waypoints[i].pose.position, pb.waypoints[i].pose.position);
    EXPECT_EQ(a.roadmap().size(), b.roadmap().size());
}

/** Calls to plan() until it says finished, at most `calls`; the number made. */
int callsUntilFinished(DepPlanner& planner, const PlanningContext& c, int calls) {
    for (int k = 1; k <= calls; ++k)
        if (planner.plan(c).status == Plan::Status::Finished)
            return k;
    return calls + 1;
}

TEST(DepFinish, AKnownRoomFinishesAfterFinishPlansIdleCallsAndNeverWithZero) {
    auto map = test::makeMap(box(0, 0, 0, 4, 4, 2));
    const Eigen::Vector3d root(2.1, 2.1, 1.1);
    map->insertPointCloud(root, test::roomScan(box(-0.1, -0.1, -0.1, 4.1, 4.1, 2.1), root, 0.5));
    ASSERT_GT(map->coverage(), 0.99);
    const PlanningContext c = contextFor(*map, root);
    DepPlanner finishing(depParams(), gainParams(), 4);
    const int calls = callsUntilFinished(finishing, c, 40);
    EXPECT_GE(calls, finishing.params().finishPlans);
    EXPECT_LE(calls, 40);
    DepParams endless = depParams();
    endless.finishPlans = 0;
    DepPlanner looking(endless, gainParams(), 4);
    EXPECT_GT(callsUntilFinished(looking, c, 40), 40);
    const Plan turn = looking.plan(c);
    ASSERT_EQ(turn.status, Plan::Status::Path);
    ASSERT_EQ(turn.waypoints.size(), 1u);
    EXPECT_EQ(turn.waypoints[0].pose.position, root);  // turning in place, looking around
}

TEST(DepFinish, FinishPlansZeroIsReadAndNegativeIsAnError) {
    const std::string zero = "0", negative = "-1";
    const auto cfg =
        test::configFromText(test::editKey(test::defaultsText(), "dep", "finish_plans", &zero));
    EXPECT_EQ(DepParams::fromConfig(*cfg).finishPlans, 0);
    const auto bad =
        test::configFromText(test::editKey(test::defaultsText(), "dep", "finish_plans", &negative));
    EXPECT_THROW(DepParams::fromConfig(*bad), InputError);
}

/** A plan along +x in a known free corridor; then a person appears across it. */
TEST(DepReplan, KeepFlyingStopsOnlyWhenThePathAheadIsBlockedAndReplanIsOn) {
    const auto map = test::makeMap(box(0, 0, 0, 10, 4, 2), 6.0);
    const Eigen::Vector3d origin(1.0, 2.0, 1.0);
    map->insertPointCloud(origin, test::roomScan(box(-0.1, -0.1, -0.1, 10.1, 4.1, 2.1), origin));
    Plan plan;
    plan.status = Plan::Status::Path;
    for (double x : {2.5, 4.0, 5.5})
        plan.waypoints.push_back({FlatPose{{x, 2.0, 1.0}, 0.0}, 0.0});
    const PlanningContext c = contextFor(*map, origin);
    DepPlanner on(depParams(true), gainParams(), 1), off(depParams(false), gainParams(), 1);
    ASSERT_TRUE(on.keepFlying(c, plan, 0));
    ASSERT_TRUE(off.keepFlying(c, plan, 0));
    // A person seen at x = 3.3 (a column of hits across the corridor).
    std::vector<Eigen::Vector3f> person;
    for (double y = 1.6; y <= 2.4; y += 0.05)
        for (double z = 0.2; z <= 1.8; z += 0.05)
            person.emplace_back(3.3f, float(y), float(z));
    map->insertPointCloud(origin, person);
    ASSERT_TRUE(map->isOccupied({3.3, 2.0, 1.0}));
    const PlanningContext blocked = contextFor(*map, origin);
    EXPECT_FALSE(on.keepFlying(blocked, plan, 0));
    EXPECT_TRUE(off.keepFlying(blocked, plan, 0));  // DEP-S flies blind
    // Already past the person: the rest of the path is clear.
    const PlanningContext past = contextFor(*map, {4.0, 2.0, 1.0});
    EXPECT_TRUE(on.keepFlying(past, plan, 2));
}

TEST(DepReplan, NextPlanStartsFromTheStoppedPoseAndAvoidsTheBlockage) {
    const auto map = test::makeMap(box(0, 0, 0, 10, 4, 2), 6.0);
    const Eigen::Vector3d origin(1.0, 2.0, 1.0);
    const Aabb walls = box(-0.1, -0.1, -0.1, 10.1, 4.1, 2.1);
    map->insertPointCloud(origin, test::roomScan(walls, origin));
    DepPlanner planner(depParams(true), gainParams(), 2);
    planner.plan(contextFor(*map, origin));
    const Eigen::Vector3d stopped(1.7, 2.1, 1.0);  // off the roadmap, as after an abort
    std::vector<Eigen::Vector3f> person;
    for (double y = 1.0; y <= 3.0; y += 0.05)
        for (double z = 0.2; z <= 1.8; z += 0.05)
            person.emplace_back(3.0f, float(y), float(z));
    map->insertPointCloud(stopped, person);
    const int before = planner.roadmap().size();
    const Plan plan = planner.plan(contextFor(*map, stopped));
    const Roadmap& rm = planner.roadmap();
    ASSERT_GT(rm.size(), before);
    const RoadmapNode& anchor = rm.node(before);  // the stopped pose became the start node
    EXPECT_TRUE(anchor.anchor);
    EXPECT_EQ(anchor.position, stopped);
    Eigen::Vector3d from = stopped;
    for (const Waypoint& w : plan.waypoints) {
        EXPECT_TRUE(map->isSegmentFreeOrUnknown(from, w.pose.position, 0.3))
            << w.pose.position.transpose();
        from = w.pose.position;
    }
    for (int e = 0; e < rm.edgeCount(); ++e) {
        const RoadmapEdge& edge = rm.edge(e);
        if (edge.checkedRevision == map->revision() && !edge.blocked && !rm.node(edge.a).anchor &&
            !rm.node(edge.b).anchor) {
            EXPECT_TRUE(
                map->isSegmentFree(rm.node(edge.a).position, rm.node(edge.b).position, 0.3));
        }
    }
}

}  // namespace
}  // namespace daep::planning
