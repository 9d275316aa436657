// The map's own point-to-key conversion against OctoMap's coordToKeyChecked, which it
// replaces in the hot loops: the same key, and the same answer at the tree's edge.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <octomap/OcTree.h>

#include "OctreeKeys.h"
#include "daep/mapping/DenseGridIndex.h"

namespace daep::mapping {
namespace {

void expectSameKey(const octomap::OcTree& tree, double c) {
    octomap::key_type ours = 0, theirs = 0;
    // Beyond int OctoMap's own conversion is undefined: compared within it only.
    const bool inTree = std::isfinite(c) && std::abs(c) < 1e6 && tree.coordToKeyChecked(c, theirs);
    ASSERT_EQ(octreeAxisKey(1.0 / tree.getResolution(), c, ours), inTree) << c;
    if (inTree) {
        ASSERT_EQ(ours, theirs) << c;
    }
    octomap::key_type floored = 0;  // the SSE4.1 pixel loop's floor
    ASSERT_EQ(octreeAxisKey<true>(1.0 / tree.getResolution(), c, floored), inTree) << c;
    if (inTree) {
        ASSERT_EQ(floored, theirs) << c;
    }
}

TEST(OctreeAxisKey, IsOctomapsKeyOnAndOffCellBoundaries) {
    for (const double resolution : {0.2, 0.1, 0.05, 0.3}) {
        const octomap::OcTree m(resolution);
        const double scale = 1.0 / resolution;
        std::mt19937 rng(5);
        std::uniform_real_distribution<double> u(-50.0, 50.0);
        for (int i = 0; i < 100000; ++i)
            expectSameKey(m, u(rng));
        for (int k = -300; k <= 300; ++k) {
            const double boundary = k * resolution;
            for (const double c : {boundary, std::nextafter(boundary, -1e9),
                                   std::nextafter(boundary, 1e9), double(float(boundary))})
                expectSameKey(m, c);
        }
        const double edge = 32768.0 * resolution;  // where the tree's keys end
        for (const double c : {edge, -edge, std::nextafter(edge, 0.0), std::nextafter(-edge, 0.0),
                               std::nextafter(-edge, -1e9), 2 * edge, -2 * edge})
            expectSameKey(m, c);
        octomap::key_type k = 0;
        EXPECT_FALSE(octreeAxisKey(scale, std::numeric_limits<double>::quiet_NaN(), k));
        EXPECT_FALSE(octreeAxisKey(scale, std::numeric_limits<double>::infinity(), k));
        EXPECT_FALSE(octreeAxisKey(scale, -1e300, k));
        EXPECT_FALSE(octreeAxisKey<true>(scale, std::numeric_limits<double>::quiet_NaN(), k));
        EXPECT_FALSE(octreeAxisKey<true>(scale, -1e300, k));
    }
}

/**
 * The unchecked index of points on the grid (either floor) is the checked one; rays test their
 * ends only.
 */
TEST(DenseGridIndex, OnGridIsTheCheckedIndexAndRaysBetweenOnGridEndsStayOnIt) {
    const DenseGridIndex grid(1.0 / 0.2, {-60, -45, -3}, {120, 90, 25});
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-14.0, 14.0), z(-1.0, 5.5), unit(-1.0, 1.0);
    int onGrid = 0, rays = 0;
    for (int i = 0; i < 20000; ++i) {
        const Eigen::Vector3d p(u(rng), u(rng), z(rng));
        if (grid(p) >= 0) {
            ++onGrid;
            ASSERT_EQ(grid.onGrid(p), grid(p));
            ASSERT_EQ(grid.onGridFloored(p), grid(p));
        }
        const Eigen::Vector3d d = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
        const Eigen::Vector3d first = p + 0.1 * d, last = p + 4.9 * d;
        if (grid(first) < 0 || grid(last) < 0)
            continue;
        ++rays;
        for (int k = 0; k < 25; ++k) {
            const Eigen::Vector3d s = p + (k + 0.5) * 0.2 * d;
            ASSERT_GE(grid(s), 0);
            ASSERT_EQ(grid.onGrid(s), grid(s));
            ASSERT_EQ(grid.onGridFloored(s), grid(s));
        }
    }
    // On and beside the cells' faces, where the two floors could part.
    for (int i = -59; i < 59; ++i)
        for (const double c :
             {i * 0.2, std::nextafter(i * 0.2, -1e9), std::nextafter(i * 0.2, 1e9)}) {
            const Eigen::Vector3d p(c, 0.5 * c, 0.05 * c);
            if (grid(p) >= 0) {
                ASSERT_EQ(grid.onGridFloored(p), grid(p)) << c;
            }
        }
    EXPECT_GT(onGrid, 5000);
    EXPECT_GT(rays, 2000);
    const Eigen::Vector3d edge(-12.0, -9.0, -0.6);  // the lowest corner: on the grid
    EXPECT_EQ(grid(edge), 0);
    EXPECT_EQ(grid(Eigen::Vector3d(std::nextafter(-12.0, -13.0), -9.0, -0.6)), -1);
    EXPECT_EQ(grid(Eigen::Vector3d(12.0, 0.0, 0.0)), -1);  // high bounds are open
}

}  // namespace
}  // namespace daep::mapping
