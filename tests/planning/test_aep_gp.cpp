#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "daep/planning/GainCache.h"
#include "daep/planning/GaussianProcess.h"

namespace daep::planning {
namespace {

double smooth(const Eigen::Vector3d& p) {
    return 20.0 + 5.0 * std::sin(p.x()) + 3.0 * std::cos(0.5 * p.y()) + p.z();
}

TEST(GaussianProcess, SinglePointPosteriorMatchesTheClosedForm) {
    const GpParams params{1.0, 1.0, 0.1};
    GaussianProcess gp(params);
    const Eigen::Vector3d x(1.0, 2.0, 0.5);
    gp.fit({x}, {4.0});
    const Eigen::Vector3d q(1.5, 2.0, 0.5);
    const double k = std::exp(-0.25 / 2.0);
    const double denominator = 1.0 + 0.01;
    const GpPrediction at = gp.predict(q);
    EXPECT_NEAR(at.mean, k * 4.0 / denominator, 1e-12);
    EXPECT_NEAR(at.sigma, std::sqrt(1.0 - k * k / denominator), 1e-12);
    const GpPrediction on = gp.predict(x);
    EXPECT_NEAR(on.mean, 4.0 / denominator, 1e-12);
    EXPECT_NEAR(on.sigma * on.sigma, 1.0 - 1.0 / denominator, 1e-12);
}

TEST(GaussianProcess, PriorFarFromTheData) {
    GaussianProcess gp(GpParams{});
    gp.fit({Eigen::Vector3d::Zero()}, {30.0});
    const GpPrediction far = gp.predict({20.0, 0.0, 0.0});
    EXPECT_NEAR(far.mean, 0.0, 1e-9);
    EXPECT_NEAR(far.sigma, 1.0, 1e-9);
    GaussianProcess empty(GpParams{});
    empty.fit({}, {});
    EXPECT_DOUBLE_EQ(empty.predict({1, 2, 3}).sigma, 1.0);
}

TEST(GaussianProcess, InterpolatesASmoothFunctionFromADenseGrid) {
    GaussianProcess gp(GpParams{1.0, 1.0, 0.1});
    std::vector<Eigen::Vector3d> x;
    std::vector<double> y;
    for (double a = 0.0; a <= 4.0; a += 0.5)
        for (double b = 0.0; b <= 4.0; b += 0.5)
            for (double c = 0.0; c <= 1.0; c += 0.5) {
                x.emplace_back(a, b, c);
                y.push_back(smooth(x.back()));
            }
    gp.fit(x, y);
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(1.0, 3.0);
    for (int i = 0; i < 50; ++i) {
        const Eigen::Vector3d q(u(rng), u(rng), 0.25 + 0.5 * (u(rng) - 1.0) / 2.0);
        const GpPrediction g = gp.predict(q);
        EXPECT_NEAR(g.mean, smooth(q), 0.25) << q.transpose();
        EXPECT_LT(g.sigma, 0.2) << q.transpose();
    }
    // Variance grows with the distance to the data.
    const double inside = gp.predict({2.0, 2.0, 0.5}).sigma;
    const double edge = gp.predict({5.0, 2.0, 0.5}).sigma;
    const double outside = gp.predict({7.0, 2.0, 0.5}).sigma;
    EXPECT_LT(inside, edge);
    EXPECT_LT(edge, outside);
}

TEST(GaussianProcess, NoisyObservationsAreSmoothed) {
    GaussianProcess gp(GpParams{1.0, 1.0, 0.5});
    // The same input twice with different values: the posterior mean sits between them.
    gp.fit({Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()}, {1.0, 3.0});
    const double mean = gp.predict(Eigen::Vector3d::Zero()).mean;
    EXPECT_NEAR(mean, 2.0 * 2.0 / (2.0 + 0.25), 1e-12);
}

TEST(GainCache, NearReturnsLiveEntriesInRadiusNearestFirst) {
    GainCache cache(1.0);
    const int a = cache.insert({0.0, 0.0, 1.0}, 0.1, 20.0);
    const int b = cache.insert({1.5, 0.0, 1.0}, 0.2, 30.0);
    const int c = cache.insert({-0.7, 0.2, 1.0}, 0.3, 40.0);
    cache.insert({5.0, 5.0, 1.0}, 0.4, 50.0);
    EXPECT_EQ(cache.near({0.1, 0.0, 1.0}, 2.0), (std::vector<int>{a, c, b}));
    EXPECT_EQ(cache.near({0.1, 0.0, 1.0}, 2.0, 2), (std::vector<int>{a, c}));
    EXPECT_EQ(cache.near({0.1, 0.0, 1.0}, 0.5), (std::vector<int>{a}));
    cache.remove(a);
    EXPECT_EQ(cache.near({0.1, 0.0, 1.0}, 2.0), (std::vector<int>{c, b}));
    EXPECT_EQ(cache.size(), 3u);
    cache.update(b, 1.0, 12.0);
    EXPECT_DOUBLE_EQ(cache.entry(b).gain, 12.0);
    EXPECT_EQ(cache.liveIds().size(), 3u);
    // Negative coordinates and far queries.
    EXPECT_TRUE(cache.near({-50.0, -50.0, -3.0}, 3.0).empty());
}

/** The live points within `radius` of p by brute force: nearest first, then by id. */
std::vector<int> nearByBruteForce(const std::vector<Eigen::Vector3d>& points,
                                  const std::vector<bool>& alive, const Eigen::Vector3d& p,
                                  double radius) {
    std::vector<std::pair<double, int>> found;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (alive[i] && (points[i] - p).squaredNorm() <= radius * radius)
            found.emplace_back((points[i] - p).squaredNorm(), static_cast<int>(i));
    std::sort(found.begin(), found.end());
    std::vector<int> ids;
    for (const auto& f : found)
        ids.push_back(f.second);
    return ids;
}

TEST(GainCache, AgreesWithBruteForceOnRandomPoints) {
    // From a few entries (the query scans them) to many (it looks up the grid's cells), with
    // entries removed along the way.
    GainCache cache(0.7);
    std::mt19937_64 rng(9);
    std::uniform_real_distribution<double> u(-6.0, 6.0);
    std::vector<Eigen::Vector3d> points;
    std::vector<bool> alive;
    for (int i = 0; i < 400; ++i) {
        points.emplace_back(u(rng), u(rng), 0.3 * u(rng));
        alive.push_back(true);
        cache.insert(points.back(), 0.0, 1.0);
        if (i % 3 == 2) {
            const int gone = static_cast<int>(rng() % points.size());
            cache.remove(gone);
            alive[static_cast<std::size_t>(gone)] = false;
        }
        if (i % 10 != 0)
            continue;
        for (const double radius : {0.3, 1.8}) {
            const Eigen::Vector3d p(u(rng), u(rng), 0.0);
            EXPECT_EQ(cache.near(p, radius), nearByBruteForce(points, alive, p, radius))
                << i << " entries, radius " << radius;
        }
    }
    EXPECT_EQ(cache.size(), static_cast<std::size_t>(std::count(alive.begin(), alive.end(), true)));
}

}  // namespace
}  // namespace daep::planning
