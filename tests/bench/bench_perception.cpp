// People detection and tracking of one depth frame (Exhibition, 22 people).
#include <benchmark/benchmark.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <memory>
#include <random>

#include "BenchParams.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/perception/PeopleDetector.h"
#include "daep/perception/PeopleTracker.h"
#include "daep/sim/DepthCamera.h"
#include "daep/world/People.h"
#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace {

/**
 * The drone at (-3.5, -3.5) has turned a full circle (mapping the hall and the people as they
 * were), then, 5 s later, looks west at the people walking along the west wall.
 */
struct DetectionScene {
    daep::world::WorldSpec world =
        daep::world::loadWorldFile(DAEP_SOURCE_DIR "/share/daep/worlds/exhibition.yaml");
    daep::world::RayCaster caster{world};
    daep::mapping::ExplorationMap map{daep::bench::benchMap(), world.explorationBox};
    mrpt::obs::CObservation3DRangeScan frame;
    daep::FlatPose drone{{-3.5, -3.5, 1.3}, M_PI};

    DetectionScene(int width, int height) {
        const daep::sim::DepthCamera camera(daep::bench::benchCamera(width, height));
        daep::world::PeopleSimulator people(world.people, daep::world::PeopleParams{});
        caster.setPeople(people.states(), people.params().bodySize);
        std::mt19937_64 rng(1);
        for (int k = 0; k < 36; ++k) {
            const daep::FlatPose turn{drone.position, k * M_PI / 18};
            camera.render(caster, turn, 0.1 * k, rng, frame);
            map.insertObservation(frame, turn);
        }
        people.advance(5.0);
        caster.setPeople(people.states(), people.params().bodySize);
        camera.render(caster, drone, 5.0, rng, frame);
    }
};

void BM_DetectAndTrackPeople(benchmark::State& state) {
    const DetectionScene scene(int(state.range(0)), int(state.range(1)));
    daep::perception::PeopleDetector detector{daep::perception::DetectorParams{}};
    daep::perception::PeopleTracker tracker{daep::bench::benchTracker()};
    double t = 5.0;
    std::size_t found = 0;
    for (auto _ : state) {
        const auto measurements = detector.detect(scene.frame, scene.drone, scene.map);
        tracker.update(t, measurements);
        benchmark::DoNotOptimize(tracker.forecasts());
        found = measurements.size();
        t += 0.2;
    }
    state.counters["people"] = double(found);
}
BENCHMARK(BM_DetectAndTrackPeople)
    ->Args({640, 480})
    ->Args({320, 240})
    ->Unit(benchmark::kMillisecond);

}  // namespace
