#pragma once

#include <Eigen/Core>
#include <cmath>

namespace daep::world {

/** Oriented box: centre, unit axes (columns) and half extents. */
struct Obb {
    Eigen::Vector3d center = Eigen::Vector3d::Zero();
    Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
    Eigen::Vector3d half = Eigen::Vector3d::Zero();

    /** Half-width of the box's projection on `axis` (not necessarily unit). */
    double radiusAlong(const Eigen::Vector3d& axis) const {
        return half.x() * std::abs(axes.col(0).dot(axis)) +
               half.y() * std::abs(axes.col(1).dot(axis)) +
               half.z() * std::abs(axes.col(2).dot(axis));
    }
    Eigen::Vector3d aabbHalf() const { return axes.cwiseAbs() * half; }
};

/**
 * A convex polytope seen by the separating axis test: its vertices, face normals and unit edge
 * directions (parallel duplicates allowed).
 */
struct ConvexView {
    const Eigen::Vector3d* vertices;
    int vertexCount;
    const Eigen::Vector3d* normals;
    int normalCount;
    const Eigen::Vector3d* edges;
    int edgeCount;
};

/** True when `axis` separates the box from the polytope (a strict gap; touching overlaps). */
inline bool separates(const Obb& box, const ConvexView& c, const Eigen::Vector3d& axis) {
    // Crosses of (nearly) parallel unit edges: the face normals cover that case.
    if (axis.squaredNorm() < 1e-12)
        return false;
    const double centre = box.center.dot(axis);
    const double r = box.radiusAlong(axis);
    double lo = c.vertices[0].dot(axis), hi = lo;
    for (int i = 1; i < c.vertexCount; ++i) {
        const double p = c.vertices[i].dot(axis);
        lo = std::min(lo, p);
        hi = std::max(hi, p);
    }
    return lo > centre + r || hi < centre - r;
}

/**
 * Exact overlap of a box and a convex polytope by the separating axis theorem: box axes,
 * polytope normals and all box-axis x polytope-edge cross products (15 axes for two boxes, the
 * 13 of Akenine-Moller for a triangle).
 */
inline bool overlapsConvex(const Obb& box, const ConvexView& c) {
    for (int i = 0; i < 3; ++i)
        if (separates(box, c, box.axes.col(i)))
            return false;
    for (int i = 0; i < c.normalCount; ++i)
        if (separates(box, c, c.normals[i]))
            return false;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < c.edgeCount; ++j)
            if (separates(box, c, box.axes.col(i).cross(c.edges[j])))
                return false;
    return true;
}

}  // namespace daep::world
