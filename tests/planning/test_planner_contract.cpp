// One contract for every registered planner (the role of OMPL's tests/base/PlannerTest.h),
// and a fifth planner, written here over the same parts and registered in one line, that
// keeps it too.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "PlanningTestUtil.h"
#include "daep/perception/PersonTrack.h"
#include "daep/planning/FlightModel.h"
#include "daep/planning/FlightSpace.h"
#include "daep/planning/GainEvaluator.h"
#include "daep/planning/PlannerRegistry.h"
#include "daep/planning/TreeParts.h"

namespace daep::planning {
namespace {

using perception::PersonForecast;

/**
 * The plainest next-best-view planner: views sampled in the box, kept where a straight flight
 * in known free space reaches them, the best gain discounted by distance flown to. It ignores
 * people. Finished after three calls in a row that found no view with gain.
 */
class GreedyNbv : public ExplorationPlanner {
public:
    GreedyNbv(const GainParams& gain, std::uint64_t seed) : gain_(gain), rng_(seed) {}
    std::string name() const override { return "greedy_nbv"; }

    Plan plan(const PlanningContext& context) override {
        Plan plan;
        plan.status = Plan::Status::NoPath;
        if (context.deadline.passed()) {
            plan.reason = "deadline: no view sampled";
            return plan;
        }
        const Aabb box = shrink(context.explorationBox, kRobotRadius);
        const Eigen::Vector3d& from = context.pose.position;
        pathSpace_.bind(*context.map, kRobotRadius, 0.05, false);
        double bestValue = 0.0;
        for (int k = 0; k < kSamples; ++k) {
            const Eigen::Vector3d to = sampleInBox(box, rng_);
            if (!pathSpace_.staticValid(from, to, false))
                continue;
            plan.tree.push_back({from, to});
            const YawGain view = gain_.bestYaw(*context.map, to);
            const double value = view.gain * std::exp(-kLambda * (to - from).norm());
            if (view.gain > kMinGain && value > bestValue) {
                bestValue = value;
                plan.waypoints = {{{to, view.yaw}, 0.0}};
                plan.gain = view.gain;
            }
        }
        idleCalls_ = plan.waypoints.empty() ? idleCalls_ + 1 : 0;
        if (plan.waypoints.empty()) {
            plan.status = idleCalls_ >= 3 ? Plan::Status::Finished : Plan::Status::NoPath;
            plan.reason = "no view with gain";
            return plan;
        }
        const FlightModel flight{context.motion, false};
        plan.waypoints = flight.flown(context.pose, context.time, plan.waypoints);
        plan.status = Plan::Status::Path;
        plan.score = bestValue;
        plan.reason = "best view";
        return plan;
    }

private:
    static constexpr double kRobotRadius = 0.3;
    static constexpr double kLambda = 0.5;
    static constexpr double kMinGain = 0.5;  ///< m^3
    static constexpr int kSamples = 40;
    PathSpaceValidator pathSpace_;
    GainEvaluator gain_;
    std::mt19937_64 rng_;
    int idleCalls_ = 0;
};

const bool kGreedyRegistered = registerPlanner(
    "greedy_nbv", [](const mrpt::config::CConfigFileBase& config, std::uint64_t seed) {
        return std::make_unique<GreedyNbv>(GainParams::fromConfig(config), seed);
    });

PersonForecast person(Eigen::Vector2d at, Eigen::Vector2d velocity, double t0) {
    PersonForecast f;
    f.id = 0;
    f.time = t0;
    f.state << at, velocity;
    f.covariance.diagonal() << 1e-4, 1e-4, 1e-3, 1e-3;
    f.accelNoise = 0.02;
    return f;
}

/** The drone's position along a plan flown as the simulator flies it (turn, then fly). */
template <typename Visit>
void alongPlan(const PlanningContext& c, const Plan& plan, double step, Visit&& visit) {
    FlatPose at = c.pose;
    double t = c.time;
    for (const Waypoint& w : plan.waypoints) {
        const double turn = std::abs(wrapAngle(w.pose.yaw - at.yaw)) / c.motion.yawRate;
        const double fly = (w.pose.position - at.position).norm() / c.motion.speed;
        for (double s = 0.0; s < turn + fly; s += step) {
            const double f = s <= turn ? 0.0 : (s - turn) / fly;
            visit(t + s, Eigen::Vector3d(at.position + f * (w.pose.position - at.position)));
        }
        t += turn + fly;
        at = w.pose;
        visit(t, at.position);
    }
}

struct PlannerContract : test::HalfKnownRoomMap {
    void SetUp() override {
        test::HalfKnownRoomMap::SetUp();
        // A pillar in the seen half, between the drone and the unknown one.
        std::vector<Eigen::Vector3f> pillar;
        for (double y = 1.6; y <= 2.4; y += 0.1)
            for (double z = 0.1; z < 2.0; z += 0.1)
                pillar.push_back(Eigen::Vector3f(3.3f, float(y), float(z)));
        map->insertPointCloud(root, pillar);
    }
    std::unique_ptr<ExplorationPlanner> make(const std::string& name, std::uint64_t seed) const {
        return createPlanner(name, *test::configFromText(test::defaultsText()), seed);
    }
    PlanningContext context(const std::vector<PersonForecast>& people) const {
        PlanningContext c = test::contextFor(*map, root);
        c.people = &people;
        return c;
    }
    /** Whether the path's flight keeps the drone's ball off every occupied cell. */
    bool clearOfGeometry(const PlanningContext& c, const Plan& plan) const {
        Eigen::Vector3d from = c.pose.position;
        for (const Waypoint& w : plan.waypoints) {
            if (!map->isSegmentFreeOrUnknown(from, w.pose.position, kDroneHalfWidth))
                return false;
            from = w.pose.position;
        }
        return true;
    }
    static constexpr double kDroneHalfWidth = 0.2;
    const std::vector<PersonForecast> nobody{};
};

TEST_F(PlannerContract, TheFixtureIsRegisteredBesideTheBuiltInOnes) {
    ASSERT_TRUE(kGreedyRegistered);
    const std::vector<std::string> names = plannerNames();
    for (const char* name : {"aep", "daep", "dep", "greedy_nbv", "rhnbvp"})
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
    EXPECT_THROW(registerPlanner("daep", [](const auto&, std::uint64_t) { return nullptr; }),
                 std::logic_error);
}

TEST_F(PlannerContract, EveryPlannerFliesTowardsTheUnknownWithAWellFormedPlan) {
    for (const std::string& name : plannerNames()) {
        SCOPED_TRACE(name);
        const auto planner = make(name, 3);
        EXPECT_EQ(planner->name(), name);
        const Plan plan = planner->plan(context(nobody));
        ASSERT_TRUE(plan.wellFormed()) << plan.reason;
        ASSERT_EQ(plan.status, Plan::Status::Path) << plan.reason;
        double previous = 12.0;
        for (const Waypoint& w : plan.waypoints) {
            EXPECT_TRUE(map->explorationBox().contains(w.pose.position)) << plan.reason;
            EXPECT_GE(w.arrivalTime, previous) << plan.reason;
            previous = w.arrivalTime;
        }
        EXPECT_GT(plan.gain, 0.0) << plan.reason;
    }
}

TEST_F(PlannerContract, EveryPlannerIsDeterministicForASeed) {
    for (const std::string& name : plannerNames()) {
        SCOPED_TRACE(name);
        const auto a = make(name, 11), b = make(name, 11);
        PlanningContext c = context(nobody);
        for (int call = 0; call < 3; ++call) {
            const Plan pa = a->plan(c), pb = b->plan(c);
            ASSERT_EQ(pa.status, pb.status) << call;
            ASSERT_EQ(pa.reason, pb.reason) << call;
            ASSERT_EQ(pa.waypoints.size(), pb.waypoints.size()) << call;
            for (std::size_t i = 0; i < pa.waypoints.size(); ++i) {
                EXPECT_EQ(pa.waypoints[i].pose.position, pb.waypoints[i].pose.position) << call;
                EXPECT_EQ(pa.waypoints[i].pose.yaw, pb.waypoints[i].pose.yaw) << call;
            }
            c.time += 1.0;
        }
    }
}

TEST_F(PlannerContract, NoPlannerFliesThroughGeometry) {
    for (const std::string& name : plannerNames()) {
        SCOPED_TRACE(name);
        for (std::uint64_t seed = 1; seed <= 5; ++seed) {
            const auto planner = make(name, seed);
            PlanningContext c = context(nobody);
            for (int call = 0; call < 4; ++call) {
                const Plan plan = planner->plan(c);
                ASSERT_TRUE(plan.wellFormed()) << seed << ": " << plan.reason;
                EXPECT_TRUE(clearOfGeometry(c, plan)) << seed << ": " << plan.reason;
                c.time += 1.0;
            }
        }
    }
}

TEST_F(PlannerContract, APeopleAwarePlannerNeverFliesThroughAPredictedPerson) {
    const Eigen::Vector2d keepOut(0.5 + kDroneHalfWidth, 0.5 + kDroneHalfWidth);
    int checked = 0;
    for (const std::string& name : plannerNames()) {
        if (!make(name, 1)->usesPeople())
            continue;
        SCOPED_TRACE(name);
        ++checked;
        for (std::uint64_t seed = 1; seed <= 5; ++seed) {
            // One person standing south-east of the drone, where its first views lie without
            // people, one walking west past it on the north side.
            PlanningContext c = context(nobody);
            const std::vector<PersonForecast> people{person({2.8, 1.0}, {0.0, 0.0}, c.time),
                                                     person({3.6, 2.9}, {-0.35, 0.0}, c.time)};
            c.people = &people;
            const auto planner = make(name, seed);
            const Plan plan = planner->plan(c);
            ASSERT_TRUE(plan.wellFormed()) << seed << ": " << plan.reason;
            alongPlan(c, plan, 0.05, [&](double t, const Eigen::Vector3d& p) {
                if (t > c.time + 10.0)  // the prediction horizon: beyond, plans are re-made
                    return;
                for (const PersonForecast& f : people) {
                    const Eigen::Vector2d gap = (f.at(t).mean - p.head<2>()).cwiseAbs();
                    EXPECT_FALSE(gap.x() < keepOut.x() && gap.y() < keepOut.y())
                        << seed << ": at t = " << t << " the drone at " << p.transpose()
                        << " meets the person at " << f.at(t).mean.transpose() << " ("
                        << plan.reason << ")";
                }
            });
        }
    }
    EXPECT_GE(checked, 1);
}

TEST_F(PlannerContract, EveryPlannerFinishesInARoomWithNothingLeftToSee) {
    auto seen = test::makeMap(test::box(0, 0, 0, 8, 4, 2), 6.0);
    const Eigen::Vector3d middle(4.0, 2.0, 1.0);
    seen->insertPointCloud(middle,
                           test::roomScan(test::box(-0.1, -0.1, -0.1, 8.1, 4.1, 2.1), middle, 0.5));
    for (const std::string& name : plannerNames()) {
        SCOPED_TRACE(name);
        const auto planner = make(name, 2);
        PlanningContext c = test::contextFor(*seen, middle);
        c.people = &nobody;
        Plan plan;
        for (int call = 0; call < 30 && plan.status != Plan::Status::Finished; ++call) {
            plan = planner->plan(c);
            ASSERT_TRUE(plan.wellFormed()) << call << ": " << plan.reason;
            c.time += 1.0;
        }
        EXPECT_EQ(plan.status, Plan::Status::Finished) << plan.reason;
    }
}

}  // namespace
}  // namespace daep::planning
