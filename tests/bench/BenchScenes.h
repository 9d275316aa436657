#pragma once

#include <benchmark/benchmark.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "../planning/PlanningTestUtil.h"
#include "BenchParams.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/perception/PersonTrack.h"
#include "daep/planning/GainEvaluator.h"
#include "daep/planning/Planner.h"
#include "daep/sim/DepthCamera.h"
#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace daep::bench {

/**
 * The world's map after the mission's take-off at its first `starts` start positions: 1 m up,
 * the 320 x 240 camera turns a full circle in 20 degree steps and every frame is integrated.
 * Returns the map; `poses` gets the pose at each start.
 */
inline std::unique_ptr<mapping::ExplorationMap> lookAroundAtStarts(const world::WorldSpec& world,
                                                                   const world::RayCaster& caster,
                                                                   std::size_t starts,
                                                                   std::vector<FlatPose>& poses) {
    const sim::DepthCamera camera(benchCamera(320, 240));
    auto map = std::make_unique<mapping::ExplorationMap>(benchMap(), world.explorationBox);
    std::mt19937_64 rng(1);
    mrpt::obs::CObservation3DRangeScan obs;
    for (std::size_t s = 0; s < std::min(starts, world.starts.size()); ++s) {
        FlatPose pose{world.starts[s] + Eigen::Vector3d(0, 0, 1.0), 0.0};
        for (int step = 0; step < 18; ++step) {
            pose.yaw = wrapAngle(step * M_PI / 9.0);
            camera.render(caster, pose, 0.0, rng, obs);
            map->insertObservation(obs, pose);
        }
        poses.push_back(pose);
    }
    return map;
}

/** The q-quantile (0..1) of the values, nearest rank: for p95 and max aggregates. */
inline double quantile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    return v[static_cast<std::size_t>(std::lround(q * static_cast<double>(v.size() - 1)))];
}

/** Where plan-call benchmarks plan from: a map, poses to plan at, and the people tracked. */
struct PlanScene {
    world::WorldSpec world;
    std::unique_ptr<mapping::ExplorationMap> map;
    std::vector<FlatPose> poses;
    std::vector<perception::PersonForecast> people;
    double time = 0.0;
};

/**
 * One planning call per repetition (so the aggregates are over calls), by a planner of type
 * PlannerT built from the defaults files with a new seed each time. Arg 0: the planner planned
 * twice before from the pose (warm cache and kept branch, as in a mission); arg 1: a fresh
 * planner. Counters: share of calls that went global, ray casts, share that gave a path.
 */
template <class PlannerT, class ParamsT>
void benchPlanCalls(benchmark::State& state, const PlanScene& scene) {
    const auto cfg = planning::test::configFromText(planning::test::defaultsText());
    const auto params = ParamsT::fromConfig(*cfg);
    const auto gain = planning::GainParams::fromConfig(*cfg);
    static std::uint64_t seed = 0;
    double global = 0.0, rayCasts = 0.0, moved = 0.0;
    for (auto _ : state) {
        state.PauseTiming();
        ++seed;
        PlannerT planner(params, gain, seed);
        planning::PlanningContext ctx;
        ctx.time = scene.time;
        ctx.pose = scene.poses[seed % scene.poses.size()];
        ctx.map = scene.map.get();
        ctx.explorationBox = scene.world.explorationBox;
        ctx.people = scene.people.empty() ? nullptr : &scene.people;
        for (int warm = 0; warm < (state.range(0) == 0 ? 2 : 0); ++warm)
            planner.plan(ctx);
        state.ResumeTiming();
        const planning::Plan plan = planner.plan(ctx);
        benchmark::DoNotOptimize(plan);
        global += planner.stats().global ? 1.0 : 0.0;
        rayCasts += planner.stats().rayCasts;
        moved += plan.waypoints.empty() ? 0.0 : 1.0;
    }
    using benchmark::Counter;
    state.counters["global"] = Counter(global, Counter::kAvgIterations);
    state.counters["ray_casts"] = Counter(rayCasts, Counter::kAvgIterations);
    state.counters["with_path"] = Counter(moved, Counter::kAvgIterations);
    state.counters["coverage_%"] = 100.0 * scene.map->coverage();
    state.counters["people"] = static_cast<double>(scene.people.size());
}

/** 200 single-call repetitions, reported as mean, median, p95 and max. */
inline void asPlanCalls(benchmark::internal::Benchmark* b) {
    b->Arg(0)
        ->Arg(1)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->Repetitions(200)
        ->ReportAggregatesOnly(true)
        ->ComputeStatistics("p95", [](const std::vector<double>& v) { return quantile(v, 0.95); })
        ->ComputeStatistics("max", [](const std::vector<double>& v) { return quantile(v, 1.0); });
}

}  // namespace daep::bench
