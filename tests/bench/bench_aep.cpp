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
 * Cafe, partly explored by the real simulator pieces: the mission's take-off look-around at
 * three of the world's start positions.
 */
const daep::bench::PlanScene& cafe() {
    static const daep::bench::PlanScene scene = [] {
        daep::bench::PlanScene s;
        s.world = daep::world::loadWorldFile(DAEP_SOURCE_DIR "/share/daep/worlds/cafe.yaml");
        const daep::world::RayCaster caster(s.world);
        s.map = daep::bench::lookAroundAtStarts(s.world, caster, 3, s.poses);
        return s;
    }();
    return scene;
}

/** One AEP local planning call (cache refresh, branch reuse, RRT* with cubature or GP gain). */
void BM_AepLocalPlan(benchmark::State& state) {
    daep::bench::benchPlanCalls<daep::planning::AepPlanner, daep::planning::AepParams>(state,
                                                                                       cafe());
}
BENCHMARK(BM_AepLocalPlan)->Apply(daep::bench::asPlanCalls);

}  // namespace
