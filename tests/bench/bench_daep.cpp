#include <benchmark/benchmark.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "../planning/PlanningTestUtil.h"
#include "BenchScenes.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/perception/PeopleTracker.h"
#include "daep/planning/DaepPlanner.h"
#include "daep/sim/DepthCamera.h"
#include "daep/world/People.h"
#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace {

/**
 * The dynamic Exhibition (22 people) after 30 s: the map holds a full turn of the 320 x 240
 * camera at three start positions, and every person has been tracked from ground truth at
 * 5 Hz for the last 2 s, as the mission does.
 */
struct BusyExhibition {
    daep::world::WorldSpec world;
    std::unique_ptr<daep::mapping::ExplorationMap> map;
    std::vector<daep::FlatPose> poses;
    std::vector<daep::perception::PersonForecast> people;
    double time = 30.0;

    BusyExhibition() {
        world = daep::world::loadWorldFile(DAEP_SOURCE_DIR "/share/daep/worlds/exhibition.yaml");
        daep::world::RayCaster caster(world);
        daep::world::PeopleSimulator walkers(world.people, daep::world::PeopleParams{});
        daep::perception::PeopleTracker tracker(daep::perception::TrackerParams{});
        walkers.advance(time - 2.0);
        for (int k = 0; k <= 10; ++k) {
            std::vector<daep::perception::PersonMeasurement> m;
            for (std::size_t i = 0; i < walkers.states().size(); ++i)
                m.push_back({static_cast<int>(i), walkers.states()[i].position,
                             Eigen::Matrix2d::Identity() * 4e-4});
            tracker.update(time - 2.0 + 0.2 * k, m);
            if (k < 10)
                walkers.advance(0.2);
        }
        people = tracker.forecasts();
        caster.setPeople(walkers.states(), daep::world::PeopleParams{}.bodySize);
        map = daep::bench::lookAroundAtStarts(world, caster, 3, poses);
    }
};

const BusyExhibition& exhibition() {
    static const BusyExhibition scene;
    return scene;
}

using daep::bench::quantile;

/**
 * One DAEP planning call among 22 tracked people (time-aware local RRT*, swept safety checks,
 * dynamic gain, frequency-map score; the global planner when the local gain runs out). Each
 * repetition is one call: the aggregates are the median and p95 over 200 calls. Arg 0: the
 * planner planned twice before from the pose (warm cache and kept branch, as in a mission);
 * arg 1: a fresh planner.
 */
void BM_DaepPlan(benchmark::State& state) {
    const BusyExhibition& scene = exhibition();
    const auto cfg = daep::planning::test::configFromText(daep::planning::test::defaultsText());
    const auto params = daep::planning::DaepParams::fromConfig(*cfg);
    const auto gain = daep::planning::GainParams::fromConfig(*cfg);
    static std::uint64_t seed = 0;
    double global = 0.0, rayCasts = 0.0, moved = 0.0;
    for (auto _ : state) {
        state.PauseTiming();
        ++seed;
        daep::planning::DaepPlanner planner(params, gain, seed);
        daep::planning::PlanningContext ctx;
        ctx.time = scene.time;
        ctx.pose = scene.poses[seed % scene.poses.size()];
        ctx.map = scene.map.get();
        ctx.explorationBox = scene.world.explorationBox;
        ctx.people = &scene.people;
        for (int warm = 0; warm < (state.range(0) == 0 ? 2 : 0); ++warm)
            planner.plan(ctx);
        state.ResumeTiming();
        const daep::planning::Plan plan = planner.plan(ctx);
        benchmark::DoNotOptimize(plan);
        global += planner.stats().global ? 1.0 : 0.0;
        rayCasts += planner.stats().rayCasts;
        moved += plan.waypoints.empty() ? 0.0 : 1.0;
    }
    state.counters["global"] = benchmark::Counter(global, benchmark::Counter::kAvgIterations);
    state.counters["ray_casts"] = benchmark::Counter(rayCasts, benchmark::Counter::kAvgIterations);
    state.counters["with_path"] = benchmark::Counter(moved, benchmark::Counter::kAvgIterations);
    state.counters["people"] = static_cast<double>(scene.people.size());
}
BENCHMARK(BM_DaepPlan)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Repetitions(200)
    ->ReportAggregatesOnly(true)
    ->ComputeStatistics("p95", [](const std::vector<double>& v) { return quantile(v, 0.95); })
    ->ComputeStatistics("max", [](const std::vector<double>& v) { return quantile(v, 1.0); });

}  // namespace
