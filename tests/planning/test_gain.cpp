#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "PlanningTestUtil.h"
#include "daep/common/Error.h"
#include "daep/common/Types.h"
#include "daep/planning/GainEvaluator.h"

namespace daep::planning {
namespace {

using test::box;
using test::makeMap;

constexpr double kDeg = M_PI / 180.0;

/** Exact volume of the unobstructed view: range^3/3 * azimuth span * (cos phiMin - cos phiMax). */
double viewVolume(const GainEvaluator& g, double azimuthSpan) {
    const double r = g.params().range;
    return r * r * r / 3.0 * azimuthSpan * (std::cos(g.phiMin()) - std::cos(g.phiMax()));
}

double sum(const std::vector<double>& v) {
    double s = 0;
    for (double x : v)
        s += x;
    return s;
}

/** Calls f(a, b) for the cell centres a, b within +-halfCells cells of (a0, b0), a cell centre. */
template <class F>
void forCellGrid(double a0, double b0, int halfCells, F f) {
    for (int i = -halfCells; i <= halfCells; ++i) {
        for (int j = -halfCells; j <= halfCells; ++j)
            f(a0 + 0.2 * i, b0 + 0.2 * j);
    }
}

/** Scan origins along x = -0.1 whose rays run straight down -x: cells with x < 0 become free. */
void clearNegativeX(mapping::ExplorationMap& map, const Eigen::Vector3d& p) {
    forCellGrid(p.y(), p.z(), 28, [&](double y, double z) {
        map.insertPointCloud({-0.1, y, z}, {Eigen::Vector3f(-30.f, float(y), float(z))});
    });
}

TEST(GainEvaluator, ViewVolumeInUnknownMap) {
    auto map = makeMap(box(-8, -8, -8, 8, 8, 8));
    const GainEvaluator g{GainParams{}};
    const Eigen::Vector3d p(0.3, -0.2, 0.5);
    const double expected = viewVolume(g, g.params().hfov);
    EXPECT_NEAR(expected, 93.8, 0.5);  // the default camera's view, for orientation
    for (double yaw : {0.0, 0.3, 2.5, -3.0, M_PI}) {
        EXPECT_NEAR(g.gainAtYaw(*map, p, yaw), expected, 1e-9 * expected) << "yaw " << yaw;
    }
    EXPECT_NEAR(sum(g.columns(*map, p)), viewVolume(g, 2 * M_PI), 1e-9 * expected);
}

TEST(GainEvaluator, StepsThatDoNotDivideTheRangesStillTileThem) {
    auto map = makeMap(box(-8, -8, -8, 8, 8, 8));
    GainParams params;
    params.hfov = 60 * kDeg;
    params.vfov = 50 * kDeg;
    params.dtheta = 7 * kDeg;
    params.dphi = 9 * kDeg;
    params.dr = 0.3;
    params.range = 4.0;
    const GainEvaluator g(params);
    EXPECT_EQ(g.columnCount(), 51);
    EXPECT_NEAR(g.phiMax() - g.phiMin(), params.vfov, 1e-12);
    const double expected = viewVolume(g, params.hfov);
    EXPECT_NEAR(g.gainAtYaw(*map, {0, 0, 0}, 1.0), expected, 1e-9 * expected);
}

TEST(GainEvaluator, HalfKnownSceneGivesHalfTheVolume) {
    auto map = makeMap(box(-8, -8, -8, 8, 8, 8), 6.0);
    const Eigen::Vector3d p(0.0, 0.1, 0.1);  // on the plane x = 0 between free and unknown
    clearNegativeX(*map, p);
    const GainEvaluator g{GainParams{}};
    const double full = viewVolume(g, 2 * M_PI);
    EXPECT_NEAR(sum(g.columns(*map, p)), 0.5 * full, 1e-9 * full);
    EXPECT_NEAR(g.gainAtYaw(*map, p, M_PI), 0.0, 1e-12);
    EXPECT_NEAR(g.gainAtYaw(*map, p, 0.0), viewVolume(g, g.params().hfov), 1e-9 * full);
    // Looking along the boundary: exactly half of the window lies on the unknown side.
    EXPECT_NEAR(g.gainAtYaw(*map, p, M_PI / 2), 0.5 * viewVolume(g, g.params().hfov), 1e-9 * full);
}

TEST(GainEvaluator, BestYawFacesTheUnknownSide) {
    auto map = makeMap(box(-8, -8, -8, 8, 8, 8), 6.0);
    const Eigen::Vector3d p(0.0, 0.1, 0.1);
    clearNegativeX(*map, p);
    const GainEvaluator g{GainParams{}};
    const YawGain best = g.bestYaw(*map, p);
    // Any yaw whose window lies wholly in x > 0 is optimal: |yaw| <= 90 - hfov/2.
    EXPECT_LE(std::abs(best.yaw), (90.0 - 51.6) * kDeg + 1e-9);
    EXPECT_NEAR(best.gain, viewVolume(g, g.params().hfov), 1e-6);
    EXPECT_NEAR(best.gain, g.gainAtYaw(*map, p, best.yaw), 1e-9);
}

TEST(GainEvaluator, BestYawRotatesWithTheUnknownSide) {
    // Only +y is unknown: the slab y < 0 is cleared by rays running down -y.
    auto map = makeMap(box(-8, -8, -8, 8, 8, 8), 6.0);
    forCellGrid(0.1, 0.1, 28, [&](double x, double z) {
        map->insertPointCloud({x, -0.1, z}, {Eigen::Vector3f(float(x), -30.f, float(z))});
    });
    const GainEvaluator g{GainParams{}};
    const YawGain best = g.bestYaw(*map, {0.1, 0.0, 0.1});
    EXPECT_GT(std::sin(best.yaw), std::sin(51.0 * kDeg));
}

TEST(GainEvaluator, OccupiedWallBlocksTheRaysBehindIt) {
    auto map = makeMap(box(-8, -8, -8, 8, 8, 8));
    const Eigen::Vector3d p(0.1, 0.1, 0.1);
    // A wall occupying the cells 2.0 <= x < 2.2, seen from behind so that x < 2 stays unknown.
    forCellGrid(0.1, 0.1, 27, [&](double y, double z) {
        map->insertPointCloud({2.5, y, z}, {Eigen::Vector3f(2.1f, float(y), float(z))});
    });
    ASSERT_TRUE(map->isOccupied({2.1, 0.1, 0.1}));
    ASSERT_TRUE(map->isUnknown({1.9, 0.1, 0.1}));

    const GainEvaluator g{GainParams{}};
    const double half = 0.5 * g.params().hfov;
    // Fine numerical integral of the view clipped by the plane x = 2 (measured from p).
    double clipped = 0.0;
    const double step = 0.1 * kDeg;
    for (double th = -half + step / 2; th < half; th += step) {
        for (double ph = g.phiMin() + step / 2; ph < g.phiMax(); ph += step) {
            const double dx = std::sin(ph) * std::cos(th);
            const double r = std::min(g.params().range, (2.0 - p.x()) / dx);
            clipped += r * r * r / 3.0 * std::sin(ph) * step * step;
        }
    }
    const double blocked = g.gainAtYaw(*map, p, 0.0);
    EXPECT_NEAR(blocked, clipped, 0.05 * clipped);
    EXPECT_LT(blocked, 0.2 * viewVolume(g, g.params().hfov));
    // The opposite view is untouched.
    EXPECT_NEAR(g.gainAtYaw(*map, p, M_PI), viewVolume(g, g.params().hfov), 1e-6);
}

TEST(GainEvaluator, RaysStopAtTheExplorationBox) {
    // p 1 m from the +x face: the view toward +x only holds the part inside the box.
    auto map = makeMap(box(-8, -8, -8, 1.1, 8, 8));
    const GainEvaluator g{GainParams{}};
    const Eigen::Vector3d p(0.1, 0.1, 0.1);
    const double inside = g.gainAtYaw(*map, p, 0.0);
    EXPECT_GT(inside, 0.0);
    EXPECT_LT(inside, 0.1 * viewVolume(g, g.params().hfov));
    EXPECT_EQ(g.gainAtYaw(*map, {2.0, 0.0, 0.0}, 0.0), 0.0);  // outside the box
}

TEST(GainEvaluator, WindowOverColumnsMatchesDirectEvaluation) {
    auto map = makeMap(box(-8, -8, -8, 8, 8, 8));
    const Aabb room = box(-3, -2, -1, 4, 3, 2);
    map->insertPointCloud({0.5, 0.5, 0.5}, test::roomScan(room, {0.5, 0.5, 0.5}, 2.0, 40.0));
    const GainEvaluator g{GainParams{}};
    const Eigen::Vector3d p(1.3, -0.4, 0.2);
    const std::vector<double> cols = g.columns(*map, p);
    for (double yaw = -M_PI; yaw < M_PI; yaw += 0.37) {
        EXPECT_NEAR(g.windowGain(cols, yaw), g.gainAtYaw(*map, p, yaw), 1e-9) << yaw;
    }
    const YawGain best = g.bestYaw(cols);
    for (int deg = -179; deg <= 180; ++deg) {
        EXPECT_LE(g.windowGain(cols, deg * kDeg), best.gain + 1e-12);
    }
}

/**
 * One ray along x, from x = `from` to `to`, through the middle of each cell row of the
 * section y in [-0.3, 4.4), z in [-0.3, zEnd) that `keep(y)` accepts: a 4 m wide box and the
 * dense grid's margin beside it. A row's ray changes no cell of another row.
 */
template <class Keep>
void raysAlongX(mapping::ExplorationMap& map, double from, double to, double zEnd,
                const Keep& keep) {
    for (double y = -0.3; y < 4.4; y += 0.2)
        for (double z = -0.3; z < zEnd; z += 0.2)
            if (keep(y))
                map.insertPointCloud({from, y, z},
                                     {Eigen::Vector3f(float(to), float(y), float(z))});
}

void raysAlongX(mapping::ExplorationMap& map, double from, double to, double zEnd) {
    raysAlongX(map, from, to, zEnd, [](double) { return true; });
}

/**
 * Box 0..16 x 0..4 x 0..2 (and the dense grid around it) known free west of x = 8, with a
 * wall in the layer at x = 8.0-8.2 and the unknown behind it; through an opening where y >= 2,
 * known free out to x = 10, unknown beyond.
 */
std::unique_ptr<mapping::ExplorationMap> wallAndOpening(bool opening = true) {
    auto map = makeMap(box(0, 0, 0, 16, 4, 2), 15.0);
    const auto walled = [opening](double y) { return y < 2.0 || !opening; };
    raysAlongX(*map, 7.9, -100.0, 2.4, walled);
    raysAlongX(*map, 7.9, 8.1, 2.4, walled);
    raysAlongX(*map, 9.9, -100.0, 2.4, [&](double y) { return !walled(y); });
    return map;
}

/** What expectSameGainsAsTheMarch met. */
struct SkipCounts {
    int noUnknownInReach = 0;  ///< points where mayMeetUnknown is false
    int seeing = 0;            ///< (point, yaw) pairs whose march saw unknown volume
};

/**
 * columns() answers 0 without marching where no ray can meet an unknown cell
 * (mayMeetUnknown); gainAtYaw marches every column. They must agree bit for bit at each point.
 */
SkipCounts expectSameGainsAsTheMarch(const mapping::ExplorationMap& map, const GainEvaluator& g,
                                     const std::vector<Eigen::Vector3d>& points) {
    SkipCounts counts;
    for (const Eigen::Vector3d& p : points) {
        counts.noUnknownInReach += !map.mayMeetUnknown(p, g.params().range);
        const std::vector<double> columns = g.columns(map, p);
        for (double yaw : {0.0, 1.2, 2.9, -2.0}) {
            const double marched = g.gainAtYaw(map, p, yaw);
            counts.seeing += marched > 0.0;
            EXPECT_EQ(g.windowGain(columns, yaw), marched) << p.transpose() << " yaw " << yaw;
        }
    }
    return counts;
}

TEST(GainEvaluator, SkippedMarchesKeepEveryViewAroundAWallAndAnOpening) {
    // Far from the unknown, before the wall, at the opening and deep in the unknown.
    const auto map = wallAndOpening();
    GainParams params;
    params.range = 1.0;
    std::vector<Eigen::Vector3d> points;
    for (double x = 0.3; x < 16.0; x += 0.35)
        for (double y = 0.3; y < 3.8; y += 0.35)
            for (double z : {0.5, 1.0, 1.5})
                points.emplace_back(x, y, z);
    const SkipCounts counts = expectSameGainsAsTheMarch(*map, GainEvaluator{params}, points);
    EXPECT_GT(counts.noUnknownInReach, 300);
    EXPECT_GT(counts.seeing, 300);
}

TEST(GainEvaluator, AFrontierNearTheEndOfTheRangeIsSeen) {
    // Box 0..16 x 0..4 x 0..2 known east of x = 7, unknown west of it: the frontier cells
    // (6.8-7.0) are the last of their blocks. The default 5 m range, from where the rays west
    // see the unknown to their last samples.
    auto map = makeMap(box(0, 0, 0, 16, 4, 2), 15.0);
    raysAlongX(*map, 7.1, 16.1, 2.4);
    std::vector<Eigen::Vector3d> points;
    for (double x = 7.5; x < 15.5; x += 0.1)
        points.emplace_back(x, 2.0, 1.0);
    const SkipCounts counts = expectSameGainsAsTheMarch(*map, GainEvaluator{GainParams{}}, points);
    EXPECT_GT(counts.noUnknownInReach, 5);
    EXPECT_GT(counts.seeing, 40);
}

TEST(GainEvaluator, ViewsSkippedInAClutteredMapAgreeWithTheMarch) {
    // Short random rays leave every arrangement of free, occupied and unknown cells, diagonal
    // steps from free into the unknown among them.
    auto map = makeMap(box(0, 0, 0, 6, 6, 2), 1.5);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> x(0.0, 6.0), z(0.0, 2.0), step(-2.5, 2.5);
    const auto inBox = [&] {  // drawn in this order whatever the compiler's argument order
        const double px = x(rng), py = x(rng);
        return Eigen::Vector3d(px, py, z(rng));
    };
    for (int frame = 0; frame < 250; ++frame) {
        const Eigen::Vector3d eye = inBox();
        std::vector<Eigen::Vector3f> ends;
        for (int k = 0; k < 60; ++k) {
            const double dx = step(rng), dy = step(rng), dz = step(rng);
            ends.push_back((eye + Eigen::Vector3d(dx, dy, dz)).cast<float>());
        }
        map->insertPointCloud(eye, ends);
    }
    GainParams params;
    params.range = 0.6;
    std::vector<Eigen::Vector3d> points;
    for (int k = 0; k < 3000; ++k)
        points.push_back(inBox());
    const SkipCounts counts = expectSameGainsAsTheMarch(*map, GainEvaluator{params}, points);
    EXPECT_GT(counts.noUnknownInReach, 100);
    EXPECT_GT(counts.seeing, 100);
}

TEST(GainEvaluator, RaysWhoseStepsSkipCellsAreAlwaysMarched) {
    // Steps of 0.45 m jump the wall's 0.2 m layer into the unknown behind it, where no free
    // cell is beside an unknown one: the march sees it, so columns() must march too.
    const auto map = wallAndOpening(false);
    GainParams params;
    params.range = 1.0;
    params.dr = 0.45;
    std::vector<Eigen::Vector3d> points;
    for (double x = 6.0; x < 8.0; x += 0.05)
        points.emplace_back(x, 1.0, 1.0);
    const SkipCounts counts = expectSameGainsAsTheMarch(*map, GainEvaluator{params}, points);
    EXPECT_GT(counts.noUnknownInReach, 10);
    EXPECT_GT(counts.seeing, 10);
}

TEST(GainEvaluator, AnUnknownCellReachedOnlyAcrossItsEdgesCountsAsSeen) {
    // Every cell of the dense grid known free, one by one (a ray cut at 15 cm from a cell's
    // centre clears that cell only), but for an unknown cell whose six face neighbours are
    // occupied: rays reach it only from free cells beside its edges and corners, which must make it
    // a frontier cell.
    auto map = makeMap(box(0, 0, 0, 2, 2, 2), 0.15);
    const Eigen::Vector3i unknown(10, 10, 10);  // the grid starts 1 m out: the cell at 1.1 m
    const auto centre = [](const Eigen::Vector3i& c) {
        return Eigen::Vector3d(-0.9 + 0.2 * c.x(), -0.9 + 0.2 * c.y(), -0.9 + 0.2 * c.z());
    };
    for (int cz = 0; cz < 20; ++cz)
        for (int cy = 0; cy < 20; ++cy)
            for (int cx = 0; cx < 20; ++cx) {
                const Eigen::Vector3i c(cx, cy, cz);
                const int away = (c - unknown).cwiseAbs().sum();
                const Eigen::Vector3d o = centre(c);
                if (away == 1)
                    map->insertPointCloud(o, {o.cast<float>()});
                else if (away > 1)
                    map->insertPointCloud(
                        o, {Eigen::Vector3f(float(o.x()) + 9.f, float(o.y()), float(o.z()))});
            }
    ASSERT_TRUE(map->isUnknown(centre(unknown)));
    ASSERT_TRUE(map->isOccupied(centre(unknown + Eigen::Vector3i(1, 0, 0))));
    ASSERT_TRUE(map->isFree(centre(unknown + Eigen::Vector3i(1, 1, 0))));
    GainParams params;
    params.range = 1.0;
    // On the diagonal through the cell's lower vertical edge, so that the rays along the 45
    // degree column step from the free cell behind the edge straight into the unknown one.
    std::vector<Eigen::Vector3d> points;
    const Eigen::Vector3d edge = centre(unknown) - Eigen::Vector3d(0.1, 0.1, 0.0);
    for (double s = 0.3; s < 0.95; s += 0.01)  // two cells or more away: no unknown beside p
        points.push_back(edge - s * Eigen::Vector3d(M_SQRT1_2, M_SQRT1_2, 0.0));
    const SkipCounts counts = expectSameGainsAsTheMarch(*map, GainEvaluator{params}, points);
    EXPECT_GT(counts.seeing, 20) << counts.seeing;
}

/** Box 0..8 x 0..4 x 0..4.1: its top cells (4.0-4.2) reach above it and stay unknown. */
TEST(GainEvaluator, UnknownCellsTheBoxCutsThroughCountAsSeen) {
    auto map = makeMap(box(0, 0, 0, 8, 4, 4.1), 15.0);
    raysAlongX(*map, 9.9, -100.0, 4.0);
    GainParams params;
    params.range = 1.0;
    std::vector<Eigen::Vector3d> points;
    for (double x = 0.3; x < 8.0; x += 0.5)
        for (double z = 0.1; z < 4.1; z += 0.1)
            points.emplace_back(x, 2.0, z);
    const SkipCounts counts = expectSameGainsAsTheMarch(*map, GainEvaluator{params}, points);
    EXPECT_GT(counts.noUnknownInReach, 50);
    EXPECT_GT(counts.seeing, 50);
}

TEST(GainParams, ReadsDegreesAndRejectsBadValues) {
    const std::string text = test::defaultsText();
    const GainParams p = GainParams::fromConfig(*test::configFromText(text));
    EXPECT_NEAR(p.hfov, 103.2 * kDeg, 1e-12);
    EXPECT_NEAR(p.dphi, 10 * kDeg, 1e-12);
    EXPECT_DOUBLE_EQ(p.range, 5.0);

    const std::string negative = "-0.2";
    try {
        GainParams::fromConfig(*test::configFromText(test::editKey(text, "gain", "dr", &negative)));
        FAIL() << "negative dr accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("[gain] dr"), std::string::npos) << e.what();
    }
    try {
        GainParams::fromConfig(*test::configFromText(test::editKey(text, "gain", "hfov_deg")));
        FAIL() << "missing hfov_deg accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("[gain] hfov_deg"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace daep::planning
