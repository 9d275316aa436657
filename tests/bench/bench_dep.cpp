#include <benchmark/benchmark.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <cmath>
#include <memory>
#include <random>

#include "../planning/PlanningTestUtil.h"
#include "BenchParams.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/planning/DepPlanner.h"
#include "daep/sim/DepthCamera.h"
#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace {

namespace dp = daep::planning;

/**
 * Cafe, partly explored by DEP itself: take-off view at start 0 (a full turn), then `plans`
 * DEP plans flown by placing the drone at every waypoint (one depth frame every 0.5 m and at
 * every turn), with the real camera, ray caster and map. What is left is a realistic map and a
 * realistic roadmap at that point of a mission.
 */
struct CafeMission {
    daep::world::WorldSpec world =
        daep::world::loadWorldFile(DAEP_SOURCE_DIR "/share/daep/worlds/cafe.yaml");
    daep::world::RayCaster caster{world};
    std::unique_ptr<daep::mapping::ExplorationMap> map;
    std::unique_ptr<dp::DepPlanner> planner;
    daep::FlatPose pose;
    std::mt19937_64 noise{1};

    explicit CafeMission(int plans) {
        const auto cfg = dp::test::configFromText(dp::test::defaultsText());
        map = dp::test::makeMap(world.explorationBox, 5.0);
        planner = std::make_unique<dp::DepPlanner>(dp::DepParams::fromConfig(*cfg),
                                                   dp::GainParams::fromConfig(*cfg), 7);
        pose.position = world.starts[0] + Eigen::Vector3d(0, 0, 1.05);
        for (int q = 0; q < 8; ++q) {
            pose.yaw = daep::wrapAngle(q * M_PI / 4);
            observe();
        }
        for (int i = 0; i < plans; ++i)
            fly(planner->plan(context()));
    }

    dp::PlanningContext context() const {
        dp::PlanningContext c;
        c.pose = pose;
        c.map = map.get();
        c.explorationBox = world.explorationBox;
        return c;
    }

    void observe() {
        static const daep::sim::DepthCamera camera(daep::bench::benchCamera(320, 240));
        mrpt::obs::CObservation3DRangeScan frame;
        camera.render(caster, pose, 0.0, noise, frame);
        map->insertObservation(frame, pose);
    }

    void fly(const dp::Plan& plan) {
        for (const dp::Waypoint& w : plan.waypoints) {
            const Eigen::Vector3d from = pose.position;
            pose.yaw = w.pose.yaw;
            const int steps = std::max(1, int(std::ceil((w.pose.position - from).norm() / 0.5)));
            for (int k = 1; k <= steps; ++k) {
                pose.position = from + (w.pose.position - from) * (double(k) / steps);
                observe();
            }
        }
    }
};

/** One DEP planning call after `range(0)` plans of a Cafe mission (a copy of the planner). */
void BM_DepPlanCafe(benchmark::State& state) {
    static const CafeMission early(5), mid(20);
    const CafeMission& mission = state.range(0) == 5 ? early : mid;
    const dp::PlanningContext context = mission.context();
    int nodes = 0;
    for (auto _ : state) {
        state.PauseTiming();
        dp::DepPlanner planner = *mission.planner;
        state.ResumeTiming();
        benchmark::DoNotOptimize(planner.plan(context));
        nodes = planner.roadmap().size();
    }
    state.counters["roadmap_nodes"] = nodes;
    state.counters["coverage_pct"] = 100.0 * mission.map->coverage();
}
BENCHMARK(BM_DepPlanCafe)->Arg(5)->Arg(20)->Unit(benchmark::kMillisecond);

/** The 32-bin weighted gain of one node in the partly explored Cafe. */
void BM_DepYawBinnedGain(benchmark::State& state) {
    static const CafeMission mission(5);
    const auto cfg = dp::test::configFromText(dp::test::defaultsText());
    const dp::DepParams params = dp::DepParams::fromConfig(*cfg);
    const dp::YawBinnedGain gain(dp::GainParams::fromConfig(*cfg), params.yawBins, params.weights);
    for (auto _ : state)
        benchmark::DoNotOptimize(gain.evaluate(*mission.map, mission.pose.position));
}
BENCHMARK(BM_DepYawBinnedGain)->Unit(benchmark::kMicrosecond);

}  // namespace
