// The planning deadline ([planning] deadline_s), the same contract for every planner.
#include <gtest/gtest.h>

#include "PlanningTestUtil.h"
#include "daep/perception/PersonTrack.h"
#include "daep/planning/PlannerRegistry.h"

namespace daep::planning {
namespace {

struct DeadlineRoom : test::HalfKnownRoomMap {
    std::unique_ptr<ExplorationPlanner> make(const std::string& name) const {
        return createPlanner(name, *test::configFromText(test::defaultsText()), 5);
    }
    PlanningContext context() const {
        PlanningContext ctx = test::contextFor(*map, root);
        ctx.people = &nobody;
        return ctx;
    }
    const std::vector<perception::PersonForecast> nobody{};
};

TEST_F(DeadlineRoom, UnsetItNeverPasses) {
    EXPECT_FALSE(PlanningDeadline{}.passed());
    EXPECT_TRUE(PlanningDeadline::in(0.0).passed());
    EXPECT_FALSE(PlanningDeadline::in(3600.0).passed());
}

TEST_F(DeadlineRoom, APassedDeadlineStopsTheTreesButNeverEndsTheMission) {
    for (const std::string& name : plannerNames()) {
        SCOPED_TRACE(name);
        // Without a deadline the planner grows its trees and flies to the unknown half.
        const Plan free = make(name)->plan(context());
        ASSERT_EQ(free.status, Plan::Status::Path) << free.reason;
        EXPECT_FALSE(free.waypoints.empty()) << free.reason;
        EXPECT_FALSE(free.tree.empty()) << free.reason;
        // With the deadline gone before it starts, nothing grows; a planner that counts
        // fruitless plans towards its end (AEP's global failures, DEP's idle plans) does not
        // count these, however many come in a row.
        const auto planner = make(name);
        PlanningContext late = context();
        for (int call = 0; call < 40; ++call) {
            late.deadline = PlanningDeadline::in(0.0);
            const Plan plan = planner->plan(late);
            ASSERT_NE(plan.status, Plan::Status::Finished) << call << ": " << plan.reason;
            ASSERT_TRUE(plan.wellFormed()) << call << ": " << plan.reason;
            EXPECT_LE(plan.tree.size(), free.tree.size()) << plan.reason;
            for (const Waypoint& w : plan.waypoints)  // a turn on the spot at most
                EXPECT_LT((w.pose.position - root).norm(), 1e-9) << plan.reason;
            late.time += 0.5;
        }
        // Once plans have time again it goes on exploring.
        late.deadline = PlanningDeadline{};
        const Plan again = planner->plan(late);
        ASSERT_EQ(again.status, Plan::Status::Path) << again.reason;
        EXPECT_FALSE(again.waypoints.empty()) << again.reason;
    }
}

}  // namespace
}  // namespace daep::planning
