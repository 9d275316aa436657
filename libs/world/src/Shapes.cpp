#include "Shapes.h"

#include <cmath>

namespace daep::world {

Eigen::Matrix3d rotationFromRpy(const Eigen::Vector3d& rpy) {
    return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
            Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
        .toRotationMatrix();
}

std::array<Eigen::Vector3d, 8> boxCorners(const Eigen::Isometry3d& pose,
                                          const Eigen::Vector3d& size) {
    std::array<Eigen::Vector3d, 8> corners;
    const Eigen::Vector3d h = 0.5 * size;
    for (int i = 0; i < 8; ++i) {
        const Eigen::Vector3d local((i & 1) ? h.x() : -h.x(), (i & 2) ? h.y() : -h.y(),
                                    (i & 4) ? h.z() : -h.z());
        corners[i] = pose * local;
    }
    return corners;
}

std::vector<Eigen::Vector3d> cylinderPrismVertices(const CylinderShape& c, double radiusScale) {
    std::vector<Eigen::Vector3d> v(2 * kCylinderSegments);
    const double r = c.radius * radiusScale;
    const double hz = 0.5 * c.length;
    for (int i = 0; i < kCylinderSegments; ++i) {
        const double a = 2.0 * M_PI * i / kCylinderSegments;
        v[i] = c.pose * Eigen::Vector3d(r * std::cos(a), r * std::sin(a), -hz);
        v[i + kCylinderSegments] = c.pose * Eigen::Vector3d(r * std::cos(a), r * std::sin(a), hz);
    }
    return v;
}

void TriangleSoup::addBox(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size) {
    const int base = static_cast<int>(vertices.size());
    for (const auto& c : boxCorners(pose, size))
        vertices.push_back(c.cast<float>());
    // Quads with outward normals (counter-clockwise seen from outside).
    static constexpr int kQuads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                         {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (const auto& q : kQuads) {
        triangles.emplace_back(base + q[0], base + q[1], base + q[2]);
        triangles.emplace_back(base + q[0], base + q[2], base + q[3]);
    }
}

void TriangleSoup::addCylinder(const CylinderShape& c) {
    constexpr int n = kCylinderSegments;
    const int base = static_cast<int>(vertices.size());
    for (const auto& v : cylinderPrismVertices(c, 1.0))
        vertices.push_back(v.cast<float>());
    const int bottomCentre = static_cast<int>(vertices.size());
    vertices.push_back((c.pose * Eigen::Vector3d(0, 0, -0.5 * c.length)).cast<float>());
    vertices.push_back((c.pose * Eigen::Vector3d(0, 0, 0.5 * c.length)).cast<float>());
    for (int i = 0; i < n; ++i) {
        const int j = (i + 1) % n;
        const int b0 = base + i, b1 = base + j, t0 = base + n + i, t1 = base + n + j;
        triangles.emplace_back(b0, b1, t1);
        triangles.emplace_back(b0, t1, t0);
        triangles.emplace_back(bottomCentre, b1, b0);
        triangles.emplace_back(bottomCentre + 1, t0, t1);
    }
}

void TriangleSoup::addMesh(const TriangleMesh& m) {
    const int base = static_cast<int>(vertices.size());
    vertices.insert(vertices.end(), m.vertices.begin(), m.vertices.end());
    for (const auto& t : m.triangles)
        triangles.push_back(t + Eigen::Vector3i::Constant(base));
}

TriangleSoup triangulateStatic(const WorldSpec& world) {
    TriangleSoup soup;
    for (const auto& b : world.boxes)
        soup.addBox(b.pose, b.size);
    for (const auto& c : world.cylinders)
        soup.addCylinder(c);
    for (const auto& m : world.meshes)
        soup.addMesh(m);
    return soup;
}

Eigen::Isometry3d personBoxPose(const Eigen::Vector2d& position, double heading,
                                const Eigen::Vector3d& bodySize) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(position.x(), position.y(), 0.5 * bodySize.z());
    pose.linear() = Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return pose;
}

}  // namespace daep::world
