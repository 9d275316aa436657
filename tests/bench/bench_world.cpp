// Benchmarks of the world module: the depth camera's ray casting hot path and its helpers.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "daep/world/People.h"
#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace {

using namespace daep::world;

/** Unit rays of a pinhole camera looking along +x (z up), square pixels, row by row. */
std::vector<Eigen::Vector3f> pinholeFan(int width, int height, double hfovDeg) {
    const double f = 0.5 * width / std::tan(0.5 * hfovDeg * M_PI / 180.0);
    const double cx = 0.5 * (width - 1), cy = 0.5 * (height - 1);
    std::vector<Eigen::Vector3f> dirs;
    dirs.reserve(static_cast<std::size_t>(width) * height);
    for (int v = 0; v < height; ++v)
        for (int u = 0; u < width; ++u)
            dirs.push_back(Eigen::Vector3d(f, cx - u, cy - v).normalized().cast<float>());
    return dirs;
}

struct Exhibition {
    WorldSpec world = loadWorldFile(resolveWorldPath("exhibition"));
    PeopleParams params;
    PeopleSimulator people{world.people, params};
    Exhibition() { people.advance(20.0); }
};

/** One 640 x 480 depth frame (103.2 deg hfov) from the hall's centre at z = 1, 22 people. */
void BM_CastRaysExhibitionFrame(benchmark::State& state) {
    Exhibition ex;
    RayCaster caster(ex.world);
    caster.setPeople(ex.people.states(), ex.params.bodySize);
    const std::vector<Eigen::Vector3f> dirs = pinholeFan(640, 480, 103.2);
    const Eigen::Vector3f origin(0, 0, 1);
    std::vector<float> ranges;
    for (auto _ : state) {
        caster.castRays(origin, dirs, 10.0f, ranges);
        benchmark::DoNotOptimize(ranges.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(dirs.size()));
}
BENCHMARK(BM_CastRaysExhibitionFrame)->Unit(benchmark::kMillisecond);

/** Moving the 22 person boxes: once per simulated camera frame. */
void BM_AdvanceAndSetPeopleExhibition(benchmark::State& state) {
    Exhibition ex;
    RayCaster caster(ex.world);
    for (auto _ : state) {
        ex.people.advance(0.05);
        caster.setPeople(ex.people.states(), ex.params.bodySize);
    }
}
BENCHMARK(BM_AdvanceAndSetPeopleExhibition)->Unit(benchmark::kMicrosecond);

/** Drone-box overlap queries spread over the exhibition hall. */
void BM_StaticOverlapExhibition(benchmark::State& state) {
    Exhibition ex;
    const StaticCollisionChecker checker(ex.world);
    const Eigen::Vector3d drone(0.4, 0.4, 0.1);
    int i = 0;
    for (auto _ : state) {
        const Eigen::Vector3d c(-7.5 + 0.05 * (i % 300), -7.5 + 0.37 * (i % 41),
                                0.06 + 0.01 * (i % 7));
        benchmark::DoNotOptimize(checker.overlaps(c, drone, 0.1 * i));
        ++i;
    }
}
BENCHMARK(BM_StaticOverlapExhibition);

}  // namespace
