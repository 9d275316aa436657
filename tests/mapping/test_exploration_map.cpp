#include <gtest/gtest.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "MapTestUtils.h"
#include "daep/common/Error.h"
#include "daep/mapping/ExplorationMap.h"

namespace daep::mapping {
namespace {

using test::cellCentre;
using test::octreeState;

Aabb makeBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    Aabb b;
    b.min = lo;
    b.max = hi;
    return b;
}

TEST(ExplorationMap, RejectsBadParameters) {
    const Aabb box = makeBox({0, 0, 0}, {4, 4, 2});
    MapParams p;
    p.resolution = 0.0;
    EXPECT_THROW(ExplorationMap(p, box), InputError);
    p = MapParams{};
    p.clampMin = 0.99;
    EXPECT_THROW(ExplorationMap(p, box), InputError);
    EXPECT_THROW(ExplorationMap(MapParams{}, makeBox({0, 0, 0}, {4, 0, 2})), InputError);
    EXPECT_NO_THROW(ExplorationMap(MapParams{}, box));
}

TEST(ExplorationMap, StartsUnknown) {
    ExplorationMap map(MapParams{}, makeBox({0, 0, 0}, {4, 4, 2}));
    EXPECT_EQ(map.knownCellsInBox(), 0u);
    EXPECT_DOUBLE_EQ(map.coverage(), 0.0);
    EXPECT_TRUE(map.isUnknown({1, 1, 1}));
    EXPECT_TRUE(map.isUnknown({100, 100, 100}));
    EXPECT_EQ(map.revision(), 0u);
}

TEST(ExplorationMap, WallCloudClearsFrontMarksWallLeavesBehindUnknown) {
    ExplorationMap map(MapParams{}, makeBox({-1, -3, 0}, {8, 3, 3}));
    // A wall in the plane x = 3.1 (middle of a cell layer), seen from (0.1, 0.1, 1.1).
    std::vector<Eigen::Vector3f> wall;
    for (double y = -1.0; y <= 1.0; y += 0.05) {
        for (double z = 0.5; z <= 1.7; z += 0.05) {
            wall.emplace_back(3.1f, float(y), float(z));
        }
    }
    map.insertPointCloud({0.1, 0.1, 1.1}, wall);
    EXPECT_EQ(map.revision(), 1u);
    for (double x = 0.1; x < 2.95; x += 0.2) {
        EXPECT_TRUE(map.isFree({x, 0.1, 1.1})) << x;
    }
    for (double y = -0.9; y <= 0.9; y += 0.2) {
        EXPECT_TRUE(map.isOccupied({3.1, y, 1.1})) << y;
        EXPECT_TRUE(map.isUnknown({3.3, y, 1.1})) << y;
        EXPECT_TRUE(map.isUnknown({4.5, y, 1.1})) << y;
    }
    EXPECT_GT(map.knownCellsInBox(), 0u);
}

/** A camera of one ray along +x at 1.1 m: a wall 3 m ahead, a walker who may step in at 1.8 m. */
struct OneRayFrames : ::testing::Test {
    ExplorationMap map{MapParams{}, makeBox({-1, -3, 0}, {8, 3, 3})};
    const Eigen::Vector3d eye{0.1, 0.1, 1.1}, wall{3.1, 0.1, 1.1}, walker{1.9, 0.1, 1.1};
    void frames(const Eigen::Vector3d& end, int n = 1) {
        for (int k = 0; k < n; ++k)
            map.insertPointCloud(eye, {end.cast<float>()});
    }
};

TEST_F(OneRayFrames, OnlyWhatMovesIntoSurelyFreeSpaceHasMovedIn) {
    frames(wall, 2);  // the wall, seen at once: occupied, never free
    EXPECT_TRUE(map.isOccupied(wall));
    EXPECT_FALSE(map.movedIn(wall));
    // Once free, not yet surely: a return there is no proof something moved in.
    frames(wall);
    frames(walker);
    EXPECT_FALSE(map.movedIn(walker));
    // Cleared down to the clamping threshold, then a return: someone walked in.
    frames(wall, 8);
    ASSERT_TRUE(map.isFree(walker));
    EXPECT_FALSE(map.movedIn(walker));
    frames(walker);
    EXPECT_TRUE(map.movedIn(walker));
    // It stays marked through their stay and after they leave; the wall behind stays static.
    frames(walker, 3);
    EXPECT_TRUE(map.isOccupied(walker));
    EXPECT_TRUE(map.movedIn(walker));
    EXPECT_FALSE(map.movedIn(wall));
    EXPECT_FALSE(map.movedIn({20.0, 0.1, 1.1}));  // off the grid
}

TEST_F(OneRayFrames, ImprintsAndFlownCellsLetACapsuleThroughWallsDoNot) {
    frames(wall, 8);
    frames(walker, 3);
    ASSERT_TRUE(map.isOccupied(walker) && map.movedIn(walker));
    const Eigen::Vector3d before(1.1, 0.1, 1.1), past(2.5, 0.1, 1.1);
    EXPECT_FALSE(map.isSegmentFree(before, past, 0.0));
    EXPECT_TRUE(map.isSegmentFreeThroughImprints(before, past, 0.0));
    EXPECT_FALSE(map.isSegmentFreeThroughImprints(before, wall, 0.0));
    // The drone's own cell, where a return ended (someone walked into it): no wall there.
    const Eigen::Vector3d own(0.7, 0.9, 1.1);
    map.insertPointCloud(before, {own.cast<float>()});
    ASSERT_TRUE(map.isOccupied(own) && !map.movedIn(own));
    EXPECT_FALSE(map.isSegmentFreeThroughImprints(own, before, 0.0));
    map.markFlown(own);
    EXPECT_TRUE(map.isSegmentFreeThroughImprints(own, before, 0.0));
    EXPECT_FALSE(map.isSegmentFree(own, before, 0.0));
}

TEST(ExplorationMap, PointsBeyondMaxRangeClearUpToMaxRangeOnly) {
    MapParams p;
    p.maxRange = 2.0;
    ExplorationMap map(p, makeBox({-1, -1, -1}, {8, 1, 1}));
    map.insertPointCloud({0.1, 0.1, 0.1}, {Eigen::Vector3f(6.1f, 0.1f, 0.1f)});
    EXPECT_TRUE(map.isFree({0.1, 0.1, 0.1}));
    EXPECT_TRUE(map.isFree({1.9, 0.1, 0.1}));
    EXPECT_TRUE(map.isUnknown({2.3, 0.1, 0.1}));
    EXPECT_TRUE(map.isUnknown({6.1, 0.1, 0.1}));
    EXPECT_EQ(map.knownCellsInBox(), 10u);
}

TEST(ExplorationMap, CoverageOfClearedRegionMatchesAnalyticCount) {
    MapParams p;
    p.maxRange = 2.0;  // each freeRow clears 10 cells
    const double res = p.resolution;
    const Aabb box = makeBox({0, 0, 0}, {3, 2, 1});
    ExplorationMap map(p, box);
    // Rows start at x cell -3 (partly outside the box); y cells -2..12, z cells -1..6.
    for (int z = -1; z <= 6; ++z) {
        for (int y = -2; y <= 12; ++y) {
            test::freeRow(map, {-3, y, z});
        }
    }
    std::size_t expected = 0;
    for (int z = -1; z <= 6; ++z) {
        for (int y = -2; y <= 12; ++y) {
            for (int x = -3; x < 7; ++x) {
                const Eigen::Vector3d c = cellCentre({x, y, z}, res);
                ASSERT_TRUE(map.isFree(c)) << c.transpose();
                expected +=
                    (c.array() >= box.min.array()).all() && (c.array() < box.max.array()).all();
            }
        }
    }
    // x centres 0.1..1.3 (7), y centres 0.1..1.9 (10), z centres 0.1..0.9 (5).
    EXPECT_EQ(expected, 7u * 10u * 5u);
    EXPECT_EQ(map.knownCellsInBox(), expected);
    EXPECT_NEAR(map.knownVolumeInBox(), expected * res * res * res, 1e-12);
    EXPECT_NEAR(map.coverage(), expected * res * res * res / box.volume(), 1e-12);
    // Re-observing known cells (and marking one occupied) does not count twice.
    test::freeRow(map, {-3, 2, 2});
    test::occupy(map, cellCentre({1, 2, 2}, res));
    EXPECT_TRUE(map.isOccupied(cellCentre({1, 2, 2}, res)));
    EXPECT_EQ(map.knownCellsInBox(), expected);
}

/** Known cells with centre in the box, counted from the octree's leaves. */
std::size_t bruteForceKnownInBox(const octomap::OcTree& tree, const Aabb& box) {
    std::size_t count = 0;
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
        // A leaf at depth d spans 2^(16 - d) cells per axis from its index key.
        const int span = 1 << (tree.getTreeDepth() - it.getDepth());
        const octomap::OcTreeKey first = it.getIndexKey();
        std::size_t perAxis[3];
        for (int a = 0; a < 3; ++a) {
            perAxis[a] = 0;
            for (int i = 0; i < span; ++i) {
                const double centre = tree.keyToCoord(octomap::key_type(first[a] + i));
                perAxis[a] += centre >= box.min[a] && centre < box.max[a];
            }
        }
        count += perAxis[0] * perAxis[1] * perAxis[2];
    }
    return count;
}

void insertRandomClouds(ExplorationMap& map, std::mt19937& rng, int clouds) {
    const Aabb& box = map.explorationBox();
    std::uniform_real_distribution<double> ux(box.min.x(), box.max.x());
    std::uniform_real_distribution<double> uy(box.min.y(), box.max.y());
    std::uniform_real_distribution<double> uz(box.min.z(), box.max.z());
    std::uniform_real_distribution<double> spread(-7.0, 7.0);
    for (int c = 0; c < clouds; ++c) {
        const Eigen::Vector3d origin(ux(rng), uy(rng), uz(rng));
        std::vector<Eigen::Vector3f> pts;
        for (int i = 0; i < 300; ++i) {
            pts.push_back((origin + Eigen::Vector3d(spread(rng), spread(rng), 0.4 * spread(rng)))
                              .cast<float>());
        }
        map.insertPointCloud(origin, pts);
    }
}

TEST(ExplorationMap, KnownCellsMatchBruteForceLeafCount) {
    const Aabb box = makeBox({-2.05, -3.0, 0.0}, {5.31, 4.13, 2.5});
    ExplorationMap map(MapParams{}, box);
    std::mt19937 rng(12345);
    for (int round = 0; round < 6; ++round) {
        insertRandomClouds(map, rng, 10);
        ASSERT_EQ(map.knownCellsInBox(), bruteForceKnownInBox(map.octree(), box)) << round;
    }
    std::size_t coarseLeaves = 0;  // the count above did expand pruned leaves
    for (auto it = map.octree().begin_leafs(); it != map.octree().end_leafs(); ++it) {
        coarseLeaves += it.getDepth() < map.octree().getTreeDepth();
    }
    EXPECT_GT(coarseLeaves, 100u);
    EXPECT_GT(map.coverage(), 0.05);
    EXPECT_LE(map.coverage(), 1.0);
}

/** End points seen from one origin. */
struct Scan {
    Eigen::Vector3d origin;
    std::vector<Eigen::Vector3f> points;
};

/**
 * Inserts each scan into our map and into OctoMap's own insertPointCloud with discretize, the
 * reference our walk of each ray (and the marks that replace its key sets) must reproduce, and
 * expects the two trees equal leaf for leaf and log-odds for log-odds.
 */
void expectOctomapsDiscreteUpdate(const Aabb& box, const std::vector<Scan>& scans,
                                  std::size_t minLeaves, int readEvery = 0) {
    const MapParams params;
    ExplorationMap map(params, box);
    octomap::OcTree reference(params.resolution);
    reference.setProbHit(params.probHit);
    reference.setProbMiss(params.probMiss);
    reference.setClampingThresMin(params.clampMin);
    reference.setClampingThresMax(params.clampMax);
    for (std::size_t s = 0; s < scans.size(); ++s) {
        const Scan& scan = scans[s];
        octomap::Pointcloud cloud;
        for (const Eigen::Vector3f& p : scan.points)
            cloud.push_back(p.x(), p.y(), p.z());
        map.insertPointCloud(scan.origin, scan.points);
        const Eigen::Vector3f o = scan.origin.cast<float>();
        reference.insertPointCloud(cloud, octomap::point3d(o.x(), o.y(), o.z()), params.maxRange,
                                   false, true);
        // The tree takes the grid's changes when read: read between frames too, node for node.
        if (readEvery > 0 && s % std::size_t(readEvery) == 0) {
            ASSERT_EQ(map.octree().size(), reference.size()) << s;
            ASSERT_EQ(map.octree().getNumLeafNodes(), reference.getNumLeafNodes()) << s;
        }
    }
    EXPECT_EQ(map.octree().size(), reference.size());
    std::size_t leaves = 0;
    for (auto it = reference.begin_leafs(); it != reference.end_leafs(); ++it, ++leaves) {
        const octomap::OcTreeNode* ours = map.octree().search(it.getKey(), it.getDepth());
        ASSERT_NE(ours, nullptr) << it.getCoordinate();
        ASSERT_EQ(ours->getLogOdds(), it->getLogOdds()) << it.getCoordinate();
    }
    EXPECT_EQ(map.octree().getNumLeafNodes(), leaves);
    EXPECT_GT(leaves, minLeaves);
}

TEST(ExplorationMap, InsertionEqualsOctomapsOwnDiscreteUpdate) {
    // Rays that leave the dense grid and end points beyond the range.
    const Aabb box = makeBox({-1.3, -2.0, 0.0}, {4.1, 3.3, 2.5});
    std::mt19937 rng(99);
    std::uniform_real_distribution<double> u(0.0, 1.0), spread(-8.0, 8.0);
    std::vector<Scan> scans;
    for (int c = 0; c < 30; ++c) {
        Scan& scan = scans.emplace_back();
        scan.origin =
            box.min + (box.max - box.min).cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
        for (int i = 0; i < 400; ++i)
            scan.points.push_back(
                (scan.origin + Eigen::Vector3d(spread(rng), spread(rng), 0.3 * spread(rng)))
                    .cast<float>());
    }
    expectOctomapsDiscreteUpdate(box, scans, 5000);
    expectOctomapsDiscreteUpdate(box, scans, 5000, 3);
}

TEST(ExplorationMap, RaysCutAtTheRangeOnCellFacesAreOctomapsToo) {
    // Rays that stay on the grid, cut at maxRange (5 m) where the cut lands on a cell face or
    // edge: from origins on faces, along the axes and the diagonals, and to random points.
    const Aabb box = makeBox({-8.0, -8.0, -6.0}, {8.0, 8.0, 6.0});
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::vector<Scan> scans;
    for (const Eigen::Vector3d& origin :
         {Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(0.2, -0.4, 0.6),
          Eigen::Vector3d(0.1, 0.3, -0.2)}) {
        Scan& scan = scans.emplace_back();
        scan.origin = origin;
        for (int x = -1; x <= 1; ++x)
            for (int y = -1; y <= 1; ++y)
                for (int z = -1; z <= 1; ++z)
                    if (x != 0 || y != 0 || z != 0)
                        for (const double reach : {5.0, 5.4, 7.0})
                            scan.points.push_back(
                                (origin + reach * Eigen::Vector3d(x, y, z).normalized())
                                    .cast<float>());
        for (int i = 0; i < 2000; ++i)
            scan.points.push_back(
                (origin + 6.0 * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized())
                    .cast<float>());
    }
    expectOctomapsDiscreteUpdate(box, scans, 3000);
}

TEST(ExplorationMap, OctreeStaysPrunedAndAgreesWithDenseGrid) {
    MapParams p;
    p.maxRange = 3.2;
    ExplorationMap map(p, makeBox({0, 0, 0}, {4, 4, 4}));
    for (int z = 0; z < 8; ++z) {
        for (int y = 0; y < 8; ++y) {
            test::freeRow(map, {0, y, z});
        }
    }
    // 16 x 8 x 8 free cells of one value collapse into two 1.6 m leaves.
    EXPECT_EQ(map.octree().getNumLeafNodes(), 2u);
    const double res = p.resolution;
    for (int z = -1; z <= 8; ++z) {
        for (int y = -1; y <= 8; ++y) {
            for (int x = -1; x <= 16; ++x) {
                const Eigen::Vector3d c = cellCentre({x, y, z}, res);
                ASSERT_EQ(map.state(c), octreeState(map.octree(), c)) << c.transpose();
            }
        }
    }
}

TEST(ExplorationMap, DenseGridAgreesWithOctreeInsideAndOutside) {
    const Aabb box = makeBox({0, 0, 0}, {6, 5, 3});
    ExplorationMap map(MapParams{}, box);
    std::mt19937 rng(7);
    insertRandomClouds(map, rng, 40);  // rays reach up to 5 m beyond the 1 m grid margin
    std::uniform_real_distribution<double> u(-7.0, 13.0);
    std::size_t outside = 0, known = 0;
    for (int i = 0; i < 200000; ++i) {
        const Eigen::Vector3d p(u(rng), u(rng), 0.6 * u(rng));
        const CellState s = map.state(p);
        ASSERT_EQ(s, octreeState(map.octree(), p)) << p.transpose();
        outside += !box.contains(p) && s != CellState::Unknown;
        known += s != CellState::Unknown;
    }
    EXPECT_GT(outside, 1000u);  // the fallback path was really exercised
    EXPECT_GT(known, 10000u);
    // Points on (or a rounding error away from) cell boundaries resolve to the same cell.
    for (int i = -20; i <= 60; ++i) {
        for (int j = -15; j <= 40; j += 5) {
            for (int k = -10; k <= 25; k += 5) {
                for (double eps : {0.0, 1e-12, -1e-12}) {
                    const Eigen::Vector3d p(i * 0.2 + eps, j * 0.2 - eps, k * 0.2 + eps);
                    ASSERT_EQ(map.state(p), octreeState(map.octree(), p)) << p.transpose();
                }
            }
        }
    }
    EXPECT_EQ(map.state({NAN, 1.0, 1.0}), CellState::Unknown);
    EXPECT_EQ(map.state({1e300, 1.0, 1.0}), CellState::Unknown);
}

TEST(ExplorationMap, CellCenter) {
    ExplorationMap map(MapParams{}, makeBox({0, 0, 0}, {4, 4, 2}));
    const Eigen::Vector3d c = map.cellCenter({0.35, -0.05, 1.99});
    EXPECT_NEAR(c.x(), 0.3, 1e-12);
    EXPECT_NEAR(c.y(), -0.1, 1e-12);
    EXPECT_NEAR(c.z(), 1.9, 1e-12);
}

TEST(ExplorationMap, WriteBinaryRoundTripsThroughOctomap) {
    const Aabb box = makeBox({0, 0, 0}, {5, 5, 3});
    ExplorationMap map(MapParams{}, box);
    std::mt19937 rng(99);
    insertRandomClouds(map, rng, 15);
    const std::string path = ::testing::TempDir() + "daep_mapping_roundtrip.bt";
    ASSERT_TRUE(map.writeBinary(path));
    octomap::OcTree loaded(0.1);
    ASSERT_TRUE(loaded.readBinary(path));
    EXPECT_DOUBLE_EQ(loaded.getResolution(), 0.2);
    EXPECT_EQ(loaded.getNumLeafNodes(), map.octree().getNumLeafNodes());
    std::uniform_real_distribution<double> u(-1.0, 6.0);
    for (int i = 0; i < 20000; ++i) {
        const Eigen::Vector3d p(u(rng), u(rng), u(rng));
        ASSERT_EQ(octreeState(loaded, p), map.state(p)) << p.transpose();
    }
    std::remove(path.c_str());
    EXPECT_FALSE(map.writeBinary("/nonexistent-dir/x/map.bt"));
}

}  // namespace
}  // namespace daep::mapping
