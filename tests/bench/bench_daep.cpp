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
 * The dynamic Exhibition (22 people) after 30 s: the map holds the take-off look-around at
 * three start positions, and every person has been tracked from ground truth at 5 Hz for the
 * last 2 s, as the mission does.
 */
const daep::bench::PlanScene& exhibition() {
    static const daep::bench::PlanScene scene = [] {
        daep::bench::PlanScene s;
        s.time = 30.0;
        s.world = daep::world::loadWorldFile(DAEP_SOURCE_DIR "/share/daep/worlds/exhibition.yaml");
        daep::world::RayCaster caster(s.world);
        daep::world::PeopleSimulator walkers(s.world.people, daep::world::PeopleParams{});
        daep::perception::PeopleTracker tracker(daep::bench::benchTracker());
        walkers.advance(s.time - 2.0);
        for (int k = 0; k <= 10; ++k) {
            std::vector<daep::perception::PersonMeasurement> m;
            for (std::size_t i = 0; i < walkers.states().size(); ++i)
                m.push_back({static_cast<int>(i), walkers.states()[i].position,
                             Eigen::Matrix2d::Identity() * 4e-4});
            tracker.update(s.time - 2.0 + 0.2 * k, m);
            if (k < 10)
                walkers.advance(0.2);
        }
        s.people = tracker.forecasts();
        caster.setPeople(walkers.states(), daep::world::PeopleParams{}.bodySize);
        s.map = daep::bench::lookAroundAtStarts(s.world, caster, 3, s.poses);
        return s;
    }();
    return scene;
}

/**
 * One DAEP planning call among the 22 tracked people (time-aware local RRT*, swept safety
 * checks, dynamic gain, frequency-map score; the global planner when the local gain runs out).
 */
void BM_DaepPlan(benchmark::State& state) {
    daep::bench::benchPlanCalls<daep::planning::DaepPlanner, daep::planning::DaepParams>(
        state, exhibition());
}
BENCHMARK(BM_DaepPlan)->Apply(daep::bench::asPlanCalls);

}  // namespace
