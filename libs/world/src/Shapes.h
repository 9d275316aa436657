#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <vector>

#include "daep/world/WorldSpec.h"

namespace daep::world {

/** Segments of the prism that stands in for a cylinder (rendering and collision). */
constexpr int kCylinderSegments = 32;

/** Gazebo convention: R = Rz(yaw) * Ry(pitch) * Rx(roll), angles in radians. */
Eigen::Matrix3d rotationFromRpy(const Eigen::Vector3d& rpy);

/** Corner i has +x half-extent when bit 0 is set, +y for bit 1, +z for bit 2. */
std::array<Eigen::Vector3d, 8> boxCorners(const Eigen::Isometry3d& pose,
                                          const Eigen::Vector3d& size);

/**
 * Vertices of the cylinder's prism: ring i at the bottom is vertex i, at the top i + segments.
 * `radiusScale` > 1 circumscribes the circle (1 / cos(pi / segments) makes the prism contain
 * the cylinder).
 */
std::vector<Eigen::Vector3d> cylinderPrismVertices(const CylinderShape& c, double radiusScale);

/** Triangles in world coordinates, as Embree wants them. */
struct TriangleSoup {
    std::vector<Eigen::Vector3f> vertices;
    std::vector<Eigen::Vector3i> triangles;

    void addBox(const Eigen::Isometry3d& pose, const Eigen::Vector3d& size);
    void addCylinder(const CylinderShape& c);
    void addMesh(const TriangleMesh& m);
};

/** All static geometry of the world as triangles. */
TriangleSoup triangulateStatic(const WorldSpec& world);

/** Pose of a person's body box centre: standing on z = 0, rotated by heading. */
Eigen::Isometry3d personBoxPose(const Eigen::Vector2d& position, double heading,
                                const Eigen::Vector3d& bodySize);

}  // namespace daep::world
