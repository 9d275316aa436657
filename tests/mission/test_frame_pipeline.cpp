// The one frame pipeline: the planner driver's people-aware plan records, and the simulator
// as an open-loop frame source.
#include <gtest/gtest.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "FrameStep.h"
#include "MissionSetup.h"
#include "PlannerDriver.h"
#include "SimulatorSource.h"
#include "StageClock.h"
#include "TestFiles.h"
#include "daep/eval/RunRecorder.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/PeopleInput.h"
#include "daep/mission/RawlogMission.h"
#include "daep/planning/PlannerRegistry.h"

namespace {

namespace fs = std::filesystem;
using namespace daep;
using namespace daep::mission;

const std::string kTinyRoom = std::string(DAEP_SOURCE_DIR) + "/tests/e2e/data/tiny_room.ini";

fs::path freshDir(const std::string& name) {
    return daep::test::freshDir("daep_test_pipeline_", name);
}

using daep::test::lines;

FlatPose at(double x, double y, double z) {
    FlatPose p;
    p.position = {x, y, z};
    return p;
}

/**
 * DAEP itself, but its plan is the one given: a straight flight along y = 0 from x = 0 to 4.
 * Whether the plan is safe is DAEP's own verdict (keepFlying).
 */
class GivenPathThroughDaep : public planning::ExplorationPlanner {
public:
    explicit GivenPathThroughDaep(const mrpt::config::CConfigFileBase& config)
        : daep_(planning::createPlanner("daep", config, 1)) {}
    std::string name() const override { return "given"; }
    bool usesPeople() const override { return true; }
    planning::Plan plan(const planning::PlanningContext& context) override {
        planning::Plan p;
        p.status = planning::Plan::Status::Path;
        for (const double x : {2.0, 4.0}) {
            planning::Waypoint w;
            w.pose = at(x, 0.0, 1.0);
            w.arrivalTime = context.time + x / context.motion.speed;
            p.waypoints.push_back(w);
        }
        p.gain = 1.0;
        return p;
    }
    bool keepFlying(const planning::PlanningContext& context, const planning::Plan& plan,
                    std::size_t next) override {
        return daep_->keepFlying(context, plan, next);
    }

private:
    std::unique_ptr<planning::ExplorationPlanner> daep_;
};

/** The `safe` column of plans.csv for the given path, with one person standing at `person`. */
std::string safeWithPersonAt(const Eigen::Vector2d& person, const std::string& name) {
    const auto config = ExperimentConfig::fromFile(kTinyRoom);
    Aabb box;
    box.min = {-6, -6, 0};
    box.max = {6, 6, 3};
    mapping::ExplorationMap map(mapping::MapParams{}, box);
    PeopleInput people(PeopleInputParams::fromConfig(config.config()), 1);
    const fs::path dir = freshDir(name);
    eval::RunRecorder recorder(dir.string(), eval::PlansFormat::Replay);
    StageClock stages;
    PlannerDriver::Setup setup;
    setup.map = &map;
    setup.explorationBox = box;
    setup.people = &people;
    setup.recorder = &recorder;
    setup.stages = &stages;
    PlannerDriver driver(std::make_unique<GivenPathThroughDaep>(config.config()), setup);

    world::PersonState standing;
    standing.position = person;
    Frame frame;  // no depth image: people from their true positions only
    frame.truePeople = std::vector<world::PersonState>{standing};
    for (int k = 0; k <= 5; ++k) {
        frame.time = 0.2 * k;
        people.update(frame, map, {1.0, 1.0, 1.8}, nullptr, "test frames");
    }
    EXPECT_EQ(people.forecasts().size(), 1u);
    driver.planReplay(frame.time, at(0.0, 0.0, 1.0));
    const auto rows = lines(dir / "plans.csv");
    EXPECT_EQ(rows.size(), 2u);
    const std::string row = rows.back();
    const auto comma = row.rfind(',', row.rfind(',') - 1);
    return row.substr(comma + 1, row.rfind(',') - comma - 1);
}

/** On recorded data the planner sees the tracked people, and plans.csv says so. */
TEST(PlannerDriver, AReplayedPlanThroughAWalkerIsUnsafeAndAroundItSafe) {
    EXPECT_EQ(safeWithPersonAt({2.0, 0.0}, "through"), "0");
    EXPECT_EQ(safeWithPersonAt({2.0, 4.0}, "beside"), "1");
}

/** The planner is told what the people source sees and how far: the blind guard needs both. */
TEST(PlannerDriver, AContextCarriesThePeopleSourcesReachForAPlannerThatUsesPeople) {
    for (const std::string source : {"ground_truth", "sensed", "detected"}) {
        const auto config = ExperimentConfig::fromFile(
            kTinyRoom, {"tracking.people_source=" + source, "tracking.sensed_range=7.5",
                        "detector.max_range=4.5"});
        Aabb box;
        box.min = {-6, -6, 0};
        box.max = {6, 6, 3};
        mapping::ExplorationMap map(mapping::MapParams{}, box);
        PeopleInput people(PeopleInputParams::fromConfig(config.config()), 1);
        PlannerDriver::Setup setup;
        setup.map = &map;
        setup.people = &people;
        PlannerDriver driver(std::make_unique<GivenPathThroughDaep>(config.config()), setup);
        const planning::PlanningContext ctx = driver.context(0.0, at(0.0, 0.0, 1.0));
        EXPECT_EQ(ctx.people, &people.forecasts()) << source;
        EXPECT_EQ(ctx.peopleFromCamera, source != "ground_truth") << source;
        const double range = source == "sensed"     ? 7.5
                             : source == "detected" ? 4.5
                                                    : std::numeric_limits<double>::infinity();
        EXPECT_EQ(ctx.peopleRange, range) << source;
    }
}

/** The simulator is a frame source like any other: a frame every camera period, in order. */
TEST(SimulatorSource, AsAFrameSourceItGivesAFrameEveryCameraPeriod) {
    const auto config = ExperimentConfig::fromFile(kTinyRoom);
    const Settings settings = loadSettings(config);
    StageClock stages;
    SimulatorSource sim(loadWorld(settings, config.source()), config.config(), 0, settings.climb,
                        settings.seed, &stages);
    const Frame first = sim.takeFirstFrame();  // a copy: the source reuses its frame
    EXPECT_EQ(first.time, 0.0);
    ASSERT_TRUE(first.truePeople);
    EXPECT_EQ(first.truePeople->size(), 1u);  // the tiny room's walker
    const FlatPose start = first.robot;
    Frame f;
    for (int k = 1; k <= 10; ++k) {
        ASSERT_TRUE(sim.next(f));
        EXPECT_NEAR(f.time, k * sim.framePeriod(), 1e-9);
        EXPECT_EQ(f.robot.position, start.position);  // no goal: it hovers
        ASSERT_TRUE(f.depth);
        EXPECT_EQ(f.depth->rangeImage.cols(), 160);
    }
    // The walker walks.
    EXPECT_GT((f.truePeople->front().position - first.truePeople->front().position).norm(), 0.5);
    // Given a goal, the drone flies there frame by frame.
    sim.drone().setGoal(at(start.position.x(), start.position.y(), start.position.z() + 0.5));
    for (int k = 0; k < 10; ++k)
        sim.next(f);
    EXPECT_NEAR(f.robot.position.z(), start.position.z() + 0.5, 1e-9);
}

}  // namespace

namespace {

/** The simulator, hovering, for `frames` frames: an open-loop source like a live camera. */
class HoveringSimulator : public FrameSource {
public:
    HoveringSimulator(const ExperimentConfig& config, int frames) : left_(frames) {
        const Settings settings = loadSettings(config);
        sim_ =
            std::make_unique<SimulatorSource>(loadWorld(settings, config.source()), config.config(),
                                              0, settings.climb, settings.seed, &stages_);
    }
    bool next(Frame& frame) override {
        if (left_-- <= 0)
            return false;
        return sim_->next(frame);
    }
    std::string name() const override { return "hovering simulator"; }

private:
    StageClock stages_;
    std::unique_ptr<SimulatorSource> sim_;
    int left_;
};

/** Any open-loop source feeds the loop a rawlog feeds: people, map, plans, records. */
TEST(OpenLoopMission, AnyFrameSourceFeedsTheLoopOfARawlog) {
    const auto config = ExperimentConfig::fromFile(
        kTinyRoom, {"experiment.planner=daep", "rawlog.world=tiny_room.yaml",
                    "rawlog.plan_every_s=1", "output.scene=false"});
    const fs::path out = freshDir("openloop");
    RawlogMission mission(config, std::make_unique<HoveringSimulator>(config, 20), out.string(),
                          nullptr);
    const auto s = mission.run();
    EXPECT_EQ(mission.frames(), 20u);
    EXPECT_EQ(s.endReason.kind, eval::EndReason::Kind::EndOfFrames);
    EXPECT_EQ(s.iterations, 4);  // frames at t = 0 .. 3.8 s, plans at 0, 1, 2 and 3 s
    EXPECT_GT(mission.map().knownCellsInBox(), 1000u);
    // Ground-truth people come with the simulator's frames: the walker is tracked.
    const auto people = lines(out / "people.csv");
    EXPECT_EQ(people.size(), 21u);  // header + one track at every frame
    EXPECT_EQ(lines(out / "trajectory.csv").size(), 21u);
}

}  // namespace
