// PeopleBuckets answers as testing every footprint does, for random footprints and points,
// points on and just off the cylinders' edges, and footprints that are not finite.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "PeopleBuckets.h"

namespace {

using daep::mapping::PeopleBuckets;
using daep::mapping::PersonFootprint;

bool inAnyFootprint(const Eigen::Vector3f& p, const std::vector<PersonFootprint>& people) {
    for (const PersonFootprint& f : people)
        if (p.z() <= f.top && (p.head<2>() - f.centre).squaredNorm() <= f.radius * f.radius)
            return true;
    return false;
}

TEST(PeopleBuckets, AgreesWithTestingEveryFootprint) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> coord(-30.0f, 30.0f), unit(0.0f, 1.0f);
    std::vector<PersonFootprint> people;
    for (int i = 0; i < 40; ++i)
        people.push_back(
            {Eigen::Vector2f(coord(rng), coord(rng)), 0.1f + 0.5f * unit(rng), 1.0f + unit(rng)});
    people.push_back({Eigen::Vector2f(1.0f, 2.0f), -0.4f, 1.7f});  // r * r still counts
    people.push_back({Eigen::Vector2f(std::nanf(""), 0.0f), 0.3f, 1.7f});
    people.push_back({Eigen::Vector2f(0.0f, 0.0f), std::numeric_limits<float>::infinity(), 1.0f});
    const PeopleBuckets buckets(people);

    int inside = 0;
    for (int i = 0; i < 200000; ++i) {
        const PersonFootprint& f = people[std::size_t(i) % 41];
        Eigen::Vector3f p;
        if (i % 2 == 0) {  // near an edge: radius times (1 +- a few float steps)
            const float a = 6.2831853f * unit(rng);
            const float r = std::abs(f.radius) * (1.0f + (unit(rng) - 0.5f) * 1e-6f);
            p = Eigen::Vector3f(f.centre.x() + r * std::cos(a), f.centre.y() + r * std::sin(a),
                                f.top + (unit(rng) - 0.5f) * 1e-5f);
        } else {
            p = Eigen::Vector3f(coord(rng), coord(rng), 2.5f * unit(rng));
        }
        const bool expected = inAnyFootprint(p, people);
        inside += expected;
        ASSERT_EQ(buckets.contains(p), expected) << p.transpose();
    }
    EXPECT_GT(inside, 20000);  // both answers were exercised
    EXPECT_FALSE(PeopleBuckets({}).contains(Eigen::Vector3f::Zero()));
}

}  // namespace
