#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "daep/world/RayCaster.h"

namespace daep::world {
namespace {

const float kInf = std::numeric_limits<float>::infinity();
const Eigen::Vector3f kOrigin(0, 0, 1);

BoxShape box(Eigen::Vector3d centre, Eigen::Vector3d size, double yaw = 0.0) {
    BoxShape b;
    b.pose.translation() = centre;
    b.pose.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    b.size = size;
    return b;
}

/** Box ahead on +x, cylinder on +y, triangle on -x; nothing below, above or on -y. */
WorldSpec analyticWorld() {
    WorldSpec w;
    w.boxes.push_back(box({5, 0, 1}, {2, 2, 2}));
    CylinderShape c;
    c.pose.translation() = Eigen::Vector3d(0, 5, 1);
    c.radius = 1.0;
    c.length = 2.0;
    w.cylinders.push_back(c);
    TriangleMesh m;
    m.vertices = {{-3, -1, 0}, {-3, 1, 0}, {-3, 0, 2}};
    m.triangles = {{0, 1, 2}};
    w.meshes.push_back(m);
    return w;
}

TEST(RayCaster, DistancesToAnalyticShapes) {
    const RayCaster rc(analyticWorld());
    EXPECT_NEAR(rc.castRay(kOrigin, {1, 0, 0}, 100), 4.0f, 1e-5);  // box face
    // The cylinder is a 32-gon prism: a vertex lies on +y, so the side is hit at r = 1.
    EXPECT_NEAR(rc.castRay(kOrigin, {0, 1, 0}, 100), 4.0f, 1e-5);
    // Between vertices the prism's side is at r cos(pi/32).
    const Eigen::Vector3f towardsAxis = (Eigen::Vector3f(std::sin(M_PI / 32), 5, 0)).normalized();
    EXPECT_NEAR(rc.castRay(kOrigin, towardsAxis, 100), std::hypot(std::sin(M_PI / 32), 5.0) - 1.0,
                0.01);
    EXPECT_NEAR(rc.castRay(kOrigin, {-1, 0, 0}, 100), 3.0f, 1e-5);  // mesh triangle
    EXPECT_EQ(rc.castRay(kOrigin, {0, 0, 1}, 100), kInf);
    EXPECT_EQ(rc.castRay(kOrigin, {0, -1, 0}, 100), kInf);
    EXPECT_EQ(rc.castRay(kOrigin, {1, 0, 0}, 3.9f), kInf);  // beyond max range
    // Slanting up onto the same face, at z = 1.8.
    const Eigen::Vector3f up45 = Eigen::Vector3f(1, 0, 0.2f).normalized();
    EXPECT_NEAR(rc.castRay(kOrigin, up45, 100), 4.0f / up45.x(), 1e-4);
}

TEST(RayCaster, RotatedBox) {
    WorldSpec w;
    w.boxes.push_back(box({3, 0, 1}, {1, 1, 1}, M_PI / 4));
    const RayCaster rc(w);
    EXPECT_NEAR(rc.castRay(kOrigin, {1, 0, 0}, 100), 3.0f - std::sqrt(0.5f), 1e-5);
}

TEST(RayCaster, PeopleAppearMoveAndLeave) {
    RayCaster rc(WorldSpec{});
    const Eigen::Vector3f down(0, -1, 0);
    EXPECT_EQ(rc.castRay(kOrigin, down, 100), kInf);

    PersonState p;
    p.position = {0, -4};
    const Eigen::Vector3d body(1.0, 1.0, 1.8);
    rc.setPeople({p}, body);
    EXPECT_NEAR(rc.castRay(kOrigin, down, 100), 3.5f, 1e-5);
    EXPECT_EQ(rc.castRay({0, 0, 1.9f}, down, 100), kInf);  // above the head

    p.position = {0, -6};
    rc.setPeople({p}, body);
    EXPECT_NEAR(rc.castRay(kOrigin, down, 100), 5.5f, 1e-5);

    p.heading = M_PI / 4;  // corner towards the ray
    rc.setPeople({p}, body);
    EXPECT_NEAR(rc.castRay(kOrigin, down, 100), 6.0f - std::sqrt(0.5f), 1e-5);

    PersonState q;
    q.position = {0, -2};
    rc.setPeople({p, q}, body);
    EXPECT_NEAR(rc.castRay(kOrigin, down, 100), 1.5f, 1e-5);

    rc.setPeople({}, body);
    EXPECT_EQ(rc.castRay(kOrigin, down, 100), kInf);
}

/** The analytic world with a person standing in it. */
void addPerson(RayCaster& rc) {
    PersonState p;
    p.position = {0, -3};
    rc.setPeople({p}, {1, 1, 1.8});
}

/** n random unit directions, flattened towards the horizontal. */
std::vector<Eigen::Vector3f> randomDirections(unsigned seed, std::size_t n) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> n01;
    std::vector<Eigen::Vector3f> dirs(n);
    for (auto& d : dirs)
        d = Eigen::Vector3f(n01(rng), n01(rng), 0.3f * n01(rng)).normalized();
    return dirs;
}

TEST(RayCaster, PacketsEqualSingleRays) {
    RayCaster rc(analyticWorld());
    addPerson(rc);
    const auto dirs = randomDirections(7, 1001);  // not a multiple of the packet size
    std::vector<float> out;
    rc.castRays(kOrigin, dirs, 6.0f, out);
    ASSERT_EQ(out.size(), dirs.size());
    int hits = 0;
    for (std::size_t i = 0; i < dirs.size(); ++i) {
        const float single = rc.castRay(kOrigin, dirs[i], 6.0f);
        if (std::isinf(single)) {
            EXPECT_TRUE(std::isinf(out[i])) << i;
        } else {
            ++hits;
            EXPECT_NEAR(out[i], single, 1e-5f) << i;
        }
    }
    EXPECT_GT(hits, 100);
    EXPECT_LT(hits, 1000);
}

TEST(RayCaster, TurnedCastsEqualCastsOfTheTurnedDirections) {
    RayCaster rc(analyticWorld());
    addPerson(rc);
    const auto dirs = randomDirections(11, 517);
    int hits = 0;
    for (const double yaw : {0.0, 0.7, -2.9, M_PI / 2, M_PI}) {
        const RayCaster::YawTurn turn{float(std::cos(yaw)), float(std::sin(yaw))};
        std::vector<Eigen::Vector3f> turned;
        for (const auto& r : dirs)
            turned.emplace_back(turn.cos * r.x() - turn.sin * r.y(),
                                turn.sin * r.x() + turn.cos * r.y(), r.z());
        std::vector<float> expected, out;
        rc.castRays(kOrigin, turned, 6.0f, expected);
        rc.castRays(kOrigin, dirs, turn, 6.0f, out);
        ASSERT_EQ(out.size(), dirs.size());
        for (std::size_t i = 0; i < dirs.size(); ++i) {
            ASSERT_EQ(std::memcmp(&out[i], &expected[i], sizeof(float)), 0) << yaw << " " << i;
            hits += std::isfinite(out[i]);
        }
    }
    EXPECT_GT(hits, 300);      // rays that hit something, and
    EXPECT_LT(hits, 5 * 400);  // rays that miss everything
}

TEST(RayCaster, EmptyInputGivesEmptyOutput) {
    const RayCaster rc(analyticWorld());
    std::vector<float> out(3, 1.0f);
    rc.castRays(kOrigin, {}, 10.0f, out);
    EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace daep::world
