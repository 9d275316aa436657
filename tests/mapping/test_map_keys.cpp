// The map's own point-to-key conversion against OctoMap's coordToKeyChecked, which it
// replaces in the hot loops: the same key, and the same answer at the tree's edge.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include <octomap/OcTree.h>

#include "OctreeKeys.h"

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
    }
}

}  // namespace
}  // namespace daep::mapping
