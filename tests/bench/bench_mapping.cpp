#include <benchmark/benchmark.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/poses/CPose3D.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "BenchParams.h"
#include "daep/mapping/DepthUnprojection.h"
#include "daep/mapping/ExplorationMap.h"

namespace {

using daep::Aabb;
using daep::FlatPose;
using daep::mapping::ExplorationMap;

// A 10 x 8 x 3 m room; the camera stands at (3, 3, 1.5) so walls are 2-7 m away.
const Eigen::Vector3d kRoomMin(-1.0, -1.0, 0.0), kRoomMax(9.0, 7.0, 3.0);
const Eigen::Vector3d kCamera(3.0, 3.0, 1.5);

Aabb roomBox() {
    Aabb b;
    b.min = kRoomMin;
    b.max = kRoomMax;
    return b;
}

/** Depth frame (90 degree FOV) of the room's inner walls seen at `yaw` from kCamera. */
mrpt::obs::CObservation3DRangeScan roomFrame(int width, int height, double yaw) {
    mrpt::obs::CObservation3DRangeScan obs;
    obs.hasRangeImage = true;
    obs.range_is_depth = true;
    obs.rangeImage_setSize(height, width);
    obs.cameraParams.ncols = std::uint32_t(width);
    obs.cameraParams.nrows = std::uint32_t(height);
    const double f = 0.5 * width, cx = 0.5 * (width - 1), cy = 0.5 * (height - 1);
    obs.cameraParams.setIntrinsicParamsFromValues(f, f, cx, cy);
    const Eigen::Vector3d fwd(std::cos(yaw), std::sin(yaw), 0),
        left(-std::sin(yaw), std::cos(yaw), 0);
    for (int v = 0; v < height; ++v) {
        for (int u = 0; u < width; ++u) {
            const Eigen::Vector3d dir =
                fwd + (cx - u) / f * left + Eigen::Vector3d(0, 0, (cy - v) / f);
            double t = 1e9;  // depth = ray parameter, as the forward component of dir is 1
            for (int a = 0; a < 3; ++a) {
                if (dir[a] > 1e-9) {
                    t = std::min(t, (kRoomMax[a] - kCamera[a]) / dir[a]);
                } else if (dir[a] < -1e-9) {
                    t = std::min(t, (kRoomMin[a] - kCamera[a]) / dir[a]);
                }
            }
            obs.rangeImage(v, u) = std::uint16_t(std::lround(t / obs.rangeUnits));
        }
    }
    return obs;
}

FlatPose cameraPose(double yaw) {
    FlatPose p;
    p.position = kCamera;
    p.yaw = yaw;
    return p;
}

constexpr int kViews = 16;

double viewYaw(int i) {
    return 2.0 * M_PI * i / kViews;
}

void BM_MappingInsertObservation640x480(benchmark::State& state) {
    std::vector<mrpt::obs::CObservation3DRangeScan> frames;
    for (int i = 0; i < kViews; ++i) {
        frames.push_back(roomFrame(640, 480, viewYaw(i)));
    }
    ExplorationMap map(daep::bench::benchMap(), roomBox());
    int i = 0;
    for (auto _ : state) {
        map.insertObservation(frames[std::size_t(i % kViews)], cameraPose(viewYaw(i % kViews)));
        ++i;
    }
    state.counters["coverage"] = map.coverage();
}
BENCHMARK(BM_MappingInsertObservation640x480)->Unit(benchmark::kMillisecond);

/** First frame into an empty map: every cell is new. */
void BM_MappingInsertObservation640x480FreshMap(benchmark::State& state) {
    const auto frame = roomFrame(640, 480, 0.0);
    for (auto _ : state) {
        state.PauseTiming();
        ExplorationMap map(daep::bench::benchMap(), roomBox());
        state.ResumeTiming();
        map.insertObservation(frame, cameraPose(0.0));
        benchmark::DoNotOptimize(map.knownCellsInBox());
    }
}
BENCHMARK(BM_MappingInsertObservation640x480FreshMap)->Unit(benchmark::kMillisecond);

void BM_MappingInsertPointCloud320x240(benchmark::State& state) {
    std::vector<std::vector<Eigen::Vector3f>> clouds;
    for (int i = 0; i < kViews; ++i) {
        clouds.push_back(daep::mapping::unprojectDepthImage(roomFrame(320, 240, viewYaw(i)),
                                                            cameraPose(viewYaw(i))));
    }
    ExplorationMap map(daep::bench::benchMap(), roomBox());
    int i = 0;
    for (auto _ : state) {
        map.insertPointCloud(kCamera, clouds[std::size_t(i % kViews)]);
        ++i;
    }
}
BENCHMARK(BM_MappingInsertPointCloud320x240)->Unit(benchmark::kMillisecond);

void BM_MappingUnprojectOwn640x480(benchmark::State& state) {
    const auto frame = roomFrame(640, 480, 0.0);
    for (auto _ : state) {
        benchmark::DoNotOptimize(daep::mapping::unprojectDepthImage(frame, cameraPose(0.0)));
    }
}
BENCHMARK(BM_MappingUnprojectOwn640x480)->Unit(benchmark::kMillisecond);

void BM_MappingUnprojectMrpt640x480(benchmark::State& state) {
    auto frame = roomFrame(640, 480, 0.0);
    mrpt::obs::T3DPointsProjectionParams pp;
    pp.takeIntoAccountSensorPoseOnRobot = true;
    pp.robotPoseInTheWorld = mrpt::poses::CPose3D(kCamera.x(), kCamera.y(), kCamera.z(), 0.0, 0, 0);
    mrpt::maps::CSimplePointsMap points;
    for (auto _ : state) {
        frame.unprojectInto(points, pp);
        benchmark::DoNotOptimize(points.size());
    }
}
BENCHMARK(BM_MappingUnprojectMrpt640x480)->Unit(benchmark::kMillisecond);

/** 1e6 state() lookups at random points of the room plus 1 m around it. */
void BM_MappingStateLookups1M(benchmark::State& state) {
    ExplorationMap map(daep::bench::benchMap(), roomBox());
    for (int i = 0; i < kViews; ++i) {
        map.insertObservation(roomFrame(320, 240, viewYaw(i)), cameraPose(viewYaw(i)));
    }
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> ux(-2.0, 10.0), uy(-2.0, 8.0), uz(-1.0, 4.0);
    std::vector<Eigen::Vector3d> pts(1000000);
    for (auto& p : pts) {
        p = {ux(rng), uy(rng), uz(rng)};
    }
    for (auto _ : state) {
        int free = 0;
        for (const auto& p : pts) {
            free += map.isFree(p);
        }
        benchmark::DoNotOptimize(free);
    }
}
BENCHMARK(BM_MappingStateLookups1M)->Unit(benchmark::kMillisecond);

}  // namespace
