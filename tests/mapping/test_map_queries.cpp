#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "DepthFrames.h"
#include "MapTestUtils.h"
#include "daep/common/Geometry.h"
#include "daep/mapping/ExplorationMap.h"

namespace daep::mapping {
namespace {

using test::cellCentre;

constexpr double kRes = 0.2;

/** A map whose cells x 0..19, y 0..9, z 0..4 are free, i.e. [0, 4] x [0, 2] x [0, 1]. */
class FreeBlockMap : public ::testing::Test {
protected:
    FreeBlockMap() : map_(params(), box()) {
        for (int z = 0; z < 5; ++z) {
            for (int y = 0; y < 10; ++y) {
                test::freeRow(map_, {0, y, z});
            }
        }
    }
    static MapParams params() {
        MapParams p;
        p.maxRange = 20 * kRes;
        return p;
    }
    static Aabb box() {
        Aabb b;
        b.min = {-1, -1, -1};
        b.max = {5, 3, 2};
        return b;
    }
    ExplorationMap map_;
};

/** A cell a ray ended in once, then seen through along its row: free, with the hit kept. */
void hitThenSeeThrough(ExplorationMap& map, const Eigen::Vector3i& cell) {
    test::occupy(map, cellCentre(cell, kRes));
    for (int i = 0; i < 6; ++i)
        test::freeRow(map, {0, cell.y(), cell.z()});
}

TEST_F(FreeBlockMap, BlockIsFreeAndSurroundingsUnknown) {
    EXPECT_TRUE(map_.isFree(cellCentre({0, 0, 0}, kRes)));
    EXPECT_TRUE(map_.isFree(cellCentre({19, 9, 4}, kRes)));
    EXPECT_TRUE(map_.isUnknown(cellCentre({20, 9, 4}, kRes)));
    EXPECT_TRUE(map_.isUnknown(cellCentre({-1, 0, 0}, kRes)));
}

TEST_F(FreeBlockMap, IsBoxFree) {
    EXPECT_TRUE(map_.isBoxFree({2.0, 1.0, 0.5}, {0.3, 0.3, 0.3}));
    EXPECT_TRUE(map_.isBoxFree({2.0, 1.0, 0.5}, {1.95, 0.95, 0.45}));
    // Touches the unknown cells beyond the block.
    EXPECT_FALSE(map_.isBoxFree({2.0, 1.0, 0.5}, {2.05, 0.95, 0.45}));
    EXPECT_FALSE(map_.isBoxFree({0.05, 1.0, 0.5}, {0.1, 0.1, 0.1}));
    test::occupy(map_, cellCentre({10, 5, 2}, kRes));  // [2.0, 2.2] x [1.0, 1.2] x [0.4, 0.6]
    EXPECT_FALSE(map_.isBoxFree({2.1, 1.1, 0.5}, {0.01, 0.01, 0.01}));
    EXPECT_FALSE(map_.isBoxFree({1.7, 1.1, 0.5}, {0.31, 0.01, 0.01}));
    EXPECT_TRUE(map_.isBoxFree({1.7, 1.1, 0.5}, {0.29, 0.01, 0.01}));
}

TEST_F(FreeBlockMap, GrazedSurfaceBesideAnOccupiedCellBlocksTheCapsule) {
    // A thin surface reaching a few cm into cell A from the occupied cell B beside it: rays
    // ended in A once, then rays through A's free part cleared it.
    const Eigen::Vector3i a(10, 4, 2), b(10, 5, 2);  // A: y in [0.8, 1.0], B: [1.0, 1.2]
    for (int i = 0; i < 3; ++i)
        test::occupy(map_, cellCentre(b, kRes));
    hitThenSeeThrough(map_, a);
    ASSERT_TRUE(map_.isFree(cellCentre(a, kRes)));
    ASSERT_TRUE(map_.isOccupied(cellCentre(b, kRes)));
    // The capsule comes within 0.25 m of A and 0.45 m of B.
    const Eigen::Vector3d from(1.9, 0.55, 0.5), to(2.3, 0.55, 0.5);
    EXPECT_FALSE(map_.isSegmentFree(from, to, 0.3));
    EXPECT_FALSE(map_.isSegmentFreeOrUnknown(from, to, 0.3));
    // Where people enter the map, a cell a person stood in beside a wall looks the same: the
    // guard is off there.
    map_.setPeopleMapped(true);
    EXPECT_TRUE(map_.isSegmentFree(from, to, 0.3));
    map_.setPeopleMapped(false);
    // Beside an occupied cell, a free cell no ray ended in is free.
    const Eigen::Vector3d left(-1.4, 0, 0);  // the same capsule over cells x 3 and 4
    for (int i = 0; i < 3; ++i)
        test::occupy(map_, cellCentre({3, 5, 2}, kRes));
    EXPECT_TRUE(map_.isSegmentFree(from + left, to + left, 0.3));
    // Once B is seen through (a person who walked on), A is free space again.
    for (int i = 0; i < 12; ++i)
        test::freeRow(map_, {0, b.y(), b.z()});
    ASSERT_TRUE(map_.isFree(cellCentre(b, kRes)));
    EXPECT_TRUE(map_.isSegmentFree(from, to, 0.3));
}

/** A, hit once (a walker passing), then seen through, beside B, occupied: a grazed surface. */
class GrazedCellMap : public FreeBlockMap {
protected:
    GrazedCellMap() {
        for (int i = 0; i < 3; ++i)
            test::occupy(map_, cellCentre(b, kRes));
        hitThenSeeThrough(map_, a);
    }
    const Eigen::Vector3i a{10, 4, 2}, b{10, 5, 2};
    const Eigen::Vector3d inA = cellCentre(a, kRes) + Eigen::Vector3d(0.03, -0.05, 0.02);
};

TEST_F(GrazedCellMap, ACellTheDroneHasBeenInIsNoGrazedSurface) {
    // Until the drone's centre is in A. A wall reaching into A would be inside the drone.
    EXPECT_FALSE(map_.isSegmentFreeOrUnknown(inA, inA, 0.0));
    EXPECT_FALSE(map_.isSegmentFree(inA + Eigen::Vector3d(-1, -0.1, 0), inA, 0.05));
    map_.markFlown(inA);
    EXPECT_TRUE(map_.isSegmentFreeOrUnknown(inA, inA, 0.0));
    EXPECT_TRUE(map_.isSegmentFree(inA + Eigen::Vector3d(-1, -0.1, 0), inA, 0.05));
    // B itself stays what it is.
    EXPECT_FALSE(map_.isSegmentFree(cellCentre(b, kRes), cellCentre(b, kRes), 0.0));
}

TEST_F(GrazedCellMap, AFrameTakenFromACellMakesItNoGrazedSurface) {
    // A frame taken with the drone's centre in A, looking away from B (-y) at nothing:
    // inserting it is what tells the map the drone has been in A.
    ASSERT_FALSE(map_.isSegmentFreeOrUnknown(inA, inA, 0.0));
    FlatPose drone;
    drone.position = inA;
    drone.yaw = -M_PI / 2;
    map_.insertObservation(test::depthFrame(4, 4, 0.0), drone);
    ASSERT_TRUE(map_.isOccupied(cellCentre(b, kRes)));
    EXPECT_TRUE(map_.isSegmentFreeOrUnknown(inA, inA, 0.0));
}

TEST_F(FreeBlockMap, ACapsuleAskedAgainSeesWhatChangedInItsRowsAndBesideThem) {
    // Each answer below follows one that passed over the same rows: what the map learnt of
    // those rows must not outlive a change in them or in the rows beside them.
    const Eigen::Vector3d from(1.9, 0.55, 0.5), to(2.3, 0.55, 0.5);  // rows y 1..4 within 0.3
    ASSERT_TRUE(map_.isSegmentFree(from, to, 0.3));
    test::occupy(map_, cellCentre({11, 3, 2}, kRes));  // on the segment's row band
    EXPECT_FALSE(map_.isSegmentFree(from, to, 0.3));
    for (int i = 0; i < 6; ++i)
        test::freeRow(map_, {0, 3, 2});
    ASSERT_TRUE(map_.isSegmentFree(from, to, 0.3));
    // A, hit once then seen through, is free; it becomes a grazed surface when B beside it
    // (out of the capsule's reach) turns occupied.
    const auto grazedOnceBesideFills = [&](const Eigen::Vector3i& a, const Eigen::Vector3i& b,
                                           const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
        hitThenSeeThrough(map_, a);
        ASSERT_TRUE(map_.isSegmentFree(p, q, 0.3));
        for (int i = 0; i < 3; ++i)
            test::occupy(map_, cellCentre(b, kRes));
        EXPECT_FALSE(map_.isSegmentFree(p, q, 0.3));
    };
    // B in the next row: 0.25 m and 0.45 m from the capsule.
    grazedOnceBesideFills({10, 4, 2}, {10, 5, 2}, from, to);
    // B in the layer above A's row: 0.25 m and 0.45 m above the axis.
    grazedOnceBesideFills({10, 2, 3}, {10, 2, 4}, {1.9, 0.5, 0.35}, {2.3, 0.5, 0.35});
}

TEST_F(FreeBlockMap, GrazedWallFaceInFrontOfAnUnknownInsideBlocksTheCapsule) {
    // A wall's face 10 cm into cell A; the wall's inside (y index 10 on) was never seen: it
    // lies beyond the free block. A was hit once, then cleared by rays along the face.
    const Eigen::Vector3i a(10, 9, 2);  // A: y in [1.8, 2.0]
    hitThenSeeThrough(map_, a);
    ASSERT_TRUE(map_.isFree(cellCentre(a, kRes)));
    ASSERT_TRUE(map_.isUnknown(cellCentre({10, 10, 2}, kRes)));
    // The capsule comes within 0.25 m of A and 0.45 m of the unknown inside.
    const Eigen::Vector3d from(1.9, 1.55, 0.5), to(2.3, 1.55, 0.5);
    EXPECT_FALSE(map_.isSegmentFree(from, to, 0.3));
    EXPECT_FALSE(map_.isSegmentFreeOrUnknown(from, to, 0.3));
    // The same capsule beside a face cell no ray ended in passes.
    const Eigen::Vector3d left(-1.4, 0, 0);
    EXPECT_TRUE(map_.isSegmentFree(from + left, to + left, 0.3));
}

TEST_F(FreeBlockMap, SweptBoxMeetsOnlyNewOccupiedCells) {
    // Cell [2.0, 2.2] x [1.4, 1.6] x [0.4, 0.6] beside the way; the box is 0.6 x 0.6 x 0.1.
    const Eigen::Vector3d half(0.3, 0.3, 0.05);
    const Eigen::Vector3d a(0.5, 1.0, 0.5), b(3.5, 1.0, 0.5);
    EXPECT_TRUE(map_.isSweptBoxClearOfNew(a, b, half));
    test::occupy(map_, cellCentre({10, 7, 2}, kRes));
    EXPECT_TRUE(map_.isSweptBoxClearOfNew(a, b, {0.39, 0.39, 0.05}));
    EXPECT_FALSE(map_.isSweptBoxClearOfNew(a, b, {0.41, 0.41, 0.05}));
    // Above it by 0.15 m: the box's half height decides, not its half width.
    const Eigen::Vector3d up(0, 0.5, 0.25);
    EXPECT_TRUE(map_.isSweptBoxClearOfNew(a + up, b + up, {0.3, 0.3, 0.14}));
    EXPECT_FALSE(map_.isSweptBoxClearOfNew(a + up, b + up, {0.3, 0.3, 0.16}));
    // A cell the box already meets where it starts does not count, wherever the move goes.
    const Eigen::Vector3d beside(2.1, 1.2, 0.5);
    EXPECT_TRUE(map_.isSweptBoxClearOfNew(beside, {2.1, 1.3, 0.5}, half));
    EXPECT_TRUE(map_.isSweptBoxClearOfNew(beside, b, half));
    // Unknown space is no obstacle; outside the map's bounds is.
    EXPECT_TRUE(map_.isSweptBoxClearOfNew(a, {0.5, -0.5, 0.5}, half));
    EXPECT_FALSE(map_.isSweptBoxClearOfNew(a, {0.5, 1.0, 1e6}, half));
}

TEST_F(FreeBlockMap, SegmentAgainstHandPlacedObstacle) {
    const Eigen::Vector3d a(0.5, 1.0, 0.5), b(3.5, 1.0, 0.5);
    EXPECT_TRUE(map_.isSegmentFree(a, b, 0.3));
    EXPECT_TRUE(map_.isSegmentFreeOrUnknown(a, b, 0.3));
    // The radius reaches the unknown cells outside the block (y < 0): only isSegmentFree fails.
    EXPECT_FALSE(map_.isSegmentFree(a, b, 1.05));
    EXPECT_TRUE(map_.isSegmentFreeOrUnknown(a, b, 1.05));

    // Obstacle cell [2.0, 2.2] x [1.4, 1.6] x [0.4, 0.6]: its box is 0.4 from the segment,
    // its centre 0.5.
    test::occupy(map_, cellCentre({10, 7, 2}, kRes));
    EXPECT_TRUE(map_.isSegmentFree(a, b, 0.39));
    EXPECT_FALSE(map_.isSegmentFree(a, b, 0.41));
    EXPECT_TRUE(map_.isSegmentFreeOrUnknown(a, b, 0.39));
    EXPECT_FALSE(map_.isSegmentFreeOrUnknown(a, b, 0.41));
    // A segment ending before the obstacle: distance from the end point to the box corner.
    const Eigen::Vector3d start(1.0, 1.0, 0.5), end(1.7, 1.0, 0.5);  // edge x=2.0, y=1.4
    EXPECT_TRUE(map_.isSegmentFree(start, end, 0.49));
    EXPECT_FALSE(map_.isSegmentFree(start, end, 0.51));
    // Degenerate segment: a sphere.
    EXPECT_TRUE(map_.isSegmentFree(end, end, 0.49));
    EXPECT_FALSE(map_.isSegmentFree(end, end, 0.51));
}

TEST_F(FreeBlockMap, CastRayStraight) {
    test::occupy(map_, cellCentre({15, 3, 2}, kRes));  // x in [3.0, 3.2)
    const Eigen::Vector3d o(0.5, 0.7, 0.5);
    EXPECT_NEAR(map_.castRay(o, {1, 0, 0}, 10.0), 2.5, 1e-9);
    EXPECT_NEAR(map_.castRay(o, {1, 0, 0}, 2.0), 2.0, 1e-12);
    EXPECT_NEAR(map_.castRay(o, {-1, 0, 0}, 10.0), 10.0, 1e-12);  // unknown does not stop it
    EXPECT_NEAR(map_.castRay({3.3, 0.7, 0.5}, {-1, 0, 0}, 10.0), 0.1, 1e-9);
    EXPECT_NEAR(map_.castRay({3.1, 0.7, 0.5}, {0, 1, 0}, 10.0), 0.0, 1e-12);  // starts inside
}

/** Cells with any state set, and a few occupied ones, in a free block with unknown holes. */
class RandomMap : public ::testing::Test {
protected:
    RandomMap() : map_(params(), box()) {
        std::mt19937 rng(2024);
        std::uniform_int_distribution<int> cx(0, 29), cy(0, 19), cz(0, 9);
        for (int z = 0; z < 10; ++z) {
            for (int y = 0; y < 20; ++y) {
                if ((y * 7 + z * 3) % 23 != 0) {  // leave some rows unknown
                    test::freeRow(map_, {0, y, z});
                }
            }
        }
        for (int i = 0; i < 25; ++i) {
            test::occupy(map_, cellCentre({cx(rng), cy(rng), cz(rng)}, kRes));  // braces: in order
        }
    }
    static MapParams params() {
        MapParams p;
        p.maxRange = 30 * kRes;
        return p;
    }
    static Aabb box() {
        Aabb b;
        b.min = {0, 0, 0};
        b.max = {6, 4, 2};
        return b;
    }
    ExplorationMap map_;
};

/**
 * Segment-to-cell-box distance by ternary search: the distance from a point moving along a
 * segment to a convex box is convex in the segment parameter.
 */
double searchedBoxDistance(const Eigen::Vector3d& lo, const Eigen::Vector3d& a,
                           const Eigen::Vector3d& b) {
    const auto dist = [&](double t) {
        const Eigen::Vector3d p = a + (b - a) * t;
        return (p - p.cwiseMax(lo).cwiseMin((lo.array() + kRes).matrix())).norm();
    };
    double l = 0.0, h = 1.0;
    for (int i = 0; i < 100; ++i) {
        const double m1 = l + (h - l) / 3.0, m2 = h - (h - l) / 3.0;
        if (dist(m1) < dist(m2)) {
            h = m2;
        } else {
            l = m1;
        }
    }
    return dist(0.5 * (l + h));
}

struct Blockers {
    bool centreWithinR = false;  ///< a blocking cell has its centre within r
    bool boxWithinR = false;     ///< a blocking cell's box is within r
};

template <typename Blocks>
Blockers bruteForce(const ExplorationMap& map, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                    double r, Blocks blocks) {
    Blockers out;
    for (int z = -8; z < 20; ++z) {
        for (int y = -8; y < 30; ++y) {
            for (int x = -8; x < 40; ++x) {
                const Eigen::Vector3d c = cellCentre({x, y, z}, kRes);
                if (!blocks(map.state(c)) ||
                    distanceToSegment(c, a, b) > r + 0.5 * std::sqrt(3.0) * kRes) {
                    continue;
                }
                out.centreWithinR |= distanceToSegment(c, a, b) <= r;
                out.boxWithinR |= searchedBoxDistance(c.array() - 0.5 * kRes, a, b) <= r;
            }
        }
    }
    return out;
}

TEST_F(RandomMap, SegmentQueriesNeverMissABlockingCell) {
    std::mt19937 rng(31337);
    std::uniform_real_distribution<double> ux(-0.5, 6.5), uy(-0.5, 4.5), uz(-0.3, 2.3);
    std::uniform_real_distribution<double> ur(0.0, 0.6);
    int freeAnswers = 0, blockedAnswers = 0;
    for (int i = 0; i < 400; ++i) {
        const double shrink = i % 2 == 0 ? 1.0 : 0.6;
        const auto sample = [&]() -> Eigen::Vector3d {
            const Eigen::Vector3d p(ux(rng), uy(rng), uz(rng));
            return Eigen::Vector3d(3.0, 2.0, 1.0) + shrink * (p - Eigen::Vector3d(3.0, 2.0, 1.0));
        };
        const Eigen::Vector3d a = sample();
        Eigen::Vector3d b = sample();
        if (i % 3 == 0) {
            b = a + (b - a) * 0.15;  // short segments too
        }
        const double r = shrink * ur(rng);
        const bool segFree = map_.isSegmentFree(a, b, r);
        const Blockers notFree =
            bruteForce(map_, a, b, r, [](CellState s) { return s != CellState::Free; });
        ASSERT_FALSE(segFree && notFree.centreWithinR) << a.transpose() << " | " << b.transpose();
        ASSERT_EQ(segFree, !notFree.boxWithinR) << a.transpose() << " | " << b.transpose();

        const bool orUnknown = map_.isSegmentFreeOrUnknown(a, b, r);
        const Blockers occupied =
            bruteForce(map_, a, b, r, [](CellState s) { return s == CellState::Occupied; });
        ASSERT_FALSE(orUnknown && occupied.centreWithinR);
        ASSERT_EQ(orUnknown, !occupied.boxWithinR) << a.transpose() << " | " << b.transpose();
        freeAnswers += segFree;
        blockedAnswers += !orUnknown;
    }
    EXPECT_GT(freeAnswers, 10);  // both outcomes were exercised
    EXPECT_GT(blockedAnswers, 10);
}

TEST(SegmentQueries, AnswersKeepUpWithTheMapTheyWereAskedOfBefore) {
    // Two maps given the same frames; one is asked between frames (what it learns of its rows
    // must follow every change, grazed surfaces included), the other only at the end.
    MapParams params;
    params.maxRange = 3.0;
    Aabb box;
    box.min = {0, 0, 0};
    box.max = {6, 4, 2};
    ExplorationMap asked(params, box), fresh(params, box);
    std::mt19937 rng(77);
    std::uniform_real_distribution<double> ux(0.0, 6.0), uy(0.0, 4.0), uz(0.0, 2.0), ur(0.0, 0.5);
    const auto point = [&] { return Eigen::Vector3d(ux(rng), uy(rng), uz(rng)); };
    std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> segments;
    for (int i = 0; i < 300; ++i) {
        const Eigen::Vector3d a = point();
        segments.push_back({a, a + 0.3 * (point() - a)});
    }
    int blocked = 0, passed = 0;
    for (int frame = 0; frame < 40; ++frame) {
        const Eigen::Vector3d origin = point();
        std::vector<Eigen::Vector3f> hits;
        for (int i = 0; i < 200; ++i)  // end points in the box: walls, and later rays through
            hits.push_back(point().cast<float>());
        asked.insertPointCloud(origin, hits);
        fresh.insertPointCloud(origin, hits);
        for (int i = 0; i < 40; ++i) {
            const auto& [a, b] = segments[std::size_t((frame * 40 + i) % 300)];
            const bool free = asked.isSegmentFree(a, b, ur(rng));
            blocked += !free;
            passed += free;
        }
    }
    EXPECT_GT(blocked, 50);  // both answers were cached along the way
    EXPECT_GT(passed, 50);
    for (const double r : {0.0, 0.15, 0.3}) {
        for (const auto& [a, b] : segments) {
            ASSERT_EQ(asked.isSegmentFree(a, b, r), fresh.isSegmentFree(a, b, r))
                << a.transpose() << " | " << b.transpose() << " r " << r;
        }
    }
}

TEST_F(RandomMap, CastRayStopsAtEntryOfFirstOccupiedCell) {
    std::mt19937 rng(4242);
    std::uniform_real_distribution<double> ux(0.0, 6.0), uy(0.0, 4.0), uz(0.0, 2.0);
    std::normal_distribution<double> n(0.0, 1.0);
    int hits = 0;
    for (int i = 0; i < 500; ++i) {
        // Drawn z, y, x as g++ evaluates constructor arguments (right to left; clang goes left to
        // right): named, the rays are the same on every compiler.
        const double oz = uz(rng), oy = uy(rng), ox = ux(rng);
        const Eigen::Vector3d o(ox, oy, oz);
        if (map_.isOccupied(o)) {
            continue;
        }
        const double dz = 0.3 * n(rng), dy = n(rng), dx = n(rng);
        const Eigen::Vector3d dir = Eigen::Vector3d(dx, dy, dz).normalized();
        const double maxRange = 6.0;
        const double t = map_.castRay(o, dir, maxRange);
        ASSERT_GE(t, 0.0);
        ASSERT_LE(t, maxRange);
        // Nothing occupied strictly before t (fine sampling).
        for (double s = 0.0; s < t - 1e-6; s += 0.002) {
            ASSERT_FALSE(map_.isOccupied(o + s * dir)) << i << " at " << s << " of " << t;
        }
        ASSERT_FALSE(map_.isOccupied(o + (t - 1e-6) * dir));
        if (t < maxRange) {
            ASSERT_TRUE(map_.isOccupied(o + (t + 1e-6) * dir)) << i;
            ++hits;
        }
    }
    EXPECT_GT(hits, 20);
}

TEST_F(FreeBlockMap, FrontierViewpointsLieInTheBlockNearItsUnknownSurroundings) {
    const auto anywhere = [](const Eigen::Vector3d&) { return true; };
    const Eigen::Vector3d from(2.0, 1.0, 0.5);
    const std::vector<Eigen::Vector3d> views = map_.frontierViewpoints(from, anywhere, 1, 0.5, 8);
    ASSERT_EQ(views.size(), 8u);
    for (std::size_t i = 0; i < views.size(); ++i) {
        EXPECT_TRUE(map_.isFree(views[i])) << views[i].transpose();
        // An unknown cell one cell away: on the block's outer layer.
        const Eigen::Vector3d& v = views[i];
        const bool outer = v.x() < kRes || v.x() > 4 - kRes || v.y() < kRes || v.y() > 2 - kRes ||
                           v.z() < kRes || v.z() > 1 - kRes;
        EXPECT_TRUE(outer) << v.transpose();
        for (std::size_t j = 0; j < i; ++j)
            EXPECT_GE((views[i] - views[j]).norm(), 0.5);
    }
    // Nearest first: the first one is on the face nearest the start, 0.4 m below it.
    EXPECT_NEAR(views.front().z(), 0.1, 1e-9);
}

TEST_F(FreeBlockMap, FrontierViewpointsAreWhereTheDroneIsUsableAndSeesTheUnknownWithinReach) {
    // Usable: 0.5 m inside the block sideways, the layer of cells at z = 0.7.
    const auto inside = [](const Eigen::Vector3d& p) {
        return p.x() > 0.5 && p.x() < 3.5 && p.y() > 0.5 && p.y() < 1.5 && p.z() > 0.6 &&
               p.z() < 0.8;
    };
    const Eigen::Vector3d from(2.0, 1.0, 0.7);
    // The unknown above the block is two cells up from that layer.
    EXPECT_TRUE(map_.frontierViewpoints(from, inside, 1, 0.5, 8).empty());
    const std::vector<Eigen::Vector3d> views = map_.frontierViewpoints(from, inside, 2, 0.5, 8);
    ASSERT_FALSE(views.empty());
    for (const Eigen::Vector3d& v : views)
        EXPECT_TRUE(inside(v)) << v.transpose();
}

TEST_F(FreeBlockMap, NoFrontierViewpointFromWhereNoFreeCellLeads) {
    const auto anywhere = [](const Eigen::Vector3d&) { return true; };
    EXPECT_TRUE(map_.frontierViewpoints({-0.5, -0.5, -0.5}, anywhere, 5, 0.5, 8).empty());
    EXPECT_TRUE(map_.frontierViewpoints({40.0, 0.5, 0.5}, anywhere, 5, 0.5, 8).empty());
}

/** Usable except in a wall of cells across the block at x 1.8..2.2, open for y > 1.6. */
bool usableBesideTheWall(const Eigen::Vector3d& p, double doorFrom) {
    return p.x() < 1.8 || p.x() > 2.2 || p.y() > doorFrom;
}

TEST_F(FreeBlockMap, AFreeCellPathTakesTheFewestFaceStepsThroughTheDoorway) {
    const auto usable = [](const Eigen::Vector3d& p) { return usableBesideTheWall(p, 1.6); };
    const auto east = [](const Eigen::Vector3d& p) { return p.x() > 3.5; };
    const Eigen::Vector3d from(0.5, 0.5, 0.5);
    const std::vector<Eigen::Vector3d> path = map_.freeCellPath(from, usable, east);
    // Cell (2, 2, 2) to the nearest x >= 18 through y >= 8: 16 steps east, 6 north.
    ASSERT_EQ(path.size(), 1u + 16u + 6u);
    EXPECT_EQ(path.front(), from);
    EXPECT_TRUE(east(path.back()));
    bool throughTheDoor = false;
    for (std::size_t k = 1; k < path.size(); ++k) {
        EXPECT_TRUE(map_.isFree(path[k]) && usable(path[k])) << path[k].transpose();
        if (k > 1) {
            EXPECT_NEAR((path[k] - path[k - 1]).norm(), kRes, 1e-9) << k;
        }
        throughTheDoor = throughTheDoor || (std::abs(path[k].x() - 1.9) < 0.05);
    }
    EXPECT_TRUE(throughTheDoor);
}

TEST_F(FreeBlockMap, NoFreeCellPathWhenTheWallIsClosedOrNoCellIsAGoal) {
    const auto closed = [](const Eigen::Vector3d& p) { return usableBesideTheWall(p, 9.0); };
    const auto east = [](const Eigen::Vector3d& p) { return p.x() > 3.5; };
    EXPECT_TRUE(map_.freeCellPath({0.5, 0.5, 0.5}, closed, east).empty());
    const auto nowhere = [](const Eigen::Vector3d&) { return false; };
    const auto anywhere = [](const Eigen::Vector3d&) { return true; };
    EXPECT_TRUE(map_.freeCellPath({0.5, 0.5, 0.5}, anywhere, nowhere).empty());
    EXPECT_TRUE(map_.freeCellPath({40.0, 0.5, 0.5}, anywhere, anywhere).empty());
    // The start cell itself is never the goal: the nearest other one is.
    EXPECT_EQ(map_.freeCellPath({0.5, 0.5, 0.5}, anywhere, anywhere).size(), 2u);
}

/**
 * A corridor box 12 x 2 x 1 m whose cells and those around its sides are made free from
 * x = `knownFrom` to its east end (12 m, where the rays end on an occupied layer outside the
 * box); west of knownFrom it stays unknown, so its frontier cells lie at x = knownFrom.
 */
void seeCorridorFrom(ExplorationMap& map, double knownFrom) {
    for (double y = -0.3; y < 2.4; y += kRes)
        for (double z = -0.3; z < 1.4; z += kRes)
            map.insertPointCloud({knownFrom + 0.1, y, z},
                                 {Eigen::Vector3f(12.1f, float(y), float(z))});
}

ExplorationMap corridorMap() {
    MapParams p;
    p.maxRange = 15.0;
    Aabb b;
    b.min = {0, 0, 0};
    b.max = {12, 2, 1};
    return ExplorationMap(p, b);
}

TEST(MayMeetUnknown, OnlyWithinRangeOfAFrontierCellOrBesideAnUnknownOne) {
    ExplorationMap map = corridorMap();
    const Eigen::Vector3d east(10.1, 1.1, 0.5), middle(3.1, 1.1, 0.5);
    EXPECT_TRUE(map.mayMeetUnknown(east, 5.0));  // all unknown
    seeCorridorFrom(map, 7.0);  // its frontier cells (6.8-7.0) are the last of their blocks
    EXPECT_TRUE(map.mayMeetUnknown(east, 5.0));               // the frontier 3 m west
    EXPECT_FALSE(map.mayMeetUnknown(east, 2.0));              // beyond a 2 m march
    EXPECT_TRUE(map.mayMeetUnknown(middle, 0.05));            // in the unknown: its first sample
    EXPECT_TRUE(map.mayMeetUnknown({40.0, 1.1, 0.5}, 0.05));  // off the grid: unsure
    EXPECT_TRUE(map.mayMeetUnknown({12.5, 1.1, 0.5}, 0.05));  // off the box: unsure
    // Known further west, the blocks that held the frontier are asked again.
    seeCorridorFrom(map, 0.0);
    EXPECT_FALSE(map.mayMeetUnknown(east, 5.0));
    EXPECT_FALSE(map.mayMeetUnknown(middle, 0.05));
    EXPECT_TRUE(map.mayMeetUnknown(middle, 5.0));  // the west end's face, 3 m away
}

}  // namespace
}  // namespace daep::mapping
