#include <benchmark/benchmark.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <algorithm>
#include <exception>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "daep/sim/DepthCamera.h"
#include "daep/world/People.h"
#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace {

/** The exhibition world with every person placed, loaded once for all benchmarks. */
struct ExhibitionScene {
    daep::world::WorldSpec world;
    std::unique_ptr<daep::world::RayCaster> caster;
    daep::FlatPose drone;

    ExhibitionScene() {
        world = daep::world::loadWorldFile(DAEP_SOURCE_DIR "/share/daep/worlds/exhibition.yaml");
        caster = std::make_unique<daep::world::RayCaster>(world);
        daep::world::PeopleSimulator people(world.people, daep::world::PeopleParams{});
        people.advance(5.0);  // people mid-route, not all on their first waypoint
        caster->setPeople(people.states(), people.params().bodySize);
        drone.position = world.starts.empty() ? world.explorationBox.center() : world.starts[0];
        drone.position.z() += 1.0;
    }
};

const ExhibitionScene* exhibition(benchmark::State& state) {
    static std::unique_ptr<ExhibitionScene> scene;
    static std::string error;
    if (!scene && error.empty()) {
        try {
            scene = std::make_unique<ExhibitionScene>();
        } catch (const std::exception& e) {
            error = e.what();
        }
    }
    if (!scene) {
        state.SkipWithError(error.c_str());
    }
    return scene.get();
}

daep::sim::CameraParams cameraParams(benchmark::State& state) {
    daep::sim::CameraParams p;
    p.width = static_cast<int>(state.range(0));
    p.height = static_cast<int>(state.range(1));
    p.maxRange = 10.0;
    return p;
}

void BM_DepthCameraRender(benchmark::State& state) {
    const ExhibitionScene* scene = exhibition(state);
    if (scene == nullptr) {
        return;
    }
    const daep::sim::DepthCamera camera(cameraParams(state));
    std::mt19937_64 rng(1);
    mrpt::obs::CObservation3DRangeScan obs;
    daep::FlatPose drone = scene->drone;
    double time = 0.0;
    for (auto _ : state) {
        camera.render(*scene->caster, drone, time, rng, obs);
        benchmark::DoNotOptimize(obs.rangeImage.data());
        drone.yaw += 0.1;  // sweep around so the frames differ
        time += 1.0 / 30.0;
    }
    state.SetItemsProcessed(state.iterations() * state.range(0) * state.range(1));
    const uint16_t* pixels = obs.rangeImage.data();
    const auto n = static_cast<std::ptrdiff_t>(obs.rangeImage.rows()) * obs.rangeImage.cols();
    state.counters["people"] = static_cast<double>(scene->world.people.size());
    state.counters["returns"] =
        static_cast<double>(std::count_if(pixels, pixels + n, [](uint16_t v) { return v != 0; })) /
        static_cast<double>(n);
}
BENCHMARK(BM_DepthCameraRender)->Args({640, 480})->Args({320, 240})->Unit(benchmark::kMillisecond);

void BM_DepthCameraRenderDepthOnly(benchmark::State& state) {
    const ExhibitionScene* scene = exhibition(state);
    if (scene == nullptr) {
        return;
    }
    const daep::sim::DepthCamera camera(cameraParams(state));
    std::mt19937_64 rng(1);
    std::vector<float> depth;
    daep::FlatPose drone = scene->drone;
    for (auto _ : state) {
        camera.renderDepth(*scene->caster, drone, &rng, depth);
        benchmark::DoNotOptimize(depth.data());
        drone.yaw += 0.1;
    }
    state.SetItemsProcessed(state.iterations() * state.range(0) * state.range(1));
}
BENCHMARK(BM_DepthCameraRenderDepthOnly)
    ->Args({640, 480})
    ->Args({320, 240})
    ->Unit(benchmark::kMillisecond);

}  // namespace
