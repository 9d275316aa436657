#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <set>

#include "PlanningTestUtil.h"
#include "daep/common/Error.h"
#include "daep/planning/FlightSpace.h"
#include "daep/planning/Planner.h"
#include "daep/planning/PlannerRegistry.h"
#include "daep/planning/RhNbvpPlanner.h"

namespace daep::planning {
namespace {

using test::box;
using test::contextFor;

RhNbvpPlanner makePlanner(std::uint64_t seed) {
    const auto cfg = test::configFromText(test::defaultsText());
    return RhNbvpPlanner(RhNbvpParams::fromConfig(*cfg), GainParams::fromConfig(*cfg), seed);
}

class HalfKnownRoom : public test::HalfKnownRoomMap {};

TEST_F(HalfKnownRoom, TreeNodesAndEdgesAreValid) {
    RhNbvpPlanner planner = makePlanner(7);
    const Plan plan = planner.plan(contextFor(*map, root));
    const Tree& tree = planner.tree();
    const RhNbvpParams& p = planner.params();
    ASSERT_GE(tree.size() - 1, p.initialIterations);
    EXPECT_EQ(plan.tree.size(), std::size_t(tree.size() - 1));
    EXPECT_TRUE(map->isSegmentFree(root, root, p.robotRadius));
    const Aabb inner = shrink(map->explorationBox(), p.robotRadius);
    EXPECT_EQ(tree.node(0).parent, -1);
    for (int i = 1; i < tree.size(); ++i) {
        const TreeNode& n = tree.node(i);
        const TreeNode& parent = tree.node(n.parent);
        ASSERT_GE(n.parent, 0);
        ASSERT_LT(n.parent, i);  // parents come first, so the tree is connected to the root
        EXPECT_TRUE(inner.contains(n.position)) << i;
        EXPECT_TRUE(map->isSegmentFree(parent.position, n.position, p.robotRadius)) << i;
        const double edge = (n.position - parent.position).norm();
        EXPECT_LE(edge, p.extensionRange + 1e-9);
        EXPECT_NEAR(n.cost, parent.cost + edge, 1e-9);
        EXPECT_NEAR(n.score, parent.score + n.gain * std::exp(-p.lambda * n.cost), 1e-9);
        EXPECT_GE(n.gain, 0.0);
        EXPECT_GE(n.yaw, -M_PI);
        EXPECT_LT(n.yaw, M_PI);
    }
}

/** An 8 x 4 x 2 m box: every cell with x < 4 is known free, the rest is unknown. */
struct WestKnownRoom : ::testing::Test {
    void SetUp() override {
        map = test::makeMap(box(0, 0, 0, 8, 4, 2));
        for (double y = 0.1; y < 4.0; y += 0.2) {
            for (double z = 0.1; z < 2.0; z += 0.2) {
                map->insertPointCloud({3.9, y, z}, {Eigen::Vector3f(-30.f, float(y), float(z))});
            }
        }
    }
    const Eigen::Vector3d root{2.0, 2.0, 1.0};
    std::unique_ptr<mapping::ExplorationMap> map;
};

TEST_F(WestKnownRoom, FirstStepHeadsForTheUnknownSide) {
    ASSERT_TRUE(map->isFree({3.9, 3.9, 1.9}));
    ASSERT_TRUE(map->isUnknown({4.1, 2.0, 1.0}));
    for (std::uint64_t seed : {1, 2, 3, 4, 5}) {
        RhNbvpPlanner planner = makePlanner(seed);
        const PlanningContext ctx = contextFor(*map, root);
        const Plan plan = planner.plan(ctx);
        ASSERT_EQ(plan.status, Plan::Status::Path) << plan.reason;
        ASSERT_EQ(plan.waypoints.size(), 1u);
        const Waypoint& w = plan.waypoints.front();
        EXPECT_GT(w.pose.position.x(), root.x()) << "seed " << seed;
        EXPECT_LE((w.pose.position - root).norm(), planner.params().extensionRange + 1e-9);
        EXPECT_NEAR(w.arrivalTime, ctx.time + ctx.motion.travelTime(ctx.pose, w.pose), 1e-12);
        const Tree& tree = planner.tree();
        const TreeNode& best = tree.node(tree.bestByScore());
        EXPECT_GT(std::cos(best.yaw), 0.0) << "seed " << seed;
        EXPECT_GT(best.position.x(), root.x()) << "seed " << seed;
        EXPECT_DOUBLE_EQ(plan.score, best.score);
        EXPECT_GT(plan.score, planner.params().zeroGain);
    }
}

TEST_F(HalfKnownRoom, RemainderOfTheBestBranchSeedsTheNextTree) {
    RhNbvpPlanner planner = makePlanner(11);
    const Plan first = planner.plan(contextFor(*map, root));
    const Tree& tree = planner.tree();
    const std::vector<int> branch = tree.branch(tree.bestByScore());
    ASSERT_EQ(first.status, Plan::Status::Path);
    std::vector<Eigen::Vector3d> remainder;
    for (std::size_t i = 1; i < branch.size(); ++i) {
        remainder.push_back(tree.node(branch[i]).position);
    }
    const Waypoint w = first.waypoints.front();
    planner.plan(contextFor(*map, w.pose.position, w.pose.yaw));
    const Tree& next = planner.tree();
    ASSERT_GE(next.size(), int(remainder.size()) + 1);
    for (std::size_t i = 0; i < remainder.size(); ++i) {
        EXPECT_EQ(next.node(int(i) + 1).position, remainder[i]);
        EXPECT_EQ(next.node(int(i) + 1).parent, int(i));
    }
}

TEST(RhNbvpPlanner, FinishedWhenEverythingIsKnown) {
    auto map = test::makeMap(box(0, 0, 0, 4, 4, 2));
    const Eigen::Vector3d root(2.1, 2.1, 1.1);
    map->insertPointCloud(root, test::roomScan(box(-0.1, -0.1, -0.1, 4.1, 4.1, 2.1), root, 0.5));
    ASSERT_GT(map->coverage(), 0.99);
    RhNbvpPlanner planner = makePlanner(3);
    const Plan plan = planner.plan(contextFor(*map, root));
    EXPECT_EQ(plan.status, Plan::Status::Finished);
    EXPECT_NE(plan.reason.find("no gain"), std::string::npos) << plan.reason;
    EXPECT_TRUE(plan.waypoints.empty());
    EXPECT_EQ(planner.tree().size() - 1, planner.params().cutoffIterations);
}

TEST(RhNbvpPlanner, UnknownSurroundingsGiveAFailedPlanNotFinished) {
    auto map = test::makeMap(box(0, 0, 0, 4, 4, 2));
    RhNbvpPlanner planner = makePlanner(3);
    const Plan plan = planner.plan(contextFor(*map, {2, 2, 1}));
    EXPECT_EQ(plan.status, Plan::Status::NoPath);
    EXPECT_TRUE(plan.waypoints.empty());
    EXPECT_NE(plan.reason.find("stalled"), std::string::npos) << plan.reason;
}

TEST_F(HalfKnownRoom, RootTooCloseToAnObstacleCanStillLeave) {
    const Eigen::Vector3d obstacle(2.3, 2.1, 1.1);  // its cell is 0.2 m from the root
    map->insertPointCloud({2.9, 2.1, 1.1}, {obstacle.cast<float>()});
    ASSERT_TRUE(map->isOccupied(obstacle));
    RhNbvpPlanner planner = makePlanner(5);
    const double r = planner.params().robotRadius;
    ASSERT_FALSE(map->isSegmentFreeOrUnknown(root, root, r));
    const Plan plan = planner.plan(contextFor(*map, root));
    ASSERT_EQ(plan.status, Plan::Status::Path) << plan.reason;
    ASSERT_EQ(plan.waypoints.size(), 1u);
    const Eigen::Vector3d& w = plan.waypoints.front().pose.position;
    EXPECT_TRUE(map->isSegmentFree(w, w, r));
    EXPECT_GT((w - obstacle).norm(), (root - obstacle).norm());
    for (const TreeNode& n : planner.tree().nodes()) {
        if (n.parent > 0) {
            EXPECT_TRUE(map->isSegmentFree(planner.tree().node(n.parent).position, n.position, r));
        }
    }
}

bool samePlans(const Plan& a, const Plan& b) {
    if (a.status != b.status || a.waypoints.size() != b.waypoints.size() ||
        a.tree.size() != b.tree.size() || a.score != b.score) {
        return false;
    }
    for (std::size_t i = 0; i < a.waypoints.size(); ++i) {
        if (a.waypoints[i].pose.position != b.waypoints[i].pose.position ||
            a.waypoints[i].pose.yaw != b.waypoints[i].pose.yaw) {
            return false;
        }
    }
    for (std::size_t i = 0; i < a.tree.size(); ++i) {
        if (a.tree[i].from != b.tree[i].from || a.tree[i].to != b.tree[i].to)
            return false;
    }
    return true;
}

TEST_F(HalfKnownRoom, SameSeedSamePlansDifferentSeedDifferentPlans) {
    RhNbvpPlanner a = makePlanner(42), b = makePlanner(42), c = makePlanner(43);
    PlanningContext ctx = contextFor(*map, root);
    for (int step = 0; step < 3; ++step) {
        const Plan pa = a.plan(ctx), pb = b.plan(ctx), pc = c.plan(ctx);
        EXPECT_TRUE(samePlans(pa, pb)) << "step " << step;
        EXPECT_FALSE(samePlans(pa, pc)) << "step " << step;
        ASSERT_EQ(pa.waypoints.size(), 1u);
        ctx.pose = pa.waypoints.front().pose;
    }
}

TEST(MotionLimits, TurnsThenFlies) {
    MotionLimits m;
    m.speed = 0.5;
    m.yawRate = 2.0;
    FlatPose a, b;
    b.position = {3, 4, 0};
    b.yaw = M_PI / 2;
    EXPECT_NEAR(m.travelTime(a, b), 10.0 + M_PI / 4, 1e-12);
    a.yaw = 3.0;
    b.yaw = -3.0;  // the short way round
    b.position = a.position;
    EXPECT_NEAR(m.travelTime(a, b), (2 * M_PI - 6.0) / 2.0, 1e-12);
}

TEST(CreatePlanner, EveryListedPlannerIsCreatedUnderItsName) {
    const auto cfg = test::configFromText(test::defaultsText());
    const auto names = plannerNames();
    EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
    EXPECT_NE(std::find(names.begin(), names.end(), "rhnbvp"), names.end());
    for (const auto& name : names) {
        const auto planner = createPlanner(name, *cfg, 1);
        ASSERT_NE(planner, nullptr) << name;
        EXPECT_EQ(planner->name(), name);
    }
}

TEST(CreatePlanner, UnknownNameListsTheValidOnes) {
    const auto cfg = test::configFromText(test::defaultsText());
    try {
        createPlanner("nbv", *cfg, 1);
        FAIL() << "unknown planner accepted";
    } catch (const InputError& e) {
        std::string valid;
        for (const auto& n : plannerNames())
            valid += (valid.empty() ? "" : ", ") + n;
        EXPECT_EQ(std::string(e.what()), "unknown planner 'nbv'; valid planners: " + valid);
    }
}

TEST(CreatePlanner, MissingOrBadKeysAreNamed) {
    const std::string text = test::defaultsText();
    const std::vector<std::pair<std::string, std::string>> keys = {{"rhnbvp", "lambda"},
                                                                   {"rhnbvp", "extension_range"},
                                                                   {"rhnbvp", "max_samples"},
                                                                   {"rhnbvp", "initial_iterations"},
                                                                   {"rhnbvp", "cutoff_iterations"},
                                                                   {"rhnbvp", "zero_gain"},
                                                                   {"planning", "robot_radius"},
                                                                   {"gain", "dtheta_deg"}};
    for (const auto& [section, key] : keys) {
        const auto cfg = test::configFromText(test::editKey(text, section, key));
        try {
            createPlanner("rhnbvp", *cfg, 1);
            FAIL() << key << " missing but accepted";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("[" + section + "] " + key), std::string::npos)
                << e.what();
        }
    }
    const std::string bad = "abc";
    const auto cfg = test::configFromText(test::editKey(text, "rhnbvp", "lambda", &bad));
    EXPECT_THROW(createPlanner("rhnbvp", *cfg, 1), InputError);
    const std::string fewer = "5";
    const auto cut =
        test::configFromText(test::editKey(text, "rhnbvp", "cutoff_iterations", &fewer));
    EXPECT_THROW(createPlanner("rhnbvp", *cut, 1), InputError);
}

}  // namespace
}  // namespace daep::planning
