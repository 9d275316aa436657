#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>

#include "daep/world/RayCaster.h"

namespace daep::world {
namespace {

const Eigen::Vector3d kDrone(0.4, 0.4, 0.1);
constexpr double kGap = 2e-3;  ///< just apart / just overlapping

BoxShape box(Eigen::Vector3d centre, Eigen::Vector3d size, Eigen::Matrix3d rotation) {
    BoxShape b;
    b.pose.translation() = centre;
    b.pose.linear() = rotation;
    b.size = size;
    return b;
}

Eigen::Matrix3d yawRotation(double yaw) {
    return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

WorldSpec worldWith(BoxShape b) {
    WorldSpec w;
    w.boxes.push_back(std::move(b));
    return w;
}

TEST(StaticCollision, AxisAlignedBoxFaces) {
    const StaticCollisionChecker c(worldWith(box({0, 0, 1}, {2, 2, 2}, yawRotation(0))));
    EXPECT_TRUE(c.overlaps({0, 0, 1}, kDrone, 0.0));           // inside
    EXPECT_TRUE(c.overlaps({1.2 - kGap, 0, 1}, kDrone, 0.0));  // side
    EXPECT_FALSE(c.overlaps({1.2 + kGap, 0, 1}, kDrone, 0.0));
    EXPECT_TRUE(c.overlaps({0, 0, 2.05 - kGap}, kDrone, 0.0));  // top
    EXPECT_FALSE(c.overlaps({0, 0, 2.05 + kGap}, kDrone, 0.0));
    // Drone turned 45 deg: its corner reaches 0.2 * sqrt(2) towards the face.
    const double corner = 1.0 + 0.2 * std::sqrt(2.0);
    EXPECT_TRUE(c.overlaps({corner - kGap, 0, 1}, kDrone, M_PI / 4));
    EXPECT_FALSE(c.overlaps({corner + kGap, 0, 1}, kDrone, M_PI / 4));
}

TEST(StaticCollision, RotatedBoxes) {
    // Wall turned 45 deg: its corner on +x is at sqrt(2).
    const StaticCollisionChecker c(worldWith(box({0, 0, 1}, {2, 2, 2}, yawRotation(M_PI / 4))));
    const double corner = std::sqrt(2.0) + 0.2;
    EXPECT_TRUE(c.overlaps({corner - kGap, 0, 1}, kDrone, 0.0));
    EXPECT_FALSE(c.overlaps({corner + kGap, 0, 1}, kDrone, 0.0));
    // Both turned 45 deg: face to face along the diagonal, touching at d / sqrt(2) = 1.2.
    const double faceToFace = 1.2 * std::sqrt(2.0);
    EXPECT_TRUE(c.overlaps({faceToFace - kGap, 0, 1}, kDrone, M_PI / 4));
    EXPECT_FALSE(c.overlaps({faceToFace + kGap, 0, 1}, kDrone, M_PI / 4));
}

TEST(StaticCollision, TiltedBoxNeedsMoreThanAabbs) {
    // A slab tilted 45 deg about x: its AABB covers the query, the slab itself does not.
    const Eigen::Matrix3d roll =
        Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const StaticCollisionChecker c(worldWith(box({0, 0, 0}, {4, 4, 0.1}, roll)));
    EXPECT_FALSE(c.overlaps({0, 1.0, -1.0}, kDrone, 0.3));
    EXPECT_TRUE(c.overlaps({0, 1.0, 1.0}, kDrone, 0.3));
}

/** Exact point-in-box test used as an oracle. */
bool inside(const BoxShape& b, const Eigen::Vector3d& p) {
    const Eigen::Vector3d local = b.pose.inverse() * p;
    return (local.cwiseAbs().array() <= 0.5 * b.size.array()).all();
}

TEST(StaticCollision, AgreesWithSampledOracleOnRandomBoxes) {
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int overlapping = 0, separated = 0;
    for (int trial = 0; trial < 300; ++trial) {
        const Eigen::Vector3d rpy(u(rng) * M_PI, u(rng) * M_PI, u(rng) * M_PI);
        const Eigen::Matrix3d r = (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
                                   Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
                                   Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
                                      .toRotationMatrix();
        const BoxShape wall = box(Eigen::Vector3d::Zero(), {1.0, 0.6, 0.3}, r);
        const StaticCollisionChecker c(worldWith(wall));
        const Eigen::Vector3d centre(0.8 * u(rng), 0.8 * u(rng), 0.6 * u(rng));
        const double yaw = u(rng) * M_PI;
        const bool sat = c.overlaps(centre, kDrone, yaw);
        // Sample the drone box densely: any sample inside the wall proves an overlap.
        bool sampledHit = false;
        const Eigen::Matrix3d dr = yawRotation(yaw);
        for (int i = 0; i <= 20 && !sampledHit; ++i)
            for (int j = 0; j <= 20 && !sampledHit; ++j)
                for (int k = 0; k <= 4 && !sampledHit; ++k) {
                    const Eigen::Vector3d local((i / 20.0 - 0.5) * kDrone.x(),
                                                (j / 20.0 - 0.5) * kDrone.y(),
                                                (k / 4.0 - 0.5) * kDrone.z());
                    sampledHit = inside(wall, centre + dr * local);
                }
        if (sampledHit) {
            EXPECT_TRUE(sat) << "trial " << trial;
        }
        (sat ? overlapping : separated)++;
    }
    EXPECT_GT(overlapping, 30);
    EXPECT_GT(separated, 30);
}

TEST(StaticCollision, Cylinder) {
    WorldSpec w;
    CylinderShape cyl;
    cyl.pose.translation() = Eigen::Vector3d(0, 0, 1);
    cyl.radius = 0.5;
    cyl.length = 2.0;
    w.cylinders.push_back(cyl);
    const StaticCollisionChecker c(w);
    EXPECT_TRUE(c.overlaps({0.7 - kGap, 0, 1}, kDrone, 0.0));
    // The circumscribed 32-gon exceeds the circle by at most 0.5 % of r (2.4 mm here).
    EXPECT_FALSE(c.overlaps({0.7 + 2 * kGap, 0, 1}, kDrone, 0.0));
    // Corner first along the diagonal: reaches the circle at d = r + 0.2 sqrt(2).
    const double d = 0.5 + 0.2 * std::sqrt(2.0);
    const Eigen::Vector3d diag(std::sqrt(0.5), std::sqrt(0.5), 0);
    EXPECT_TRUE(c.overlaps(Eigen::Vector3d(0, 0, 1) + (d - kGap) * diag, kDrone, 0.0));
    EXPECT_FALSE(c.overlaps(Eigen::Vector3d(0, 0, 1) + (d + 3 * kGap) * diag, kDrone, 0.0));
    EXPECT_TRUE(c.overlaps({0, 0, 2.05 - kGap}, kDrone, 0.0));  // on the top cap
    EXPECT_FALSE(c.overlaps({0, 0, 2.05 + kGap}, kDrone, 0.0));
}

TEST(StaticCollision, MeshTriangles) {
    WorldSpec w;
    TriangleMesh m;  // a sloped triangle: z = x over x, y in [0, 2]
    m.vertices = {{0, 0, 0}, {2, 0, 2}, {0, 2, 0}};
    m.triangles = {{0, 1, 2}};
    w.meshes.push_back(m);
    const StaticCollisionChecker c(w);
    EXPECT_TRUE(c.overlaps({0.5, 0.5, 0.5}, kDrone, 0.0));
    // Distance from the lowest-right box corner (x + 0.2, z - 0.05) to the plane z = x.
    EXPECT_TRUE(c.overlaps({0.5, 0.5, 0.75 - kGap}, kDrone, 0.0));
    EXPECT_FALSE(c.overlaps({0.5, 0.5, 0.75 + kGap}, kDrone, 0.0));
    EXPECT_FALSE(c.overlaps({1.5, 1.5, 1.5}, kDrone, 0.0));          // beyond the hypotenuse
    EXPECT_FALSE(c.overlaps({0.5, -0.2 - kGap, 0.5}, kDrone, 0.0));  // off the y = 0 edge
    EXPECT_TRUE(c.overlaps({0.5, -0.2 + kGap, 0.5}, kDrone, 0.0));
}

TEST(StaticCollision, LargeMeshStaysFast) {
    // 100k-triangle height field, 0.1 m cells over 22.4 x 22.4 m.
    WorldSpec w;
    TriangleMesh m;
    const int n = 224;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j)
            m.vertices.emplace_back(0.1f * i, 0.1f * j, 0.05f * std::sin(0.3f * i));
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const int a = i * (n + 1) + j;
            m.triangles.emplace_back(a, a + n + 1, a + 1);
            m.triangles.emplace_back(a + 1, a + n + 1, a + n + 2);
        }
    ASSERT_GT(m.triangles.size(), 100000u);
    w.meshes.push_back(m);
    const StaticCollisionChecker c(w);
    const auto t0 = std::chrono::steady_clock::now();
    int hits = 0;
    for (int q = 0; q < 20000; ++q) {
        const double x = 0.5 + (q % 200) * 0.1, y = 0.5 + (q / 200) * 0.2;
        hits += c.overlaps({x, y, (q % 2) ? 0.0 : 0.3}, kDrone, 0.01 * q) ? 1 : 0;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(hits, 10000);  // on the surface yes, 0.3 m above it no
    EXPECT_LT(seconds, 2.0);
}

TEST(StaticCollision, EmptyWorldNeverOverlaps) {
    const StaticCollisionChecker c(WorldSpec{});
    EXPECT_FALSE(c.overlaps({0, 0, 0}, kDrone, 0.0));
}

}  // namespace
}  // namespace daep::world
