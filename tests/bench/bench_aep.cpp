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
#include "daep/planning/AepPlanner.h"
#include "daep/sim/DepthCamera.h"
#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace {

/**
 * Cafe, partly explored by the real simulator pieces: at three of the world's start positions
 * (1 m up) the depth camera (320 x 240) turns a full circle in 20 degree steps and every frame
 * is integrated into the exploration map, as in the mission's take-off.
 */
struct PartlyExploredCafe {
    daep::world::WorldSpec world;
    std::unique_ptr<daep::mapping::ExplorationMap> map;
    std::vector<daep::FlatPose> poses;

    PartlyExploredCafe() {
        world = daep::world::loadWorldFile(DAEP_SOURCE_DIR "/share/daep/worlds/cafe.yaml");
        const daep::world::RayCaster caster(world);
        map = daep::bench::lookAroundAtStarts(world, caster, 3, poses);
    }
};

const PartlyExploredCafe& cafe() {
    static const PartlyExploredCafe scene;
    return scene;
}

using daep::bench::quantile;

/**
 * One AEP local planning call (cache refresh, branch reuse, RRT* growth with cubature or GP
 * gain); each repetition is one call, so the aggregates are the median and p95 over 200 calls.
 * Arg 0: the planner has already planned twice from the pose (warm gain cache and kept branch,
 * as in a mission); arg 1: a fresh planner (cold cache, every node ray cast). Counters: share of
 * calls that fell back to the global planner.
 */
void BM_AepLocalPlan(benchmark::State& state) {
    const PartlyExploredCafe& scene = cafe();
    const auto cfg = daep::planning::test::configFromText(daep::planning::test::defaultsText());
    const auto params = daep::planning::AepParams::fromConfig(*cfg);
    const auto gain = daep::planning::GainParams::fromConfig(*cfg);
    static std::uint64_t seed = 0;
    double global = 0.0;
    double rayCasts = 0.0;
    for (auto _ : state) {
        state.PauseTiming();
        ++seed;
        daep::planning::AepPlanner planner(params, gain, seed);
        daep::planning::PlanningContext ctx;
        ctx.pose = scene.poses[seed % scene.poses.size()];
        ctx.map = scene.map.get();
        ctx.explorationBox = scene.world.explorationBox;
        for (int warm = 0; warm < (state.range(0) == 0 ? 2 : 0); ++warm)
            planner.plan(ctx);
        state.ResumeTiming();
        benchmark::DoNotOptimize(planner.plan(ctx));
        global += planner.stats().global ? 1.0 : 0.0;
        rayCasts += planner.stats().rayCasts;
    }
    state.counters["global"] = benchmark::Counter(global, benchmark::Counter::kAvgIterations);
    state.counters["ray_casts"] = benchmark::Counter(rayCasts, benchmark::Counter::kAvgIterations);
    state.counters["coverage_%"] = 100.0 * scene.map->coverage();
}
BENCHMARK(BM_AepLocalPlan)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Repetitions(200)
    ->ReportAggregatesOnly(true)
    ->ComputeStatistics("p95", [](const std::vector<double>& v) { return quantile(v, 0.95); })
    ->ComputeStatistics("max", [](const std::vector<double>& v) { return quantile(v, 1.0); });

}  // namespace
