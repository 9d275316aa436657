// Benchmarks of the world module: the depth camera's ray casting hot path and its helpers.
#include <benchmark/benchmark.h>

#include <octomap/OcTree.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "daep/world/People.h"
#include "daep/world/RayCaster.h"
#include "daep/world/VoxelMaps.h"
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

/**
 * A scanned building's map at 0.05 m: a 20 x 20 x 3 m storey, outer and inner walls one cell
 * thick every 4 m, floor and ceiling, a 25 cm door in every inner wall and scattered clutter;
 * written as .bt and a world file around it, once per process.
 */
struct LargeMap {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "daep_bench_large_map";
    std::string world = (dir / "building.yaml").string();
    std::size_t nodes = 0;

    LargeMap() {
        std::filesystem::create_directories(dir);
        octomap::OcTree tree(0.05);
        const int n = 400, h = 60;  // cells: 20 m, 3 m
        auto occupy = [&](int i, int j, int k) {
            tree.updateNode(octomap::point3d(0.05f * i - 10.0f + 0.025f, 0.05f * j - 10.0f + 0.025f,
                                             0.05f * k + 0.025f),
                            true, true);
        };
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                occupy(i, j, -1);
                occupy(i, j, h);
                const bool wallX = i % 80 == 0 || i == n - 1, wallY = j % 80 == 0 || j == n - 1;
                const bool door = (i % 80 == 40 || j % 80 == 40) && i > 0 && j > 0;
                if ((wallX || wallY) && !door)
                    for (int k = 0; k < h; ++k)
                        occupy(i, j, k);
            }
        // Clutter that merges with nothing: 200k scattered cells up to 2 m (a fixed sequence).
        std::uint32_t r = 12345;
        auto next = [&r](int m) { return int((r = r * 1664525u + 1013904223u) >> 8) % m; };
        // The start (-8, -8) keeps a clear metre around it: the loader rejects a start in geometry.
        const auto nearStart = [](int i, int j) {
            return std::abs(0.05 * i - 10.0 + 8.0) < 0.6 && std::abs(0.05 * j - 10.0 + 8.0) < 0.6;
        };
        for (int c = 0; c < 200000; ++c) {
            const int i = next(n), j = next(n), k = next(40);
            if (!nearStart(i, j))
                occupy(i, j, k);
        }
        tree.updateInnerOccupancy();
        tree.prune();
        nodes = tree.size();
        tree.writeBinary((dir / "building.bt").string());
        std::ofstream(world) << "exploration_box: {min: [-9.5, -9.5, 0], max: [9.5, 9.5, 2.9]}\n"
                                "starts: [[-8, -8, 0.3]]\noctomap: building.bt\n";
    }
    static const LargeMap& get() {
        static const LargeMap map;
        return map;
    }
};

/** Loading the large map's world file: reading the octree, merging its leaves into boxes. */
void BM_LoadLargeOctomapWorld(benchmark::State& state) {
    const LargeMap& large = LargeMap::get();
    std::size_t cells = 0, boxes = 0;
    for (auto _ : state) {
        const WorldSpec w = loadWorldFile(large.world);
        cells = w.voxelMaps[0].cells;
        boxes = w.voxelMaps[0].boxes.size();
    }
    state.counters["octree_nodes"] = double(large.nodes);
    state.counters["cells"] = double(cells);
    state.counters["boxes"] = double(boxes);
}
BENCHMARK(BM_LoadLargeOctomapWorld)->Unit(benchmark::kMillisecond);

/** Building the Embree scene and the collision checker of the large map. */
void BM_BuildLargeOctomapScene(benchmark::State& state) {
    const WorldSpec w = loadWorldFile(LargeMap::get().world);
    for (auto _ : state) {
        const RayCaster caster(w);
        const StaticCollisionChecker checker(w);
        benchmark::DoNotOptimize(&caster);
        benchmark::DoNotOptimize(&checker);
    }
}
BENCHMARK(BM_BuildLargeOctomapScene)->Unit(benchmark::kMillisecond);

/** One 640 x 480 depth frame in a room of the large map. */
void BM_CastRaysLargeOctomapFrame(benchmark::State& state) {
    const WorldSpec w = loadWorldFile(LargeMap::get().world);
    const RayCaster caster(w);
    const std::vector<Eigen::Vector3f> dirs = pinholeFan(640, 480, 103.2);
    std::vector<float> ranges;
    for (auto _ : state) {
        caster.castRays({-7, -7, 1}, dirs, 10.0f, ranges);
        benchmark::DoNotOptimize(ranges.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<int64_t>(dirs.size()));
}
BENCHMARK(BM_CastRaysLargeOctomapFrame)->Unit(benchmark::kMillisecond);

/** Drone-box overlap queries along the large map's walls. */
void BM_StaticOverlapLargeOctomap(benchmark::State& state) {
    const WorldSpec w = loadWorldFile(LargeMap::get().world);
    const StaticCollisionChecker checker(w);
    const Eigen::Vector3d drone(0.4, 0.4, 0.1);
    int i = 0;
    for (auto _ : state) {
        const Eigen::Vector3d c(-9.9 + 0.05 * (i % 397), -6.0 + 0.37 * (i % 41),
                                0.5 + 0.01 * (i % 7));
        benchmark::DoNotOptimize(checker.overlaps(c, drone, 0.1 * i));
        ++i;
    }
}
BENCHMARK(BM_StaticOverlapLargeOctomap);

}  // namespace
