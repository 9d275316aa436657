#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "PlanningTestUtil.h"
#include "daep/common/Error.h"
#include "daep/planning/AepPlanner.h"
#include "daep/planning/FlightSpace.h"
#include "daep/planning/Planner.h"
#include "daep/planning/PlannerRegistry.h"

namespace daep::planning {
namespace {

using test::box;
using test::contextFor;

AepPlanner makePlanner(std::uint64_t seed) {
    const auto cfg = test::configFromText(test::defaultsText());
    return AepPlanner(AepParams::fromConfig(*cfg), GainParams::fromConfig(*cfg), seed);
}

/** Points in every direction from `origin`, `distance` away (beyond the mapping range). */
std::vector<Eigen::Vector3f> sphereScan(const Eigen::Vector3d& origin, double distance) {
    std::vector<Eigen::Vector3f> points;
    for (double el = -90.0; el <= 90.0; el += 1.0)
        for (double az = 0.0; az < 360.0; az += 1.0) {
            const double e = el * M_PI / 180.0;
            const double a = az * M_PI / 180.0;
            const Eigen::Vector3d d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a),
                                    std::sin(e));
            points.push_back((origin + distance * d).cast<float>());
        }
    return points;
}

using test::westKnown;

TEST(AepGain, CubatureMatchesTheAnalyticUnknownShell) {
    // A ball of radius 2 m around p is known free, everything else unknown: the gain is the
    // field-of-view sector of the shell between 2 and 5 m.
    const Eigen::Vector3d p(20.0, 20.0, 20.0);
    auto map = test::makeMap(box(0, 0, 0, 40, 40, 40), 2.0);
    map->insertPointCloud(p, sphereScan(p, 30.0));
    AepPlanner planner = makePlanner(1);
    const GainEvaluator evaluator(GainParams{});
    const double solid =
        GainParams{}.hfov * (std::cos(evaluator.phiMin()) - std::cos(evaluator.phiMax()));
    const double shell = solid * (std::pow(5.0, 3) - std::pow(2.0, 3)) / 3.0;
    const YawGain g = planner.evaluateGain(*map, p);
    EXPECT_NEAR(g.gain, shell, 0.04 * shell);
    EXPECT_EQ(planner.stats().rayCasts, 1);
    // Fully unknown: the whole view volume, exactly (the dr^3/12 term included).
    auto unknown = test::makeMap(box(0, 0, 0, 40, 40, 40));
    const double full = solid * 125.0 / 3.0;
    EXPECT_NEAR(planner.evaluateGain(*unknown, {5.0, 5.0, 5.0}).gain, full, 1e-9 * full);
}

TEST(AepGain, BestYawFacesTheUnknownSide) {
    auto map = westKnown(8.0, 4.0);
    for (const Eigen::Vector3d& p :
         {Eigen::Vector3d(2.5, 2.0, 1.0), Eigen::Vector3d(3.0, 1.5, 0.7)}) {
        AepPlanner planner = makePlanner(2);
        const YawGain g = planner.evaluateGain(*map, p);
        EXPECT_GT(std::cos(g.yaw), 0.9) << g.yaw;
        EXPECT_GT(g.gain, 0.0);
    }
}

TEST(AepGain, ConfidentCacheReplacesRayCasting) {
    auto map = test::makeMap(box(0, 0, 0, 40, 40, 40));
    AepPlanner planner = makePlanner(3);
    const Eigen::Vector3d p(10, 10, 10);
    const YawGain first = planner.evaluateGain(*map, p);  // ray cast and cached
    EXPECT_EQ(planner.cache().size(), 1u);
    EXPECT_EQ(planner.stats().rayCasts, 1);
    // Right next to a cached viewpoint the GP is confident: its mean, no ray cast.
    const YawGain near = planner.evaluateGain(*map, p + Eigen::Vector3d(0.05, 0.0, 0.0));
    EXPECT_EQ(planner.stats().rayCasts, 1);
    EXPECT_EQ(planner.stats().gpPredictions, 1);
    EXPECT_NEAR(near.gain, first.gain * std::exp(-0.05 * 0.05 / 2.0) / 1.01, 1e-9);
    EXPECT_DOUBLE_EQ(near.yaw, first.yaw);
    EXPECT_EQ(planner.cache().size(), 1u);
    // 1 m away the GP is unsure: ray cast, and the new viewpoint is cached too.
    planner.evaluateGain(*map, p + Eigen::Vector3d(1.0, 0, 0));
    EXPECT_EQ(planner.stats().rayCasts, 2);
    EXPECT_EQ(planner.cache().size(), 2u);
}

TEST(AepGain, RefreshDropsCachedViewpointsThatBecameKnown) {
    auto map = westKnown(16.0, 4.0);
    AepPlanner planner = makePlanner(4);
    const Eigen::Vector3d p(3.5, 2.0, 1.0);
    planner.evaluateGain(*map, p);
    ASSERT_EQ(planner.cache().size(), 1u);
    // Now map everything up to x = 14: nothing unknown within 5 m of p.
    for (double y = 0.1; y < 4.0; y += 0.2)
        for (double z = 0.1; z < 2.0; z += 0.2)
            map->insertPointCloud({13.9, y, z}, {Eigen::Vector3f(-100.f, float(y), float(z))});
    planner.refreshCache(*map, {6.0, 2.0, 1.0});
    EXPECT_EQ(planner.cache().size(), 0u);
    EXPECT_EQ(planner.stats().cacheDropped, 1);
}

void expectConsistentTree(const AepPlanner& planner, const mapping::ExplorationMap& map,
                          bool scores) {
    const Tree& tree = planner.tree();
    const AepParams& p = planner.params();
    const Aabb inner = shrink(map.explorationBox(), p.robotRadius);
    for (int i = 1; i < tree.size(); ++i) {
        const TreeNode& n = tree.node(i);
        ASSERT_GE(n.parent, 0);
        const TreeNode& parent = tree.node(n.parent);
        const double edge = (n.position - parent.position).norm();
        EXPECT_TRUE(inner.contains(n.position)) << i;
        EXPECT_TRUE(map.isSegmentFree(parent.position, n.position, p.robotRadius)) << i;
        EXPECT_NEAR(n.cost, parent.cost + edge, 1e-9) << i;
        if (scores) {
            EXPECT_NEAR(n.score, parent.score + n.gain * std::exp(-p.lambda * edge), 1e-9) << i;
        }
        // No cycles: the branch reaches the root within size() steps.
        EXPECT_LE(tree.branch(i).size(), std::size_t(tree.size()));
    }
}

/** RRT*: no node could be reached more cheaply through a neighbour within the rewire radius. */
void expectRewired(const AepPlanner& planner, const mapping::ExplorationMap& map) {
    const Tree& tree = planner.tree();
    const AepParams& p = planner.params();
    int improvable = 0;
    for (int i = 1; i < tree.size(); ++i)
        for (int j = 1; j < tree.size(); ++j) {
            const double d = (tree.node(i).position - tree.node(j).position).norm();
            if (i != j && d <= p.rewireRadius && tree.node(j).cost + d < tree.node(i).cost - 1e-6 &&
                map.isSegmentFree(tree.node(j).position, tree.node(i).position, p.robotRadius))
                ++improvable;
        }
    // Rewiring is local to each insertion, so a few late improvements may remain.
    EXPECT_LE(improvable, tree.size() / 10) << improvable << " of " << tree.size();
}

TEST(AepPlanner, LocalPlanHeadsForTheUnknownWithAConsistentRrtStar) {
    auto map = westKnown(8.0, 4.0);
    for (std::uint64_t seed : {1, 2, 3}) {
        AepPlanner planner = makePlanner(seed);
        const PlanningContext ctx = contextFor(*map, {2.0, 2.0, 1.0});
        const Plan plan = planner.plan(ctx);
        ASSERT_EQ(plan.status, Plan::Status::Path) << plan.reason;
        ASSERT_EQ(plan.waypoints.size(), 1u) << plan.reason;
        EXPECT_FALSE(planner.stats().global);
        EXPECT_GT(plan.score, planner.params().zeroGain);
        const Waypoint& w = plan.waypoints.front();
        // RRT* may pick any parent within the rewire radius, so edges reach up to it.
        EXPECT_LE((w.pose.position - ctx.pose.position).norm(),
                  planner.params().rewireRadius + 1e-9);
        EXPECT_NEAR(w.arrivalTime, ctx.time + ctx.motion.travelTime(ctx.pose, w.pose), 1e-12);
        const Tree& tree = planner.tree();
        EXPECT_GE(tree.size() - 1, planner.params().initialIterations);
        EXPECT_LE(tree.size() - 1, planner.params().cutoffIterations);
        EXPECT_GT(tree.node(tree.bestByScore()).position.x(), 2.0);
        expectConsistentTree(planner, *map, true);
    }
}

TEST(AepPlanner, BestBranchIsReusedInTheNextTree) {
    auto map = westKnown(8.0, 4.0);
    AepPlanner planner = makePlanner(5);
    const Plan first = planner.plan(contextFor(*map, {1.5, 2.0, 1.0}));
    const std::vector<int> branch = planner.tree().branch(planner.tree().bestByScore());
    ASSERT_GE(branch.size(), 2u) << first.reason;
    const Eigen::Vector3d second = planner.tree().node(branch[1]).position;
    const Waypoint w = first.waypoints.front();
    planner.plan(contextFor(*map, w.pose.position, w.pose.yaw));
    EXPECT_TRUE((planner.tree().node(1).position - second).norm() < 1e-12);
}

TEST(AepPlanner, GlobalPlanFliesToTheCheapestFrontier) {
    // 24 m long room, known up to x = 12; the drone sits at the far west end where no local
    // branch sees anything. Two frontiers from earlier planning: near (9.5, 3) and far (11, 1).
    auto map = westKnown(24.0, 12.0);
    AepPlanner planner = makePlanner(6);
    const Eigen::Vector3d nearF(9.5, 3.0, 1.0), farF(11.0, 1.0, 1.0);
    planner.evaluateGain(*map, farF);
    planner.evaluateGain(*map, nearF);
    ASSERT_EQ(planner.cache().size(), 2u);
    const PlanningContext ctx = contextFor(*map, {1.0, 2.0, 1.0}, M_PI);
    const Plan plan = planner.plan(ctx);
    ASSERT_EQ(plan.status, Plan::Status::Path) << plan.reason;
    EXPECT_TRUE(planner.stats().global);
    ASSERT_GE(plan.waypoints.size(), 2u);
    EXPECT_GE(planner.tree().size() - 1, planner.params().globalMinNodes);
    const Waypoint& last = plan.waypoints.back();
    EXPECT_LT((last.pose.position - nearF).norm(), planner.params().goalRadius) << plan.reason;
    EXPECT_GT(std::cos(last.pose.yaw), 0.9);  // the frontier's best yaw: east
    // Arrival times follow the motion model; every segment is in known free space.
    FlatPose at = ctx.pose;
    double t = ctx.time;
    for (const Waypoint& w : plan.waypoints) {
        t += ctx.motion.travelTime(at, w.pose);
        EXPECT_NEAR(w.arrivalTime, t, 1e-9);
        EXPECT_TRUE(map->isSegmentFree(at.position, w.pose.position, planner.params().robotRadius));
        at = w.pose;
    }
    expectConsistentTree(planner, *map, false);
    expectRewired(planner, *map);
}

TEST(AepPlanner, PathSpaceNotOccupiedLetsTheTreeIntoUnknownSpaceButNotThroughWalls) {
    // Known free for x < 3, unknown beyond, and a wall of hits across the corridor at x = 6.
    auto map = westKnown(10.0, 3.0);
    for (double y = 0.1; y < 4.0; y += 0.2)
        for (double z = 0.1; z < 2.0; z += 0.2)
            map->insertPointCloud({6.1, y, z}, {Eigen::Vector3f(6.1f, float(y), float(z))});
    std::string text = test::defaultsText();
    const std::string unknownToo = "not_occupied";
    const auto cfg =
        test::configFromText(test::editKey(text, "planning", "path_space", &unknownToo));
    const AepParams params = AepParams::fromConfig(*cfg);
    ASSERT_TRUE(params.crossUnknown);
    double farthest = 0.0, highest = 0.0;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
        AepPlanner planner(params, GainParams::fromConfig(*cfg), seed);
        planner.plan(contextFor(*map, {2.0, 2.0, 1.0}));
        for (int i = 0; i < planner.tree().size(); ++i) {
            const Eigen::Vector3d& p = planner.tree().node(i).position;
            EXPECT_LT(p.x(), 5.9);  // the wall's cells and the robot radius before them
            EXPECT_LE(p.z(), 2.0 - 0.05 + 1e-9);  // the box's top less the drone's half-height
            farthest = std::max(farthest, p.x());
            highest = std::max(highest, p.z());
        }
    }
    EXPECT_GT(farthest, 3.5);  // beyond the known space
    EXPECT_GT(highest, 1.7);   // above the box shrunk by the robot radius
    // With known_free (the default) every node stays in the known part.
    AepPlanner known = makePlanner(1);
    known.plan(contextFor(*map, {2.0, 2.0, 1.0}));
    for (int i = 0; i < known.tree().size(); ++i)
        EXPECT_LT(known.tree().node(i).position.x(), 3.0);
}

TEST(AepPlanner, FinishedWhenNoFrontierIsLeft) {
    auto map = westKnown(8.0, 8.5);
    AepPlanner planner = makePlanner(7);
    const Plan plan = planner.plan(contextFor(*map, {2.0, 2.0, 1.0}));
    EXPECT_EQ(plan.status, Plan::Status::Finished) << plan.reason;
    EXPECT_EQ(planner.cache().size(), 0u);
}

/** westKnown(16, 12) with a wall of hits across the corridor at x = 6 (a person's imprint). */
std::unique_ptr<mapping::ExplorationMap> corridorClosedAtSix() {
    auto map = westKnown(16.0, 12.0);
    for (double y = 0.1; y < 4.0; y += 0.2)
        for (double z = 0.1; z < 2.0; z += 0.2)
            map->insertPointCloud({6.1, y, z}, {Eigen::Vector3f(6.1f, float(y), float(z))});
    return map;
}

/** An AEP planner that has cached the frontiers at the corridor's unknown end (x > 12). */
std::unique_ptr<AepPlanner> plannerThatSawTheFarEnd(const std::string& counter) {
    const auto cfg = test::configFromText(
        test::editKey(test::defaultsText(), "aep", "global_planner_counter", &counter));
    auto planner =
        std::make_unique<AepPlanner>(AepParams::fromConfig(*cfg), GainParams::fromConfig(*cfg), 5);
    auto open = westKnown(16.0, 12.0);
    const Plan there = planner->plan(contextFor(*open, {9.0, 2.0, 1.0}));
    EXPECT_FALSE(there.waypoints.empty()) << there.reason;
    EXPECT_GT(planner->cache().size(), 0u);
    return planner;
}

/** An AEP planner with map_frontiers set, and a global tree too small to survey far. */
AepPlanner plannerWithSmallGlobalTree(const std::string& mapFrontiers) {
    std::string text = test::editKey(test::defaultsText(), "aep", "map_frontiers", &mapFrontiers);
    for (const char* key : {"global_min_nodes", "global_max_nodes"}) {
        const std::string two = "2";
        text = test::editKey(text, "aep", key, &two);
    }
    const auto cfg = test::configFromText(text);
    return AepPlanner(AepParams::fromConfig(*cfg), GainParams::fromConfig(*cfg), 3);
}

TEST(AepPlanner, WithMapFrontiersItDoesNotFinishWhileTheMapHasAFrontierNoSampleFound) {
    // Known free up to x = 30 and nothing cached: no local sample sees past x = 17, and a
    // two-node global tree surveys nothing far away.
    auto map = westKnown(40.0, 30.0);
    const PlanningContext ctx = contextFor(*map, {2.0, 2.0, 1.0});
    AepPlanner trusting = plannerWithSmallGlobalTree("false");
    const Plan ended = trusting.plan(ctx);
    EXPECT_EQ(ended.status, Plan::Status::Finished) << ended.reason;
    EXPECT_NE(ended.reason.find("no frontiers left"), std::string::npos) << ended.reason;

    AepPlanner looking = plannerWithSmallGlobalTree("true");
    const Plan plan = looking.plan(ctx);
    EXPECT_NE(plan.status, Plan::Status::Finished) << plan.reason;
    ASSERT_GT(looking.cache().size(), 0u);
    for (int id : looking.cache().liveIds())  // viewpoints by the unknown end, with clearance
        EXPECT_GT(looking.cache().entry(id).position.x(), 28.5);

    // Everything known: then it finishes all the same.
    auto seen = westKnown(40.0, 40.5);
    const Plan done = plannerWithSmallGlobalTree("true").plan(contextFor(*seen, {2.0, 2.0, 1.0}));
    EXPECT_EQ(done.status, Plan::Status::Finished) << done.reason;
}

TEST(AepPlanner, WithMapFrontiersAFailedGlobalPlanLooksForTheFrontierItCanReach) {
    // The frontier cached at the far east end (x > 12) is shut off by a wall at x = 6; the
    // corridor is unknown west of x = -12, farther than any local sample sees from x = 5, and
    // a two-node global tree surveys nothing. Trusting the cache, the failed global plan
    // leaves only the far end cached; looking on the map's own frontier after it, the
    // viewpoints by the western unknown are cached too, for the next global tree to reach.
    for (const std::string mapFrontiers : {"false", "true"}) {
        std::string text =
            test::editKey(test::defaultsText(), "aep", "map_frontiers", &mapFrontiers);
        for (const char* key : {"global_min_nodes", "global_max_nodes"}) {
            const std::string two = "2";
            text = test::editKey(text, "aep", key, &two);
        }
        const auto cfg = test::configFromText(text);
        AepPlanner planner(AepParams::fromConfig(*cfg), GainParams::fromConfig(*cfg), 5);
        planner.cache().insert({14.0, 2.0, 1.0}, 0.0, 100.0);
        auto closed = test::makeMap(box(-20, 0, 0, 16, 4, 2), 23.9);  // clears x > -12
        for (double y = 0.1; y < 4.0; y += 0.2)
            for (double z = 0.1; z < 2.0; z += 0.2) {
                closed->insertPointCloud({11.9, y, z},
                                         {Eigen::Vector3f(-100.f, float(y), float(z))});
                closed->insertPointCloud({6.1, y, z}, {Eigen::Vector3f(6.1f, float(y), float(z))});
            }
        const Plan failed = planner.plan(contextFor(*closed, {5.0, 2.0, 1.0}));
        EXPECT_TRUE(failed.waypoints.empty()) << failed.reason;
        EXPECT_NE(failed.status, Plan::Status::Finished) << failed.reason;
        int west = 0;
        for (int id : planner.cache().liveIds())
            west += planner.cache().entry(id).position.x() < -9.0;
        if (mapFrontiers == "true")
            EXPECT_GT(west, 0);
        else
            EXPECT_EQ(west, 0);
        // Failing again, it caches no frontier twice.
        const std::size_t cached = planner.cache().size();
        for (int k = 0; k < 3; ++k)
            EXPECT_TRUE(planner.plan(contextFor(*closed, {5.0, 2.0, 1.0})).waypoints.empty());
        EXPECT_EQ(planner.cache().size(), cached);
    }
}

TEST(AepPlanner, WithMapPathsATreeTooSmallToReachAFrontierDoesNotCountAsAFailure) {
    // A frontier cached 27 m down a known free corridor; a two-node global tree reaches
    // nothing that far. Without map paths every global plan fails and counts; with them the
    // drone flies there through the map's free cells, every leg with its clearance.
    for (const std::string mapPaths : {"false", "true"}) {
        std::string text = test::editKey(test::defaultsText(), "aep", "map_paths", &mapPaths);
        for (const char* key : {"global_min_nodes", "global_max_nodes"}) {
            const std::string two = "2";
            text = test::editKey(text, "aep", key, &two);
        }
        const std::string counter = "25";
        text = test::editKey(text, "aep", "global_planner_counter", &counter);
        const auto cfg = test::configFromText(text);
        AepPlanner planner(AepParams::fromConfig(*cfg), GainParams::fromConfig(*cfg), 5);
        auto map = westKnown(40.0, 30.0);
        planner.cache().insert({29.0, 2.0, 1.0}, 0.0, 100.0);
        const Plan plan = planner.plan(contextFor(*map, {2.0, 2.0, 1.0}));
        if (mapPaths == "false") {
            EXPECT_TRUE(plan.waypoints.empty()) << plan.reason;
            continue;
        }
        ASSERT_EQ(plan.status, Plan::Status::Path) << plan.reason;
        EXPECT_NE(plan.reason.find("through the map's free cells"), std::string::npos)
            << plan.reason;
        ASSERT_FALSE(plan.waypoints.empty());
        EXPECT_LT((plan.waypoints.back().pose.position - Eigen::Vector3d(29.0, 2.0, 1.0)).norm(),
                  1e-9);
        Eigen::Vector3d at(2.0, 2.0, 1.0);
        for (const Waypoint& w : plan.waypoints) {
            EXPECT_TRUE(map->isSegmentFree(at, w.pose.position, planner.params().robotRadius))
                << w.pose.position.transpose();
            at = w.pose.position;
        }
        EXPECT_LE(plan.waypoints.size(), 4u);  // shortcut: straight down the corridor
    }
}

TEST(AepPlanner, AsTheReferenceBaselineItKeepsTryingWhileAFrontierIsLeft) {
    // The reference AEP's loop ends only when no frontier is left: back at x = 2 behind the
    // imprint, every global plan fails, and the drone hovers global_retry_wait_s and retries.
    const std::unique_ptr<AepPlanner> owned = plannerThatSawTheFarEnd("0");
    AepPlanner& planner = *owned;
    ASSERT_EQ(planner.params().globalPlannerCounter, 0);
    ASSERT_GT(planner.params().globalRetryWait, 0.0);
    auto closed = corridorClosedAtSix();
    PlanningContext ctx = contextFor(*closed, {2.0, 2.0, 1.0});
    for (int k = 0; k < 40; ++k) {
        ctx.time += 0.5;
        const Plan plan = planner.plan(ctx);
        ASSERT_EQ(plan.status, Plan::Status::Wait) << k << ": " << plan.reason;
        EXPECT_TRUE(plan.waypoints.empty()) << plan.reason;
        EXPECT_EQ(plan.waitSeconds, planner.params().globalRetryWait);
    }
    // The imprint cleared (the person walked on), the way is open again.
    auto open = westKnown(16.0, 12.0);
    const Plan plan = planner.plan(contextFor(*open, {2.0, 2.0, 1.0}));
    ASSERT_FALSE(plan.waypoints.empty()) << plan.reason;
    EXPECT_GT(plan.waypoints.back().pose.position.x(), 6.5) << plan.reason;
}

TEST(AepPlanner, WithACounterItFinishesAfterThatManyFailedGlobalPlans) {
    const std::unique_ptr<AepPlanner> owned = plannerThatSawTheFarEnd("25");
    AepPlanner& planner = *owned;
    auto closed = corridorClosedAtSix();
    const PlanningContext ctx = contextFor(*closed, {2.0, 2.0, 1.0});
    for (int k = 1; k < 25; ++k)
        ASSERT_EQ(planner.plan(ctx).status, Plan::Status::Wait) << k;
    const Plan last = planner.plan(ctx);
    EXPECT_EQ(last.status, Plan::Status::Finished) << last.reason;
    EXPECT_NE(last.reason.find("after 25 global plans"), std::string::npos) << last.reason;
}

TEST(AepPlanner, KeepFlyingStopsWhenThePathGetsBlocked) {
    auto map = westKnown(24.0, 12.0);
    AepPlanner planner = makePlanner(8);
    Plan plan;
    plan.status = Plan::Status::Path;
    plan.waypoints.push_back({{{4.0, 2.0, 1.0}, 0.0}, 0.0});
    plan.waypoints.push_back({{{8.0, 2.0, 1.0}, 0.0}, 0.0});
    const PlanningContext ctx = contextFor(*map, {2.0, 2.0, 1.0});
    EXPECT_TRUE(planner.keepFlying(ctx, plan, 0));
    map->insertPointCloud({5.0, 2.0, 1.0}, {Eigen::Vector3f(6.0f, 2.0f, 1.0f)});
    EXPECT_FALSE(planner.keepFlying(ctx, plan, 0));
    EXPECT_TRUE(planner.keepFlying(ctx, plan, 1));
}

TEST(AepPlanner, SameSeedSamePlans) {
    auto map = westKnown(8.0, 4.0);
    AepPlanner a = makePlanner(9), b = makePlanner(9);
    for (int i = 0; i < 3; ++i) {
        const Plan pa = a.plan(contextFor(*map, {2.0, 2.0, 1.0}));
        const Plan pb = b.plan(contextFor(*map, {2.0, 2.0, 1.0}));
        ASSERT_EQ(pa.waypoints.size(), pb.waypoints.size());
        EXPECT_EQ(pa.waypoints.front().pose.position, pb.waypoints.front().pose.position);
    }
}

TEST(CreatePlanner, KnowsAepAndNamesItsMissingKeys) {
    const std::string text = test::defaultsText();
    const auto cfg = test::configFromText(text);
    EXPECT_EQ(createPlanner("aep", *cfg, 1)->name(), "aep");
    for (const std::string key :
         {"lambda", "zero_gain", "sigma_thresh", "cache_node_threshold", "global_min_nodes",
          "goal_radius", "global_planner_counter", "global_retry_wait_s", "max_sampling_radius",
          "rewire_radius", "map_frontiers", "map_paths"}) {
        const auto missing = test::configFromText(test::editKey(text, "aep", key));
        try {
            createPlanner("aep", *missing, 1);
            FAIL() << key << " missing but accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("[aep] " + key), std::string::npos) << e.what();
        }
    }
    const std::string bad = "2";
    EXPECT_THROW(
        createPlanner(
            "aep", *test::configFromText(test::editKey(text, "aep", "global_goal_bias", &bad)), 1),
        InputError);
}

}  // namespace
}  // namespace daep::planning
