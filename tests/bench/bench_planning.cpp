#include <benchmark/benchmark.h>

#include <memory>

#include "../planning/PlanningTestUtil.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/planning/GainEvaluator.h"
#include "daep/planning/RhNbvpPlanner.h"

namespace {

using daep::planning::test::box;

/**
 * A 15 x 15 x 2 m (450 m^3, Exhibition-sized) empty hall, partly known: three camera-like
 * scans (+-38.7 deg elevation, 5 m mapping range) from its south-west corner.
 */
struct PartlyKnownHall {
    std::unique_ptr<daep::mapping::ExplorationMap> map;
    daep::Aabb hall = box(-7.5, -7.5, 0, 7.5, 7.5, 2);

    PartlyKnownHall() {
        map = daep::planning::test::makeMap(hall, 5.0);
        const daep::Aabb walls = box(-7.6, -7.6, -0.1, 7.6, 7.6, 2.1);
        for (const Eigen::Vector3d& o :
             {Eigen::Vector3d(-5.5, -5.5, 1.0), Eigen::Vector3d(-3.0, -5.5, 1.0),
              Eigen::Vector3d(-5.5, -3.0, 1.0)}) {
            map->insertPointCloud(o, daep::planning::test::roomScan(walls, o, 0.5, 38.7));
        }
    }
};

const PartlyKnownHall& hall() {
    static const PartlyKnownHall scene;
    return scene;
}

daep::planning::PlanningContext hallContext() {
    daep::planning::PlanningContext c;
    c.pose.position = {-4.5, -4.5, 1.0};
    c.map = hall().map.get();
    c.explorationBox = hall().hall;
    return c;
}

void BM_GainBestYaw(benchmark::State& state) {
    const daep::planning::GainEvaluator gain{daep::planning::GainParams{}};
    const Eigen::Vector3d p(-2.5, -2.5, 1.0);  // at the edge of the known area
    for (auto _ : state)
        benchmark::DoNotOptimize(gain.bestYaw(*hall().map, p));
}
BENCHMARK(BM_GainBestYaw)->Unit(benchmark::kMicrosecond);

void BM_GainAtYaw(benchmark::State& state) {
    const daep::planning::GainEvaluator gain{daep::planning::GainParams{}};
    const Eigen::Vector3d p(-2.5, -2.5, 1.0);
    for (auto _ : state)
        benchmark::DoNotOptimize(gain.gainAtYaw(*hall().map, p, 0.7));
}
BENCHMARK(BM_GainAtYaw)->Unit(benchmark::kMicrosecond);

/**
 * One RH-NBVP plan from a fresh planner (no remembered branch). Arg 0: default parameters (the
 * tree stops at initial_iterations once gain is found); arg 1: zero_gain out of reach, so the
 * tree grows to cutoff_iterations, the cost of a "finished" verdict.
 */
void BM_RhNbvpPlan(benchmark::State& state) {
    const auto cfg = daep::planning::test::configFromText(daep::planning::test::defaultsText());
    auto params = daep::planning::RhNbvpParams::fromConfig(*cfg);
    if (state.range(0) == 1)
        params.zeroGain = 1e9;
    const auto gain = daep::planning::GainParams::fromConfig(*cfg);
    const daep::planning::PlanningContext context = hallContext();
    std::uint64_t seed = 0;
    std::size_t nodes = 0;
    for (auto _ : state) {
        daep::planning::RhNbvpPlanner planner(params, gain, ++seed);
        benchmark::DoNotOptimize(planner.plan(context));
        nodes += std::size_t(planner.tree().size());
    }
    state.counters["nodes"] = benchmark::Counter(double(nodes) / double(state.iterations()));
}
BENCHMARK(BM_RhNbvpPlan)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
