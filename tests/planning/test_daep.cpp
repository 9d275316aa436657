#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "PlanningTestUtil.h"
#include "daep/common/Error.h"
#include "daep/perception/PersonTrack.h"
#include "daep/planning/DaepPlanner.h"
#include "daep/planning/FlightSpace.h"
#include "daep/planning/GainEvaluator.h"
#include "daep/planning/PlannerRegistry.h"
#include "daep/planning/WayOut.h"

namespace daep::planning {
namespace {

using perception::PersonForecast;
using test::contextFor;

std::string daepText(const std::string& key = "", const std::string& value = "") {
    std::string text = test::defaultsText();
    if (!key.empty())
        text = test::editKey(text, "daep", key, &value);
    return text;
}

DaepPlanner makePlanner(std::uint64_t seed, const std::string& key = "",
                        const std::string& value = "") {
    const auto cfg = test::configFromText(daepText(key, value));
    return DaepPlanner(DaepParams::fromConfig(*cfg), GainParams::fromConfig(*cfg), seed);
}

/** A planner on the heap, for helpers that prepare one (planners do not move). */
std::unique_ptr<DaepPlanner> newPlannerFromText(const std::string& text, std::uint64_t seed) {
    const auto cfg = test::configFromText(text);
    return std::make_unique<DaepPlanner>(DaepParams::fromConfig(*cfg), GainParams::fromConfig(*cfg),
                                         seed);
}

/** makePlanner on the heap. */
std::unique_ptr<DaepPlanner> newPlanner(std::uint64_t seed, const std::string& key = "",
                                        const std::string& value = "") {
    return newPlannerFromText(daepText(key, value), seed);
}

PersonForecast walker(int id, Eigen::Vector2d p, Eigen::Vector2d v, double t0) {
    PersonForecast f;
    f.id = id;
    f.time = t0;
    f.state << p, v;
    f.covariance.diagonal() << 1e-4, 1e-4, 1e-3, 1e-3;
    f.accelNoise = 0.02;
    return f;
}

/** A planner whose frequency map has seen one person standing at `at` for a while. */
std::unique_ptr<DaepPlanner> withPersonSeenAt(const std::string& score,
                                              const mapping::ExplorationMap& map,
                                              const Eigen::Vector2d& at) {
    const auto cfg = test::configFromText(daepText("score", score));
    auto planner = std::make_unique<DaepPlanner>(DaepParams::fromConfig(*cfg),
                                                 GainParams::fromConfig(*cfg), 1);
    PlanningContext ctx = contextFor(map, {1, 1, 1});
    for (int k = 0; k < 10; ++k) {
        ctx.time = 12.0 + 0.25 * k;
        const std::vector<PersonForecast> people{walker(0, at, {0, 0}, ctx.time)};
        ctx.people = &people;
        planner->keepFlying(ctx, Plan{}, 0);
    }
    return planner;
}

struct DaepRoom : test::HalfKnownRoomMap {};

TEST_F(DaepRoom, ScoreBoostsGainWhereTheFrequencyMapSawPeople) {
    const auto paper = withPersonSeenAt("paper", *map, {3.5, 2.5});
    const double lambda = paper->params().lambda, zeta = paper->daepParams().zeta;
    const Eigen::Vector3d busy(3.4, 2.6, 1.0), quiet(1.5, 0.5, 1.0);
    EXPECT_DOUBLE_EQ(paper->frequencyMap().value(busy.head<2>()), 1.0);
    EXPECT_DOUBLE_EQ(paper->frequencyMap().value(quiet.head<2>()), 0.0);
    const BranchObjective& score = *paper->parts().objective;
    EXPECT_NEAR(score.score(2.0, 10.0, 1.2, busy),
                2.0 + 10.0 * std::exp(-lambda * 1.2) * (1 + zeta), 1e-12);
    EXPECT_NEAR(score.score(2.0, 10.0, 1.2, quiet), 2.0 + 10.0 * std::exp(-lambda * 1.2), 1e-12);
    // The reference code's variant puts the frequency into the exponent: a penalty.
    const auto reference = withPersonSeenAt("reference", *map, {3.5, 2.5});
    EXPECT_NEAR(reference->parts().objective->score(2.0, 10.0, 1.2, busy),
                2.0 + 10.0 * std::exp(-lambda * 1.2 * (1 + zeta)), 1e-12);
}

TEST_F(DaepRoom, WithoutPeopleItPlansLikeAepToTheUnknown) {
    DaepPlanner planner = makePlanner(5);
    const Plan plan = planner.plan(contextFor(*map, root));
    ASSERT_EQ(plan.status, Plan::Status::Path);
    ASSERT_FALSE(plan.waypoints.empty());
    EXPECT_GT(plan.gain, 0.0);
}

TEST_F(DaepRoom, EveryPlannedMoveKeepsClearOfWalkingPeople) {
    // Two people cross the known half of the room while the drone plans from its middle.
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
        DaepPlanner planner = makePlanner(seed);
        PlanningContext ctx = contextFor(*map, root);
        const std::vector<PersonForecast> people{walker(0, {0.5, 3.0}, {0.35, 0}, ctx.time),
                                                 walker(1, {4.0, 0.5}, {-0.2, 0.25}, ctx.time)};
        ctx.people = &people;
        const Plan plan = planner.plan(ctx);
        ASSERT_EQ(plan.status, Plan::Status::Path) << seed;
        const std::vector<TimedSegment> moves = planner.timedMoves(ctx, plan, 0);
        for (const TimedSegment& m : moves)
            EXPECT_TRUE(planner.obstacles().isSafe(m)) << "seed " << seed;
        // Every node of the tree was reached by safe moves at its own arrival time.
        const Tree& tree = planner.tree();
        for (int i = 1; i < tree.size(); ++i) {
            const TreeNode& n = tree.node(i);
            const TreeNode& parent = tree.node(n.parent);
            EXPECT_NEAR(n.time,
                        parent.time + ctx.motion.travelTime({parent.position, parent.yaw},
                                                            {n.position, n.yaw}),
                        1e-9);
        }
    }
}

TEST_F(DaepRoom, EscapesAPersonWalkingAtTheHoveringDrone) {
    DaepPlanner planner = makePlanner(3);
    PlanningContext ctx = contextFor(*map, root);
    // 1.6 m away, coming straight at the drone: contact within about 2 s.
    const std::vector<PersonForecast> people{walker(0, {3.6, 2.0}, {-0.35, 0}, ctx.time)};
    ctx.people = &people;
    ASSERT_FALSE(DynamicObstacles(planner.daepParams().safety, people)
                     .isSafeToHover(root, ctx.time, ctx.time + 3));
    const Plan plan = planner.plan(ctx);
    ASSERT_EQ(plan.status, Plan::Status::Path);
    ASSERT_FALSE(plan.waypoints.empty()) << plan.reason;
    const TimedSegment first = planner.timedMoves(ctx, plan, 0).front();
    TimedSegment stay;
    stay.from = stay.to = root;
    stay.start = ctx.time;
    stay.turnTime = first.end() - ctx.time;
    EXPECT_GT(planner.obstacles().clearance(first), planner.obstacles().clearance(stay))
        << plan.reason;
    EXPECT_TRUE(map->isSegmentFree(first.to, first.to, planner.params().robotRadius));
}

TEST_F(DaepRoom, TheEscapeMovesAtOnceToSafetyPreferringWhatTheCameraSees) {
    DaepPlanner planner = makePlanner(3);
    // Facing south-west while a person walks at the drone from the east.
    const double yaw = -2.4;
    PlanningContext ctx = contextFor(*map, root, yaw);
    std::vector<PersonForecast> people{walker(0, {3.5, 2.0}, {-0.35, 0}, ctx.time)};
    people[0].accelNoise = 1e-4;  // a steady walker: the prediction stays tight
    ctx.people = &people;
    const Plan plan = planner.escape(ctx);
    ASSERT_EQ(plan.waypoints.size(), 1u) << plan.reason;
    const FlatPose goal = plan.waypoints[0].pose;
    EXPECT_DOUBLE_EQ(goal.yaw, yaw);  // no turn first
    const double r = planner.params().robotRadius;
    EXPECT_TRUE(map->isSegmentFree(root, goal.position, r));
    const double horizon = planner.daepParams().evasionHorizon;
    auto clearanceVia = [&](const Eigen::Vector3d& to) {
        const TimedSegment move = timedSegment(ctx.pose, {to, yaw}, ctx.time, 0.5, 1.0);
        TimedSegment hover;
        hover.from = hover.to = to;
        hover.start = move.end();
        hover.turnTime = std::max(0.0, ctx.time + horizon - move.end());
        return std::min(planner.obstacles().clearance(move), planner.obstacles().clearance(hover));
    };
    // Staying is unsafe; the escape is safe, and in view.
    EXPECT_LT(clearanceVia(root), 0.0);
    EXPECT_GT(clearanceVia(goal.position), 0.0) << plan.reason;
    EXPECT_EQ(plan.reason.find("blind"), std::string::npos) << plan.reason;
    // In flight the escape is not stopped by the person it escapes from.
    EXPECT_TRUE(plan.escape);
    EXPECT_TRUE(planner.keepFlying(ctx, plan, 0));
    // No shorter safe escape along the camera's view (or, if the escape is blind, none at all).
    const Eigen::Vector2d chosen = (goal.position - root).head<2>();
    const bool chosenSeen =
        std::abs(wrapAngle(std::atan2(chosen.y(), chosen.x()) - yaw)) <= 0.5 * GainParams{}.hfov;
    for (const double d : {0.4, 0.8, 1.2, 1.6})
        for (int k = 0; k < 16; ++k) {
            const double a = 2 * M_PI * k / 16;
            const Eigen::Vector3d other = root + d * Eigen::Vector3d(std::cos(a), std::sin(a), 0);
            const bool seen = std::abs(wrapAngle(a - yaw)) <= 0.5 * GainParams{}.hfov;
            if (!map->isSegmentFree(root, other, r) || clearanceVia(other) <= 0.0)
                continue;
            EXPECT_FALSE(seen && !chosenSeen) << "a seen escape was safe: " << k << " " << d;
            if (seen == chosenSeen) {
                EXPECT_GE(d, chosen.norm() - 1e-9) << k;
            }
        }
}

TEST_F(DaepRoom, AnEscapeIsDroppedOnlyForAClearlyBetterOneWhenItsWayIsNoLongerClear) {
    DaepPlanner planner = makePlanner(3);
    PlanningContext ctx = contextFor(*map, root, -2.4);
    std::vector<PersonForecast> coming{walker(0, {3.5, 2.0}, {-0.35, 0}, ctx.time)};
    coming[0].accelNoise = 1e-4;
    ctx.people = &coming;
    const Plan plan = planner.escape(ctx);
    ASSERT_TRUE(plan.escape);
    ASSERT_EQ(plan.waypoints.size(), 1u) << plan.reason;
    const Eigen::Vector3d goal = plan.waypoints[0].pose.position;
    // A frame later, halfway: the walker came on as predicted, so the escape is flown on.
    PlanningContext later = ctx;
    later.time += 0.2;
    later.pose.position = 0.5 * (root + goal);
    std::vector<PersonForecast> asPredicted{walker(0, {3.43, 2.0}, {-0.35, 0}, later.time)};
    asPredicted[0].accelNoise = 1e-4;
    later.people = &asPredicted;
    EXPECT_TRUE(planner.keepFlying(later, plan, 0));
    // Someone the camera had not seen stands 1 m to the side of where the escape leads: it is
    // dropped for a fresh escape that keeps clearly farther from both.
    std::vector<PersonForecast> beside = asPredicted;
    beside.push_back(walker(1, goal.head<2>() + Eigen::Vector2d(0.0, -1.0), {0, 0}, later.time));
    beside[1].accelNoise = 1e-4;
    later.people = &beside;
    EXPECT_FALSE(planner.keepFlying(later, plan, 0));
    const Plan fresh = planner.escape(later);
    ASSERT_TRUE(fresh.escape) << fresh.reason;
    const WayOut onward = judgeWay(planner.obstacles(), later.pose.position, later.time, {goal},
                                   later.motion, later.time + planner.daepParams().evasionHorizon);
    std::vector<Eigen::Vector3d> freshPath;
    for (const Waypoint& w : fresh.waypoints)
        freshPath.push_back(w.pose.position);
    const WayOut instead = judgeWay(planner.obstacles(), later.pose.position, later.time, freshPath,
                                    later.motion, later.time + planner.daepParams().evasionHorizon);
    EXPECT_GT(onward.exposure, 0.0);
    EXPECT_LT(instead.exposure, onward.exposure - 0.4) << fresh.reason;
}

TEST_F(DaepRoom, InsideAKeepOutAlreadyTheEscapeLeadsAwayFromThePerson) {
    // Someone stands 1 m east of the drone, well inside the distance bodies keep: every move
    // shares the gap at its start, so only where the moves lead can tell them apart.
    DaepPlanner planner = makePlanner(3);
    PlanningContext ctx = contextFor(*map, root, 0.0);
    std::vector<PersonForecast> people{walker(0, {3.0, 2.0}, {0, 0}, ctx.time)};
    people[0].accelNoise = 1e-4;
    ctx.people = &people;
    const Plan plan = planner.escape(ctx);
    ASSERT_EQ(plan.waypoints.size(), 1u) << plan.reason;
    const Eigen::Vector2d away = (plan.waypoints[0].pose.position - root).head<2>();
    EXPECT_GT(away.norm(), 0.3) << plan.reason;
    EXPECT_LT(away.x(), -0.95 * away.norm()) << plan.reason;  // west, straight away
}

TEST_F(DaepRoom, UnderALowCeilingTheEscapeLeadsAwayFromAWalkerNotTowardsThem) {
    // The box is 2 m high, so the drone (at most 1.7 m) cannot climb over a person's head
    // (1.85 m plus the clearance). Just under the ceiling, with someone 0.7 m east walking at
    // the drone, every escape was as deep below the head as the drone is: they tied, and the
    // first candidate, 0.4 m east, won (the Crosswalks collisions of stop 33).
    DaepPlanner planner = makePlanner(3);
    const Eigen::Vector3d high(2.0, 2.0, 1.6);
    PlanningContext ctx = contextFor(*map, high, 0.0);
    std::vector<PersonForecast> people{walker(0, {2.7, 2.0}, {-0.35, 0}, ctx.time)};
    people[0].accelNoise = 1e-4;
    ctx.people = &people;
    const Plan plan = planner.escape(ctx);
    ASSERT_FALSE(plan.waypoints.empty()) << plan.reason;
    const Eigen::Vector2d away = (plan.waypoints.back().pose.position - high).head<2>();
    EXPECT_GT(away.norm(), 0.3) << plan.reason;
    EXPECT_LT(away.x(), -0.7 * away.norm()) << plan.reason;  // westwards, ahead of them
}

TEST_F(DaepRoom, KeepFlyingStopsWhenAPersonIsPredictedOnTheRestOfThePath) {
    DaepPlanner planner = makePlanner(2);
    PlanningContext ctx = contextFor(*map, root);
    Plan plan;
    plan.status = Plan::Status::Path;
    plan.waypoints.push_back({{{3.5, 2.0, 1.0}, 0.0}, ctx.time + 3.0});
    const std::vector<PersonForecast> far{walker(0, {0.5, 3.5}, {0, 0}, ctx.time)};
    ctx.people = &far;
    EXPECT_TRUE(planner.keepFlying(ctx, plan, 0));
    // Someone steps towards the drone's way: at 0.35 m/s they meet it mid-path.
    const std::vector<PersonForecast> crossing{walker(0, {2.8, 0.6}, {0, 0.35}, ctx.time)};
    ctx.people = &crossing;
    EXPECT_FALSE(planner.keepFlying(ctx, plan, 0));
}

TEST_F(DaepRoom, EvasionWhileHoveringOnlyWhenHoveringHereIsNoLongerSafe) {
    DaepPlanner planner = makePlanner(3);
    PlanningContext ctx = contextFor(*map, root);
    const std::vector<PersonForecast> far{walker(0, {0.5, 3.5}, {0, 0}, ctx.time)};
    ctx.people = &far;
    const double later = ctx.time + 100.0;  // capped at evasion_horizon_s
    EXPECT_FALSE(planner.evasion(ctx, later).has_value());
    // The same person 1.6 m away, coming straight at the drone: escape now.
    const std::vector<PersonForecast> coming{walker(0, {3.6, 2.0}, {-0.35, 0}, ctx.time)};
    ctx.people = &coming;
    // Not when the drone hovers for only 0.3 s more: the plan then in hand will see to it.
    EXPECT_FALSE(planner.evasion(ctx, ctx.time + 0.3).has_value());
    const std::optional<Plan> escape = planner.evasion(ctx, later);
    ASSERT_TRUE(escape.has_value());
    EXPECT_TRUE(escape->escape) << escape->reason;
    ASSERT_FALSE(escape->waypoints.empty());
    for (const Waypoint& w : escape->waypoints)  // no turn: the drone moves at once
        EXPECT_DOUBLE_EQ(w.pose.yaw, ctx.pose.yaw);
    EXPECT_NE(escape->reason.find("evasion"), std::string::npos) << escape->reason;
}

TEST_F(DaepRoom, APlanSafeWhenPlanningBeganButNotWhenItEndsDoesNotStart) {
    DaepPlanner planner = makePlanner(2);
    PlanningContext ctx = contextFor(*map, root);
    const std::vector<PersonForecast> nobody;
    ctx.people = &nobody;
    const Plan plan = planner.plan(ctx);
    ASSERT_FALSE(plan.waypoints.empty()) << plan.reason;
    // Planning took 2 s; meanwhile a frame showed someone standing on the path's first leg.
    PlanningContext later = ctx;
    later.time = ctx.time + 2.0;
    EXPECT_TRUE(planner.startsSafely(later, plan));
    const Eigen::Vector3d on = 0.5 * (root + plan.waypoints.front().pose.position);
    const std::vector<PersonForecast> inTheWay{walker(0, on.head<2>(), {0, 0}, later.time)};
    later.people = &inTheWay;
    EXPECT_FALSE(planner.startsSafely(later, plan));
    Plan escape = plan;
    escape.escape = true;  // an escape is the best move there is: it is flown
    EXPECT_TRUE(planner.startsSafely(later, escape));
}

/** Four people standing across the 4 m wide corridor at x = 6, measured at t. */
std::vector<PersonForecast> peopleAcrossTheCorridor(double t) {
    std::vector<PersonForecast> wall;
    for (int i = 0; i < 4; ++i)
        wall.push_back(walker(i, {6.0, 0.5 + i}, {0, 0}, t));
    return wall;
}

TEST(DaepDynamicFrontiers, PeopleBlockingTheWayToTheUnknownMakeItWaitNotFinish) {
    // Four people stand across the corridor at x = 6; the unknown lies beyond x = 12.
    auto map = test::westKnown(16.0, 12.0);
    DaepPlanner planner = makePlanner(3);
    PlanningContext ctx = contextFor(*map, {2.0, 2.0, 1.0});
    std::vector<PersonForecast> wall = peopleAcrossTheCorridor(ctx.time);
    ctx.people = &wall;
    const Plan blocked = planner.plan(ctx);
    ASSERT_EQ(blocked.status, Plan::Status::Path) << blocked.reason;
    EXPECT_NE(blocked.reason.find("people block the way"), std::string::npos) << blocked.reason;
    EXPECT_GT(planner.cache().size(), 0u);  // the frontiers beyond them are kept
    for (const Waypoint& w : blocked.waypoints)
        EXPECT_LT(w.pose.position.x(), 5.0);  // it waits on its side (a look around)
    // However long they stand there, it does not give up.
    for (int k = 0; k < 4; ++k) {
        ctx.time += 1.0;
        for (PersonForecast& f : wall)
            f.time = ctx.time;
        ASSERT_NE(planner.plan(ctx).status, Plan::Status::Finished) << k;
    }
    // Once they have gone, it sets off towards the unknown.
    const std::vector<PersonForecast> nobody;
    ctx.people = &nobody;
    const Plan free = planner.plan(ctx);
    ASSERT_EQ(free.status, Plan::Status::Path) << free.reason;
    ASSERT_FALSE(free.waypoints.empty()) << free.reason;
    EXPECT_GT(free.waypoints.back().pose.position.x(), 2.2) << free.reason;  // east, onwards
}

TEST(DaepDynamicFrontiers, FinishesOnceTheBlockedFrontierIsGone) {
    auto map = test::westKnown(16.0, 12.0);
    DaepPlanner planner = makePlanner(4);
    PlanningContext ctx = contextFor(*map, {2.0, 2.0, 1.0});
    std::vector<PersonForecast> wall = peopleAcrossTheCorridor(ctx.time);
    ctx.people = &wall;
    ASSERT_NE(planner.plan(ctx).status, Plan::Status::Finished);
    // The whole corridor becomes known (seen from the far end): nothing is left to explore.
    auto known = test::westKnown(16.0, 16.5);
    PlanningContext done = contextFor(*known, {2.0, 2.0, 1.0});
    done.people = &wall;
    Plan plan;
    for (int k = 0; k < 30 && plan.status != Plan::Status::Finished; ++k) {
        done.time += 1.0;
        plan = planner.plan(done);
    }
    EXPECT_EQ(plan.status, Plan::Status::Finished) << plan.reason;
}

/** westKnown(16, 12) with cells 0.3 to 0.5 m around `at` occupied (a head passing under it). */
std::unique_ptr<mapping::ExplorationMap> hemmedInAt(const Eigen::Vector3d& at) {
    auto map = test::westKnown(16.0, 12.0);
    for (double x = -0.7; x < 0.8; x += 0.2)
        for (double y = -0.7; y < 0.8; y += 0.2)
            for (double z = -0.7; z < 0.8; z += 0.2) {
                const Eigen::Vector3d c = map->cellCenter(at + Eigen::Vector3d(x, y, z));
                const double d = (c - map->cellCenter(at)).norm();
                if (d > 0.25 && d < 0.5)
                    map->insertPointCloud(c, {c.cast<float>()});
            }
    return map;
}

TEST(DaepDynamicFrontiers, HemmedInByAnImprintMappedAroundItItWaitsForTheMapToClear) {
    // The frontiers beyond x = 12 are cached, with or without someone seen far off; then the
    // cells all around the hovering drone are mapped occupied: no tree node can be added.
    for (const bool someoneSeen : {true, false}) {
        auto open = test::westKnown(16.0, 12.0);
        const std::unique_ptr<DaepPlanner> owned = newPlanner(5, "global_planner_counter", "25");
        DaepPlanner& planner = *owned;
        const std::vector<PersonForecast> nobody;
        const std::vector<PersonForecast> farOff{walker(0, {15.0, 0.5}, {0, 0}, 12.0)};
        PlanningContext ctx = contextFor(*open, {9.0, 2.0, 1.0});
        ctx.people = someoneSeen ? &farOff : &nobody;
        ASSERT_FALSE(planner.plan(ctx).waypoints.empty());
        ASSERT_GT(planner.cache().size(), 0u);
        const Eigen::Vector3d at(2.0, 2.0, 1.0);
        auto hemmed = hemmedInAt(at);
        ASSERT_FALSE(hemmed->isSegmentFree(at, at, planner.params().robotRadius));
        PlanningContext stuck = contextFor(*hemmed, at);
        stuck.people = &nobody;
        Plan plan;
        for (int k = 0; k < 30; ++k) {
            stuck.time += 0.25;
            plan = planner.plan(stuck);
            if (plan.status == Plan::Status::Finished)
                break;
        }
        if (!someoneSeen) {  // a world without people: nothing else could have hemmed it in
            EXPECT_EQ(plan.status, Plan::Status::Finished) << plan.reason;
            continue;
        }
        // Among people, more plans than the counter, each saying why; none ends the mission.
        ASSERT_NE(plan.status, Plan::Status::Finished) << plan.reason;
        EXPECT_NE(plan.reason.find("hemmed in where it hovers"), std::string::npos) << plan.reason;
        // The camera cleared the imprint: on towards the frontiers.
        PlanningContext cleared = contextFor(*open, at);
        cleared.people = &nobody;
        cleared.time = stuck.time + 0.25;
        plan = planner.plan(cleared);
        ASSERT_FALSE(plan.waypoints.empty()) << plan.reason;
        EXPECT_GT(plan.waypoints.back().pose.position.x(), 2.5) << plan.reason;
    }
}

TEST_F(DaepRoom, FrontiersPeopleHideForNowAreStillCached) {
    // Someone is within view range of every node: the tree scores the views past them, and
    // the cache keeps what each node would see were they gone.
    DaepPlanner planner = makePlanner(6);
    PlanningContext ctx = contextFor(*map, root);
    const std::vector<PersonForecast> people{
        walker(0, {1.0, 1.0}, {0, 0}, ctx.time), walker(1, {1.0, 3.0}, {0, 0}, ctx.time),
        walker(2, {6.5, 1.0}, {0, 0}, ctx.time), walker(3, {6.5, 3.0}, {0, 0}, ctx.time)};
    ctx.people = &people;
    planner.plan(ctx);
    ASSERT_GT(planner.cache().size(), 0u);
    const GainEvaluator gain(GainParams::fromConfig(*test::configFromText(daepText())));
    for (int id : planner.cache().liveIds()) {
        const CachedGain& c = planner.cache().entry(id);
        EXPECT_GT(c.gain, planner.params().view.cacheThreshold);
        EXPECT_LE(c.gain, gain.bestYaw(*map, c.position).gain * 6.0 + 1e-9);  // boosted at most
    }
}

TEST(DaepParams, MissingOrBadKeysAreNamed) {
    const std::string text = test::defaultsText();
    const auto missing = test::configFromText(test::editKey(text, "daep", "sigma_inflation"));
    try {
        DaepParams::fromConfig(*missing);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("[daep] sigma_inflation"), std::string::npos)
            << e.what();
    }
    const std::string bad = "sideways";
    const auto wrong = test::configFromText(test::editKey(text, "daep", "score", &bad));
    EXPECT_THROW(DaepParams::fromConfig(*wrong), InputError);
    const DaepParams p = DaepParams::fromConfig(*test::configFromText(text));
    EXPECT_DOUBLE_EQ(p.aep.zeroGain, 15.0);  // DAEP's value, not AEP's 25
    EXPECT_DOUBLE_EQ(p.aep.lambda, 0.75);
    EXPECT_DOUBLE_EQ(p.zeta, 0.5);
    EXPECT_DOUBLE_EQ(p.borderBoost, 6.0);
    EXPECT_EQ(p.score, daep::planning::DynamicScore::Paper);
}

TEST(DaepPlanner, IsCreatedByNameAndWantsPeople) {
    const auto cfg = test::configFromText(test::defaultsText());
    const auto planner = createPlanner("daep", *cfg, 1);
    EXPECT_EQ(planner->name(), "daep");
    EXPECT_TRUE(planner->usesPeople());
    EXPECT_FALSE(createPlanner("aep", *cfg, 1)->usesPeople());
}

}  // namespace
}  // namespace daep::planning

namespace daep::planning {
namespace {

TEST_F(DaepRoom, FacingTravelFliesEveryLegLookingAheadThenTurnsToTheView) {
    DaepPlanner planner = makePlanner(4, "face_travel_direction", "true");
    PlanningContext ctx = contextFor(*map, root, 2.5);
    const std::vector<PersonForecast> people{walker(0, {0.6, 0.6}, {0.1, 0.0}, ctx.time)};
    ctx.people = &people;
    const Plan plan = planner.plan(ctx);
    ASSERT_GE(plan.waypoints.size(), 1u) << plan.reason;
    FlatPose at = ctx.pose;
    for (const Waypoint& w : plan.waypoints) {
        const Eigen::Vector2d leg = (w.pose.position - at.position).head<2>();
        if (leg.norm() > 0.05) {  // a flight leg: flown facing along it
            EXPECT_NEAR(std::abs(wrapAngle(w.pose.yaw - std::atan2(leg.y(), leg.x()))), 0.0, 1e-9);
        }
        at = w.pose;
    }
    // The tree's arrival times include both turns.
    const Tree& tree = planner.tree();
    for (int i = 1; i < tree.size(); ++i) {
        const TreeNode& n = tree.node(i);
        const TreeNode& p = tree.node(n.parent);
        const Eigen::Vector2d leg = (n.position - p.position).head<2>();
        if (leg.norm() < 0.05)
            continue;
        const double heading = std::atan2(leg.y(), leg.x());
        const double expected = std::abs(wrapAngle(heading - p.yaw)) +
                                (n.position - p.position).norm() / 0.5 +
                                std::abs(wrapAngle(n.yaw - heading));
        EXPECT_NEAR(n.time - p.time, expected, 1e-9) << i;
    }
}

/** newPlanner(3) with `blind_lost_s` set as well (0: people lost are followed along walkways). */
std::unique_ptr<DaepPlanner> newPlannerFollowingLost(const std::string& lostSeconds,
                                                     const std::string& key = "",
                                                     const std::string& value = "") {
    return newPlannerFromText(
        test::editKey(daepText(key, value), "daep", "blind_lost_s", &lostSeconds), 3);
}

/**
 * A camera-fed planner (with `key` = `value` in [daep]) that saw a person stand behind it, at
 * (0.5, 2.5), then lost them at 4.25 s; by default (`lostSeconds` = 0) it follows them along
 * the walkways alone, the room's one walkway their cell.
 */
std::unique_ptr<DaepPlanner> guardedAfterAWalkerBehind(const mapping::ExplorationMap& map,
                                                       const Eigen::Vector3d& at,
                                                       const std::string& value,
                                                       const std::string& key = "blind_guard",
                                                       const std::string& lostSeconds = "0") {
    std::unique_ptr<DaepPlanner> owned = newPlannerFollowingLost(lostSeconds, key, value);
    DaepPlanner& planner = *owned;
    PlanningContext ctx = contextFor(map, at);  // facing +x: the walker is behind
    ctx.peopleFromCamera = true;
    for (int k = 0; k < 10; ++k) {
        ctx.time = 2.0 + 0.25 * k;
        const std::vector<PersonForecast> people{walker(0, {0.5, 2.5}, {0, 0}, ctx.time)};
        ctx.people = &people;
        planner.keepFlying(ctx, Plan{}, 0);
    }
    return owned;
}

TEST_F(DaepRoom, BeforeStoppingNearAWalkwayItHasNotWatchedItTurnsToLookAtIt) {
    const std::unique_ptr<DaepPlanner> owned = guardedAfterAWalkerBehind(*map, root, "auto");
    DaepPlanner& planner = *owned;
    PlanningContext ctx = contextFor(*map, root);  // t = 12: the walkway unseen for 10 s
    ctx.peopleFromCamera = true;
    const std::vector<PersonForecast> nobody;
    ctx.people = &nobody;
    for (int look = 0; look < planner.daepParams().blind.maxLooks; ++look) {
        const Plan plan = planner.plan(ctx);
        ASSERT_EQ(plan.waypoints.size(), 1u);
        EXPECT_EQ(plan.reason.rfind("look:", 0), 0u) << plan.reason;
        EXPECT_TRUE(plan.waypoints[0].pose.position.isApprox(root));
        EXPECT_NEAR(plan.waypoints[0].pose.yaw, std::atan2(0.5, -1.5), 1e-9);
        ctx.time += 0.1;  // still facing away: the walkway stays unseen
    }
    // After blind_max_looks looks in a row it goes anyway.
    const Plan go = planner.plan(ctx);
    ASSERT_FALSE(go.waypoints.empty());
    EXPECT_EQ(go.reason.rfind("look:", 0), std::string::npos) << go.reason;
    EXPECT_GT((go.waypoints[0].pose.position - root).norm(), 0.1);
}

TEST_F(DaepRoom, ALookBeforeAStopTurnsToSeeEveryWalkwayThatThreatensIt) {
    // Two walkers stood behind the drone, 90 degrees apart as it sees them, then were lost.
    // Turned at either walkway the camera (103 degrees wide) misses the other; turned between
    // them it sees both, and the stop is clear after one look. Followed along their walkways
    // alone: off them, in the small room, they could be anywhere behind the drone by now.
    std::unique_ptr<DaepPlanner> owned = newPlannerFollowingLost("0");
    DaepPlanner& planner = *owned;
    const Eigen::Vector2d west(0.5, 2.5), south(1.5, 0.5);
    PlanningContext ctx = contextFor(*map, root);  // facing +x: both are behind
    ctx.peopleFromCamera = true;
    for (int k = 0; k < 10; ++k) {
        ctx.time = 2.0 + 0.25 * k;
        const std::vector<PersonForecast> people{walker(0, west, {0, 0}, ctx.time),
                                                 walker(1, south, {0, 0}, ctx.time)};
        ctx.people = &people;
        planner.keepFlying(ctx, Plan{}, 0);
    }
    const std::vector<PersonForecast> nobody;
    ctx.people = &nobody;
    ctx.time = 12.0;
    const Plan look = planner.plan(ctx);
    ASSERT_EQ(look.waypoints.size(), 1u);
    ASSERT_EQ(look.reason.rfind("look:", 0), 0u) << look.reason;
    const FlatPose turned = look.waypoints[0].pose;
    EXPECT_TRUE(turned.position.isApprox(root));
    const double halfFov = 0.5 * GainParams::fromConfig(*test::configFromText(daepText())).hfov;
    for (const Eigen::Vector2d& walkway : {west, south}) {
        const Eigen::Vector2d d = walkway - root.head<2>();
        EXPECT_LT(std::abs(wrapAngle(std::atan2(d.y(), d.x()) - turned.yaw)), halfFov)
            << walkway.transpose() << " " << look.reason;
    }
    // The look flown, the camera saw nobody there: the stop needs no second look.
    ctx.pose = turned;
    ctx.time = look.waypoints[0].arrivalTime;
    planner.keepFlying(ctx, Plan{}, 0);
    ctx.time += 0.2;
    const Plan go = planner.plan(ctx);
    ASSERT_FALSE(go.waypoints.empty());
    EXPECT_EQ(go.reason.rfind("look:", 0), std::string::npos) << go.reason;
}

TEST_F(DaepRoom, TheBlindWatchCountsAsSeenOnlyWhatTheCameraFindsPeopleIn) {
    // Facing +x down the 8 m room: a cell 5.5 m ahead is seen by a camera that finds people up
    // to blind_watch_range (10 m), not by one whose detector stops at 5 m.
    const Eigen::Vector2d near(4.5, 2.5), far(7.5, 2.5);
    for (const double range : {std::numeric_limits<double>::infinity(), 5.0}) {
        std::unique_ptr<DaepPlanner> planner = newPlanner(3);
        PlanningContext ctx = contextFor(*map, root);
        ctx.peopleFromCamera = true;
        ctx.peopleRange = range;
        const std::vector<PersonForecast> nobody;
        ctx.people = &nobody;
        ctx.time = 1.0;
        planner->keepFlying(ctx, Plan{}, 0);
        EXPECT_EQ(planner->blindWatch().lastSeen(near), 1.0) << range;
        EXPECT_EQ(planner->blindWatch().lastSeen(far) == 1.0, range > 5.5) << range;
    }
}

TEST_F(DaepRoom, AWalkwayJustLookedAtOrAGuardSwitchedOffNeedsNoLook) {
    const std::vector<PersonForecast> nobody;
    {
        const std::unique_ptr<DaepPlanner> owned = guardedAfterAWalkerBehind(*map, root, "auto");
        DaepPlanner& planner = *owned;
        PlanningContext ctx = contextFor(*map, root, std::atan2(0.5, -1.5));  // facing it now
        ctx.peopleFromCamera = true;
        ctx.people = &nobody;
        planner.keepFlying(ctx, Plan{}, 0);
        ctx.time += 0.2;
        const Plan plan = planner.plan(ctx);
        ASSERT_FALSE(plan.waypoints.empty());
        EXPECT_EQ(plan.reason.rfind("look:", 0), std::string::npos) << plan.reason;
    }
    for (const char* guard : {"auto", "false"}) {
        const std::unique_ptr<DaepPlanner> owned = guardedAfterAWalkerBehind(*map, root, guard);
        DaepPlanner& planner = *owned;
        PlanningContext ctx = contextFor(*map, root);
        ctx.peopleFromCamera = std::string(guard) == "false";  // auto needs camera people
        ctx.people = &nobody;
        const Plan plan = planner.plan(ctx);
        ASSERT_FALSE(plan.waypoints.empty());
        EXPECT_EQ(plan.reason.rfind("look:", 0), std::string::npos) << guard << plan.reason;
    }
}

TEST_F(DaepRoom, TheBlindWatchSaysWhetherSomeoneUnseenCouldBeAtAPlace) {
    const Eigen::Vector2d walkway(0.5, 2.5), farFromIt(6.5, 2.5);
    const std::vector<PersonForecast> nobody;
    const std::unique_ptr<DaepPlanner> owned =
        guardedAfterAWalkerBehind(*map, root, "auto", "blind_guard", "30");
    DaepPlanner& planner = *owned;
    // Lost behind the drone at 4.25 s: they may be there still; off the walkway, they may
    // have walked 1.4 m (behind the drone, unseen) but not 6 m; and after blind_lost_s the
    // guard expects them on the walkways alone.
    EXPECT_EQ(planner.unseenWatchAt(walkway, 12.0), UnseenWatch::Open);
    EXPECT_EQ(planner.unseenWatchAt({1.5, 3.5}, 12.0), UnseenWatch::Lost);
    EXPECT_STREQ(unseenWatchName(UnseenWatch::Lost), "lost");
    EXPECT_EQ(planner.unseenWatchAt(farFromIt, 12.0), UnseenWatch::NoWalkway);
    EXPECT_STREQ(unseenWatchName(UnseenWatch::NoWalkway), "no_walkway");
    EXPECT_EQ(planner.unseenWatchAt({1.5, 3.5}, 4.25 + 30.1), UnseenWatch::NoWalkway);
    // Turned to the walkway, the camera finds it empty: cleared until someone could walk in.
    PlanningContext ctx = contextFor(*map, root, std::atan2(0.5, -1.5));
    ctx.peopleFromCamera = true;
    ctx.people = &nobody;
    planner.keepFlying(ctx, Plan{}, 0);
    EXPECT_EQ(planner.unseenWatchAt(walkway, ctx.time), UnseenWatch::Cleared);
    EXPECT_STREQ(unseenWatchName(UnseenWatch::Cleared), "cleared");
    // People from ground truth: the guard is off, and so is its watch.
    ctx.peopleFromCamera = false;
    planner.keepFlying(ctx, Plan{}, 0);
    EXPECT_EQ(planner.unseenWatchAt(walkway, ctx.time), UnseenWatch::None);
    EXPECT_STREQ(unseenWatchName(UnseenWatch::None), "-");
}

/** An 8 x 4 x 2.5 m box (room over the heads) under a 2.7 m ceiling, seen from (2, 2, 1). */
struct TallRoom : test::HalfKnownRoomMap {
    void SetUp() override { map = test::halfSeenRoom(2.5, 2.7); }
};

/** The same plan made with fly_over_heads = `lift` and false: raised, and as planned. */
std::pair<Plan, Plan> planRaisedAndNot(const mapping::ExplorationMap& map,
                                       const Eigen::Vector3d& at, std::uint64_t seed,
                                       const std::string& lift, bool fromCamera) {
    PlanningContext ctx = contextFor(map, at);
    ctx.peopleFromCamera = fromCamera;
    const std::vector<PersonForecast> nobody;
    ctx.people = &nobody;
    DaepPlanner raising = makePlanner(seed, "fly_over_heads", lift);
    DaepPlanner asPlanned = makePlanner(seed, "fly_over_heads", "false");
    return {raising.plan(ctx), asPlanned.plan(ctx)};
}

/**
 * Plans from `root` with people from the camera, raised and as planned, seeds 1-6: every stop
 * is the planned one, at its height or at `overHeads`, and points added to climb are at
 * `overHeads`; every leg is flyable and timed as flown. Returns how many stops were raised.
 */
int stopsRaisedTo(const mapping::ExplorationMap& map, const Eigen::Vector3d& root,
                  double overHeads) {
    int raised = 0;
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        const auto [plan, asPlanned] = planRaisedAndNot(map, root, seed, "auto", true);
        EXPECT_EQ(plan.status, Plan::Status::Path) << plan.reason;
        EXPECT_NE(plan.reason.find("over heads"), std::string::npos) << plan.reason;
        PlanningContext ctx = contextFor(map, root);
        FlatPose at = ctx.pose;
        double t = ctx.time;
        std::size_t k = 0;  // the planned stop met next
        for (const Waypoint& w : plan.waypoints) {
            const FlatPose& p = w.pose;
            EXPECT_TRUE(segmentFlyable(map, at.position, p.position, 0.3, 0.05, false)) << seed;
            t += ctx.motion.travelTime(at, p);  // timed as flown, climbs included
            EXPECT_NEAR(w.arrivalTime, t, 1e-9) << seed;
            const FlatPose before = at;
            at = p;
            if (before.position.z() < overHeads - 1e-9 && p.position.z() > overHeads - 1e-9 &&
                p.position.head<2>().isApprox(before.position.head<2>(), 1e-9)) {
                EXPECT_DOUBLE_EQ(p.yaw, before.yaw) << "a climb on the spot before its turn";
            }
            if (k >= asPlanned.waypoints.size()) {
                ADD_FAILURE() << "more stops than planned, seed " << seed;
                break;
            }
            const FlatPose& q = asPlanned.waypoints[k].pose;
            if (!p.position.head<2>().isApprox(q.position.head<2>(), 1e-9) || p.yaw != q.yaw) {
                // A point added to climb first, over the heads: with the leg's heading, or
                // straight up with the heading the drone had, before the turn.
                EXPECT_NEAR(p.position.z(), overHeads, 1e-9) << seed;
                if (p.yaw != q.yaw) {  // straight up, then (next) the turn
                    EXPECT_TRUE(p.position.head<2>().isApprox(before.position.head<2>(), 1e-9));
                }
                continue;
            }
            // The same stop, the same view; higher where its legs allow it.
            EXPECT_DOUBLE_EQ(p.yaw, q.yaw);
            if (std::abs(p.position.z() - overHeads) < 1e-9)
                ++raised;
            else
                EXPECT_DOUBLE_EQ(p.position.z(), q.position.z()) << seed;
            ++k;
        }
        EXPECT_EQ(k, asPlanned.waypoints.size()) << seed;  // every planned stop, in order
    }
    return raised;
}

TEST_F(TallRoom, WithPeopleFromTheCameraStopsAreRaisedOverTheirHeads) {
    // Over a body (1.8 m), half the drone (0.05 m), the clearance (0.2 m) and 5 cm.
    EXPECT_GT(stopsRaisedTo(*map, root, 1.8 + 0.05 + 0.2 + 0.05), 3);
}

/** An 8 x 4 x 2 m box (Crosswalks' height) in a room whose ceiling is 2.7 m high. */
struct LowBoxTallRoom : test::HalfKnownRoomMap {
    void SetUp() override { map = test::halfSeenRoom(2.0, 2.7); }
};

TEST_F(LowBoxTallRoom, StopsOverTheHeadsRiseToTheBoxsTopLessHalfTheDrone) {
    // Under a 2 m box's top less robot_radius (1.7 m) nobody can be flown over; at its top
    // less half the drone (1.95 m) its underside is 10 cm over the bodies' 1.8 m.
    EXPECT_GT(stopsRaisedTo(*map, root, 2.0 - 0.05), 3);
}

TEST_F(LowBoxTallRoom, LessRoomOverTheHeadsThanTheLeastGapKeepsTheStopsAmongThem) {
    const std::string on = "true";
    const auto cfg = test::configFromText(test::editKey(
        daepText("over_heads_min_clearance", "0.051"), "daep", "fly_over_heads", &on));
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
        DaepPlanner planner(DaepParams::fromConfig(*cfg), GainParams::fromConfig(*cfg), seed);
        PlanningContext ctx = contextFor(*map, root);
        ctx.peopleFromCamera = true;
        const std::vector<PersonForecast> nobody;
        ctx.people = &nobody;
        const Plan plan = planner.plan(ctx);
        ASSERT_FALSE(plan.waypoints.empty()) << plan.reason;
        EXPECT_EQ(plan.reason.find("over heads"), std::string::npos) << plan.reason;
        for (const Waypoint& w : plan.waypoints)
            EXPECT_LE(w.pose.position.z(), 2.0 - 0.3 + 1e-9) << seed;
    }
}

/**
 * An 8 x 4 x 2.5 m box, known west of x = 4.4 and unknown east of x = 4.6, between them a
 * lintel from z = 1.6 m up across the whole width: the unknown is seen under it, from low.
 */
std::unique_ptr<mapping::ExplorationMap> roomBehindALintel() {
    auto map = test::makeMap(test::box(0, 0, 0, 8, 4, 2.5), 6.0);
    for (double y = 0.1; y < 4.0; y += 0.2)
        for (double z = 0.1; z < 2.7; z += 0.2) {  // the cells up to 2.6 m: room over heads
            const bool lintel = z > 1.6;
            const double from = lintel ? 4.5 : 4.59;  // the doorway itself is free
            map->insertPointCloud({from, y, z}, {Eigen::Vector3f(-100.f, float(y), float(z))});
            if (lintel)
                map->insertPointCloud({4.5, y, z}, {Eigen::Vector3f(4.5f, float(y), float(z))});
        }
    return map;
}

TEST(DaepOverHeads, AGoalWhoseViewIsUnderALintelIsNotRaisedOverTheHeads) {
    auto map = roomBehindALintel();
    const auto cfg = test::configFromText(daepText());
    GainEvaluator gain(GainParams::fromConfig(*cfg));  // the planner's, border boost and all
    const DaepParams params = DaepParams::fromConfig(*cfg);
    gain.setYawAngleBooster(params.borderBoost, params.borderDistance);
    const double overHeads = 1.8 + 0.05 + 0.2 + 0.05;
    int keptLow = 0;
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
        const auto [plan, asPlanned] = planRaisedAndNot(*map, {2.0, 2.0, 1.0}, seed, "auto", true);
        ASSERT_FALSE(plan.waypoints.empty()) << plan.reason;
        ASSERT_FALSE(asPlanned.waypoints.empty()) << asPlanned.reason;
        const Eigen::Vector3d goal = asPlanned.waypoints.back().pose.position;
        const Eigen::Vector3d up(goal.x(), goal.y(), overHeads);
        ASSERT_TRUE(map->isSegmentFree(up, up, 0.3));
        const Eigen::Vector3d& flown = plan.waypoints.back().pose.position;
        if (gain.bestYaw(*map, up).gain < 0.5 * asPlanned.gain) {
            // The goal where it was planned: the view it was chosen for.
            EXPECT_TRUE(flown.isApprox(goal, 1e-9)) << seed << ": " << flown.transpose();
            ++keptLow;
        } else {
            EXPECT_TRUE(flown.isApprox(up, 1e-9)) << seed << ": " << flown.transpose();
        }
    }
    EXPECT_GT(keptLow, 1);
}

TEST_F(TallRoom, WithGroundTruthPeopleOrNoRoomOverHeadsThePlanIsKept) {
    // Ground truth (auto is off), and a 2 m box under a 2.1 m ceiling: over the heads the
    // drone's ball would reach the ceiling.
    const auto lowMap = test::halfSeenRoom(2.0, 2.1);
    for (std::uint64_t seed = 1; seed <= 3; ++seed)
        for (const auto& [m, lift, fromCamera] :
             {std::tuple{map.get(), "auto", false}, std::tuple{lowMap.get(), "true", true}}) {
            const auto [plan, asPlanned] = planRaisedAndNot(*m, root, seed, lift, fromCamera);
            ASSERT_EQ(plan.waypoints.size(), asPlanned.waypoints.size());
            for (std::size_t k = 0; k < plan.waypoints.size(); ++k)
                EXPECT_TRUE(
                    plan.waypoints[k].pose.position.isApprox(asPlanned.waypoints[k].pose.position))
                    << seed;
        }
}

/** How a drone hovering at `root` evades someone 2.5 m east walking at it. */
struct EscapeFromAWalker {
    Eigen::Vector3d to = Eigen::Vector3d::Zero();  ///< where the one-move escape goes
    std::string reason;
    bool moveSafe = false;  ///< the escape move, by the planner's own check
    double hoverGap = 0.0;  ///< the clearance hovering there for 20 s after it
};

EscapeFromAWalker escapeFromAWalkerEast(const mapping::ExplorationMap& map,
                                        const Eigen::Vector3d& root, bool fromCamera) {
    DaepPlanner planner = makePlanner(3);
    PlanningContext ctx = contextFor(map, root, 0.0);
    ctx.peopleFromCamera = fromCamera;
    std::vector<PersonForecast> people{walker(0, {4.5, 2.0}, {-0.35, 0}, ctx.time)};
    ctx.people = &people;
    const std::optional<Plan> escape = planner.evasion(ctx, ctx.time + 3.0);
    EscapeFromAWalker out;
    if (!escape || escape->waypoints.size() != 1) {
        ADD_FAILURE() << "no one-move escape: " << (escape ? escape->reason : "none");
        return out;
    }
    out.to = escape->waypoints[0].pose.position;
    out.reason = escape->reason;
    out.moveSafe = planner.obstacles().isSafe(planner.timedMoves(ctx, *escape, 0)[0]);
    TimedSegment hover;
    hover.from = hover.to = out.to;
    hover.start = escape->waypoints[0].arrivalTime;
    hover.turnTime = 20.0;
    out.hoverGap = planner.obstacles().clearance(hover);
    return out;
}

TEST_F(LowBoxTallRoom, TheEscapeFromAWalkerIsStraightUpToTheBoxsTopLessHalfTheDrone) {
    // Up there the walker passes under the drone: the climb and the hover after it are safe.
    const EscapeFromAWalker escape = escapeFromAWalkerEast(*map, root, true);
    EXPECT_TRUE(escape.to.isApprox(Eigen::Vector3d(2.0, 2.0, 1.95))) << escape.reason;
    EXPECT_TRUE(escape.moveSafe) << escape.reason;
    EXPECT_GT(escape.hoverGap, 0.0) << escape.reason;
}

TEST_F(TallRoom, WithRoomOverHeadsTheEscapeFromAWalkerIsStraightUp) {
    // With people from the camera (who may have company it has not seen) the drone climbs
    // over their heads; with ground truth it moves aside as before.
    const EscapeFromAWalker up = escapeFromAWalkerEast(*map, root, true);
    EXPECT_TRUE(up.to.isApprox(Eigen::Vector3d(2.0, 2.0, 2.1))) << up.reason;
    EXPECT_TRUE(up.moveSafe) << up.reason;
    const EscapeFromAWalker aside = escapeFromAWalkerEast(*map, root, false);
    EXPECT_LT(aside.to.z(), 2.0) << aside.reason;
}

TEST_F(TallRoom, AStopOverTheHeadsNeedsNoLookAtTheWalkwaysBehind) {
    // A walker stood behind the drone (west), then was lost: with the stops kept low, the
    // drone first turns to look at that walkway; over the heads nobody from it can reach it.
    for (const std::string flag : {"false", "auto"}) {
        const std::unique_ptr<DaepPlanner> owned =
            guardedAfterAWalkerBehind(*map, root, flag, "fly_over_heads");
        DaepPlanner& planner = *owned;
        PlanningContext ctx = contextFor(*map, root);  // t = 12: the walkway unseen for 10 s
        ctx.peopleFromCamera = true;
        const std::vector<PersonForecast> nobody;
        ctx.people = &nobody;
        const Plan plan = planner.plan(ctx);
        ASSERT_FALSE(plan.waypoints.empty()) << plan.reason;
        const bool looked = plan.reason.rfind("look:", 0) == 0;
        EXPECT_EQ(looked, flag == "false") << plan.reason;
        if (!looked) {
            EXPECT_GE(plan.waypoints.front().pose.position.z(), planner.obstacles().clearedHeight())
                << plan.reason;
        }
    }
}

/**
 * The Exhibition corner: a 6 x 6 m room, all of it seen, and a person walking at 0.35 m/s
 * straight at a drone that stopped in its south-west corner.
 */
/** DAEP with the trap check on (trap_horizon_s = 5; off by default). */
DaepPlanner trapGuarded() {
    return makePlanner(3, "trap_horizon_s", "5");
}

struct CornerRoom : ::testing::Test {
    void SetUp() override { seeRoom(2.0, 2.1); }
    /** A box `top` m high in a room with its ceiling at `ceiling`, seen from the middle. */
    void seeRoom(double top, double ceiling) {
        map = test::makeMap(test::box(0, 0, 0, 6, 6, top), 10.0);
        walls = test::box(-0.1, -0.1, -0.1, 6.1, 6.1, ceiling);
        map->insertPointCloud(middle, test::roomScan(walls, middle, 0.5));
    }
    /** Someone 2.1 m (or `away` x sqrt 2) from `stop`, from the north-east, walking at it. */
    static std::vector<PersonForecast> walkerComingAt(const Eigen::Vector3d& stop, double t,
                                                      double away = 1.5) {
        const Eigen::Vector2d from = stop.head<2>() + Eigen::Vector2d(away, away);
        std::vector<PersonForecast> people{walker(0, from, {-0.25, -0.25}, t)};
        people[0].accelNoise = 1e-4;  // a steady walker: the prediction stays tight
        people[0].covariance.diagonal() << 1e-4, 1e-4, 1e-5, 1e-5;
        return people;
    }
    /**
     * The most clearance any escape from `at` keeps (flying there, then hovering until the
     * walker has passed), over the short moves the planner picks escapes from.
     */
    static double bestEscapeGap(const DaepPlanner& planner, const mapping::ExplorationMap& map,
                                const PlanningContext& ctx, const Eigen::Vector3d& at) {
        const double r = planner.params().robotRadius;
        const Aabb box = shrink(ctx.explorationBox, r);
        double best = -std::numeric_limits<double>::infinity();
        for (const double d : {0.4, 0.8, 1.2, 1.6})
            for (int k = 0; k < 16; ++k) {
                const double a = 2 * M_PI * k / 16;
                const FlatPose to{at + d * Eigen::Vector3d(std::cos(a), std::sin(a), 0),
                                  ctx.pose.yaw};
                if (!box.contains(to.position) || !map.isSegmentFree(at, to.position, r))
                    continue;
                const TimedSegment move = timedSegment(ctx.pose, to, ctx.time, 0.5, 1.0);
                TimedSegment hover;
                hover.from = hover.to = to.position;
                hover.start = move.end();
                hover.turnTime = ctx.time + 12.0 - move.end();
                best = std::max(best, std::min(planner.obstacles().clearance(move),
                                               planner.obstacles().clearance(hover)));
            }
        return best;
    }
    const Eigen::Vector3d middle{3.0, 3.0, 1.0};
    const Eigen::Vector3d corner{0.7, 0.7, 1.0};
    Aabb walls;
    std::unique_ptr<mapping::ExplorationMap> map;
};

TEST_F(CornerRoom, CorneredByAWalkerNoEscapeKeepsClearOfThem) {
    // The situation that ended in collisions: every escape from the corner runs along a wall,
    // within reach of the person coming in; in the open the same walker is easily escaped.
    for (const bool cornered : {true, false}) {
        DaepPlanner planner = trapGuarded();
        const Eigen::Vector3d at = cornered ? corner : middle;
        PlanningContext ctx = contextFor(*map, at, M_PI / 4);  // facing them
        const std::vector<PersonForecast> people = walkerComingAt(at, ctx.time);
        ctx.people = &people;
        ASSERT_TRUE(planner.evasion(ctx, ctx.time + 10).has_value()) << cornered;
        const double gap = bestEscapeGap(planner, *map, ctx, at);
        if (cornered) {
            EXPECT_LT(gap, 0.0);
        } else {
            EXPECT_GT(gap, 0.0);
        }
        EXPECT_EQ(planner.isTrap(ctx, at, ctx.time), cornered);
    }
}

TEST_F(CornerRoom, TheCornerIsATrapOnlyWhileSomeoneCanWalkUpToItInTime) {
    DaepPlanner planner = trapGuarded();
    PlanningContext ctx = contextFor(*map, middle);
    const auto trapWith = [&](DaepPlanner& p, std::vector<PersonForecast> people,
                              const Eigen::Vector3d& stop, double arrival) {
        ctx.people = &people;
        p.plan(ctx);
        return p.isTrap(ctx, stop, ctx.time + arrival);
    };
    const double t = ctx.time;
    EXPECT_FALSE(trapWith(planner, {}, corner, 5));
    // Standing in the far corner: 6.6 m away, more than trap_horizon_s at walking speed.
    EXPECT_FALSE(trapWith(planner, {walker(0, {5.4, 5.4}, {0, 0}, t)}, corner, 5));
    // Standing 2.1 m away: they could be at the drone in 3 s.
    const PersonForecast near = walker(0, {2.2, 2.2}, {0, 0}, t);
    EXPECT_TRUE(trapWith(planner, {near}, corner, 5));
    // Walking away, they are out of reach by the time the drone arrives.
    EXPECT_FALSE(trapWith(planner, {walker(0, {2.2, 2.2}, {0.3, 0.3}, t)}, corner, 15));
    // A wall alone is no trap: along it the drone gets out of their way.
    EXPECT_FALSE(trapWith(planner, {near}, {3.0, 0.7, 1.0}, 5)) << "south wall";
    // Switched off.
    DaepPlanner unguarded = makePlanner(3, "trap_horizon_s", "0");
    EXPECT_FALSE(trapWith(unguarded, {near}, corner, 5));
}

TEST_F(CornerRoom, APlanIntoTheCornerWhileSomeoneIsNearStopsShortOfIt) {
    DaepPlanner planner = trapGuarded();
    PlanningContext ctx = contextFor(*map, middle);
    const std::vector<PersonForecast> near{walker(0, {2.2, 2.2}, {0, 0}, ctx.time)};
    ctx.people = &near;
    planner.plan(ctx);
    Plan plan;
    plan.status = Plan::Status::Path;
    plan.waypoints.push_back({{{2.0, 3.5, 1.0}, 0.0}, ctx.time + 2.0});
    plan.waypoints.push_back({{{0.7, 3.0, 1.0}, 0.0}, ctx.time + 5.0});
    plan.waypoints.push_back({{corner, 0.0}, ctx.time + 10.0});
    const Plan cut = planner.cutBeforeTrap(ctx, plan);
    ASSERT_EQ(cut.waypoints.size(), 2u) << cut.reason;
    EXPECT_NE(cut.reason.find("cut before a trap"), std::string::npos) << cut.reason;
    // Every plan the planner hands out stops only where the drone can get away.
    for (int k = 0; k < 5; ++k) {
        const Plan made = planner.plan(ctx);
        for (const Waypoint& w : made.waypoints)
            EXPECT_FALSE(planner.isTrap(ctx, w.pose.position, w.arrivalTime)) << made.reason;
        ctx.time += 0.5;
    }
}

/** The Apartment's alcove: a walker's route ends in the corner the drone stands in. */
struct TallCornerRoom : CornerRoom {
    // The Apartment's heights: room over the heads, the drone flies up to 2.2 m.
    void SetUp() override { seeRoom(2.5, 3.05); }
};

TEST_F(TallCornerRoom, CorneredWithGroundTruthPeopleTheDroneClimbsOverTheWalker) {
    // Not cruising over the heads (people from ground truth), the drone still climbs over the
    // walker when no move on its own level keeps clear; in the open it moves aside.
    for (const bool cornered : {true, false}) {
        DaepPlanner planner = makePlanner(3);
        // At head height, as in the Apartment: a climb of 0.4 m leaves the box.
        const Eigen::Vector3d at = (cornered ? corner : middle) + Eigen::Vector3d(0, 0, 0.9);
        map->insertPointCloud(at, test::roomScan(walls, at, 0.5));
        PlanningContext ctx = contextFor(*map, at, M_PI / 4);
        ctx.peopleFromCamera = false;
        const std::vector<PersonForecast> people = walkerComingAt(at, ctx.time, 1.2);
        ctx.people = &people;
        const std::optional<Plan> escape = planner.evasion(ctx, ctx.time + 10);
        ASSERT_TRUE(escape.has_value()) << cornered;
        ASSERT_EQ(escape->waypoints.size(), 1u) << escape->reason;
        const Eigen::Vector3d to = escape->waypoints[0].pose.position;
        EXPECT_TRUE(planner.obstacles().isSafe(planner.timedMoves(ctx, *escape, 0)[0]))
            << escape->reason;
        if (cornered) {
            EXPECT_LT(bestEscapeGap(planner, *map, ctx, at), 0.0);
            EXPECT_TRUE(to.isApprox(Eigen::Vector3d(at.x(), at.y(), 2.1))) << escape->reason;
        } else {
            EXPECT_DOUBLE_EQ(to.z(), at.z()) << escape->reason;
        }
    }
}

/**
 * The Exhibition corner with people the camera missed: a queue walking past the corner left
 * their imprints in the map (cells hit after they were seen surely free) all around the drone.
 */
TEST_F(CornerRoom, WalledInByImprintsTheDroneEscapesThroughThem) {
    for (int k = 0; k < 6; ++k)
        map->insertPointCloud(middle, test::roomScan(walls, middle, 0.5));
    std::vector<Eigen::Vector3f> imprints;
    for (double z = 0.1; z < 2.0; z += 0.2)
        for (double u = 0.1; u < 1.2; u += 0.2) {
            imprints.emplace_back(1.1f, float(u), float(z));
            imprints.emplace_back(float(u), 1.1f, float(z));
        }
    for (int k = 0; k < 3; ++k)
        map->insertPointCloud(middle, imprints);
    ASSERT_TRUE(map->isOccupied({1.1, 0.5, 1.0}));
    ASSERT_TRUE(map->movedIn({1.1, 0.5, 1.0}));
    ASSERT_TRUE(map->movedIn({0.5, 1.1, 1.0}));

    const Eigen::Vector3d at(0.5, 0.5, 1.0);
    DaepPlanner planner = trapGuarded();
    const double r = planner.params().robotRadius;
    PlanningContext ctx = contextFor(*map, at, M_PI / 4);
    const std::vector<PersonForecast> people = walkerComingAt(at, ctx.time);
    ctx.people = &people;
    // No short move out of the corner is free of occupied cells: the drone used to wait there.
    for (const double d : {0.4, 0.8, 1.2, 1.6})
        for (int k = 0; k < 16; ++k) {
            const double a = 2 * M_PI * k / 16;
            const Eigen::Vector3d to = at + d * Eigen::Vector3d(std::cos(a), std::sin(a), 0);
            EXPECT_FALSE(map->isSegmentFree(at, to, r)) << d << " m at " << a;
        }
    const Plan plan = planner.plan(ctx);
    ASSERT_TRUE(plan.escape) << plan.reason;
    EXPECT_NE(plan.reason.find("through imprints"), std::string::npos) << plan.reason;
    const Eigen::Vector3d goal = plan.waypoints.back().pose.position;
    EXPECT_FALSE(map->isSegmentFree(at, goal, r)) << goal.transpose();
    EXPECT_TRUE(map->isSegmentFreeThroughImprints(at, goal, r)) << goal.transpose();

    // The same cells as a wall (occupied when first seen): the corner keeps the drone.
    const std::unique_ptr<mapping::ExplorationMap> walled =
        test::makeMap(test::box(0, 0, 0, 6, 6, 2), 10.0);
    for (int k = 0; k < 3; ++k)
        walled->insertPointCloud(middle, imprints);
    for (int k = 0; k < 5; ++k)
        walled->insertPointCloud(at, test::roomScan(walls, at, 0.5));
    ASSERT_TRUE(walled->isOccupied({1.1, 0.5, 1.0}));
    ASSERT_FALSE(walled->movedIn({1.1, 0.5, 1.0}));
    DaepPlanner cornered = trapGuarded();
    PlanningContext there = contextFor(*walled, at, M_PI / 4);
    there.people = &people;
    const Plan waited = cornered.plan(there);
    EXPECT_FALSE(waited.escape) << waited.reason;
    EXPECT_NE(waited.reason.find("no escape is free of static obstacles"), std::string::npos)
        << waited.reason;
}

}  // namespace
}  // namespace daep::planning
