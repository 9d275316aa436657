#include "daep/planning/FlightSpace.h"

#include <algorithm>
#include <cmath>

#include "daep/mapping/ExplorationMap.h"

namespace daep::planning {

Eigen::Vector3d steer(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double maxStep) {
    const Eigen::Vector3d d = to - from;
    const double length = d.norm();
    if (length <= maxStep)
        return to;
    return from + d * (maxStep / length);
}

Aabb shrink(const Aabb& box, double margin) {
    Aabb out;
    for (int a = 0; a < 3; ++a) {
        const double lo = box.min[a] + margin;
        const double hi = box.max[a] - margin;
        const double mid = 0.5 * (box.min[a] + box.max[a]);
        out.min[a] = lo <= hi ? lo : mid;
        out.max[a] = lo <= hi ? hi : mid;
    }
    return out;
}

Eigen::Vector3d sampleInBox(const Aabb& box, std::mt19937_64& rng) {
    Eigen::Vector3d p;
    for (int a = 0; a < 3; ++a) {
        p[a] = std::uniform_real_distribution<double>(box.min[a], box.max[a])(rng);
    }
    return p;
}

double sampleYaw(std::mt19937_64& rng) {
    return std::uniform_real_distribution<double>(-M_PI, M_PI)(rng);
}

double clearanceFromOccupied(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                             double radius) {
    if (map.isSegmentFreeOrUnknown(p, p, radius))
        return radius;
    double clear = 0.0, blocked = radius;
    if (!map.isSegmentFreeOrUnknown(p, p, clear))
        return -1.0;
    for (int i = 0; i < 6; ++i) {
        const double mid = 0.5 * (clear + blocked);
        (map.isSegmentFreeOrUnknown(p, p, mid) ? clear : blocked) = mid;
    }
    return clear;
}

namespace {

/**
 * Whether the line a -> b leaves a's own cell within `halfHeight` of a's height and then meets
 * no occupied cell. A drone without clearance (its cell, or one it touches, holds an imprint
 * mapped after it stopped there) may leave along such a line: not deeper into what it touches.
 * What its own cell holds may lie on either side of it, so the line must not cross it there:
 * a wall in that cell would reach into the drone's body, but a surface above or below it need
 * only be `halfHeight` away (the map keeps out returns inside the body alone).
 */
bool isLineClearPastOwnCell(const mapping::ExplorationMap& map, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, double halfHeight) {
    const Eigen::Vector3d d = b - a;
    const Eigen::Vector3d centre = map.cellCenter(a);
    const double half = 0.5 * map.resolution();
    double leave = 1.0;
    for (int axis = 0; axis < 3; ++axis) {
        if (d[axis] != 0.0) {
            const double face = centre[axis] + (d[axis] > 0.0 ? half : -half);
            leave = std::min(leave, (face - a[axis]) / d[axis]);
        }
    }
    leave = std::max(0.0, leave);
    if (std::abs(d.z()) * leave > halfHeight)
        return false;
    constexpr double kPastTheFace = 1e-6;  // metres: off the face shared with a's cell
    const double t = std::min(1.0, leave + kPastTheFace / std::max(d.norm(), 1e-12));
    return map.isSegmentFreeOrUnknown(a + d * t, b, 0.0);
}

}  // namespace

bool segmentFlyable(const mapping::ExplorationMap& map, const Eigen::Vector3d& a,
                    const Eigen::Vector3d& b, double radius, double halfHeight,
                    bool leavingBlockedRoot) {
    if (!leavingBlockedRoot)
        return map.isSegmentFree(a, b, radius);
    if (!map.isSegmentFree(b, b, radius))
        return false;
    const double length = (b - a).norm();
    const Eigen::Vector3d start =
        length > radius ? Eigen::Vector3d(a + (b - a) * (radius / length)) : b;
    if (map.isSegmentFreeOrUnknown(start, b, radius))
        return true;
    // Hemmed in closer than the radius (by a surface or a person's imprint seen after the drone
    // stopped): any move that never comes closer to it than the drone already is. That
    // clearance holds for what is near the drone only: a leg out along the end of a wall at
    // it would hit the wall, while one over a blob of mapped heads must stay possible.
    const double clear = clearanceFromOccupied(map, a, radius);
    const bool keepsClearance = clear > 0.0 ? map.isSegmentFreeOrUnknown(a, b, clear)
                                            : isLineClearPastOwnCell(map, a, b, halfHeight);
    return keepsClearance &&
           map.isSweptBoxClearOfNew(a, b, Eigen::Vector3d(radius, radius, halfHeight));
}

}  // namespace daep::planning
