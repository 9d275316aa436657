#include "WorldValidation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "daep/common/Error.h"
#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace daep::world {
namespace {

/** The body a start or a walking person must leave free (metres). */
constexpr double kStartProbe = 0.1;  ///< a small cube resting on the start point
/**
 * A narrow body around the walked line: the benchmark's own routes pass 0.2 m from Field's
 * posts, and the simulated 1 m body is a collision proxy, not the person's width.
 */
constexpr double kPersonFootprint = 0.2;
constexpr double kPersonBottom = 0.3;  ///< above floors people stand on (Cafe's is 0.19 m)
constexpr double kPersonTop = 1.8;     ///< the simulated body's height
constexpr double kRouteStep = 0.05;

std::string formatPoint(const Eigen::Vector3d& p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.2f, %.2f, %.2f)", p.x(), p.y(), p.z());
    return buf;
}

std::string formatPoint(const Eigen::Vector2d& p) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "(%.2f, %.2f)", p.x(), p.y());
    return buf;
}

std::string quotedName(const std::string& name) {
    return name.empty() ? "" : " '" + name + "'";
}

[[noreturn]] void fail(const WorldSpec& w, const std::string& what) {
    throw InputError(w.sourceFile + ": " + what);
}

template <typename Vec>
void requireInRange(const WorldSpec& w, const Vec& v, const std::string& item) {
    if (!v.allFinite())
        fail(w, item + ": a coordinate is not a finite number");
    if (v.cwiseAbs().maxCoeff() > kMaxCoordinate) {
        char buf[160];
        std::snprintf(buf, sizeof buf,
                      ": coordinate %.6g m lies farther than %.0f m from the origin",
                      v.cwiseAbs().maxCoeff(), kMaxCoordinate);
        fail(w, item + buf);
    }
}

void checkCoordinates(const WorldSpec& w) {
    requireInRange(w, w.explorationBox.min, "exploration_box.min");
    requireInRange(w, w.explorationBox.max, "exploration_box.max");
    if (!(w.explorationBox.max.array() > w.explorationBox.min.array()).all())
        fail(w, "exploration_box: max must exceed min on every axis");
    if (w.explorationBox.volume() > kMaxExplorationVolume)
        fail(w, "exploration_box: " + std::to_string(w.explorationBox.volume()) +
                    " m^3 is larger than the " + std::to_string(kMaxExplorationVolume) +
                    " m^3 a map can hold");
    for (std::size_t i = 0; i < w.starts.size(); ++i)
        requireInRange(w, w.starts[i], "starts[" + std::to_string(i) + "]");
    for (std::size_t i = 0; i < w.cylinders.size(); ++i) {
        const CylinderShape& c = w.cylinders[i];
        const std::string item = "cylinders[" + std::to_string(i) + "]" + quotedName(c.name);
        requireInRange(w, c.pose.translation(), item + " center");
        requireInRange(w, Eigen::Vector2d(c.radius, c.length), item + " radius/length");
    }
    for (std::size_t i = 0; i < w.meshes.size(); ++i) {
        const TriangleMesh& m = w.meshes[i];
        const std::string item = "meshes[" + std::to_string(i) + "]" + quotedName(m.name);
        if (m.triangles.empty())
            fail(w, item + ": the mesh has no triangles");
        for (const Eigen::Vector3f& v : m.vertices)
            requireInRange(w, v.cast<double>(), item + " vertex");
    }
    for (std::size_t i = 0; i < w.people.size(); ++i)
        for (std::size_t j = 0; j < w.people[i].waypoints.size(); ++j)
            requireInRange(w, w.people[i].waypoints[j],
                           "people[" + std::to_string(i) + "]" + quotedName(w.people[i].name) +
                               " waypoint " + std::to_string(j));
    // Last: the ground slab is sized from the rest, so a far shape is named before it.
    for (std::size_t i = 0; i < w.boxes.size(); ++i) {
        const std::string item = "boxes[" + std::to_string(i) + "]" + quotedName(w.boxes[i].name);
        requireInRange(w, w.boxes[i].pose.translation(), item + " center");
        requireInRange(w, w.boxes[i].size, item + " size");
    }
}

/** The shapes of `w` one at a time, for naming the one a probe hits. */
std::string shapeHit(const WorldSpec& w, const Eigen::Vector3d& center, const Eigen::Vector3d& size,
                     double yaw) {
    const auto hits = [&](WorldSpec one) {
        one.explorationBox = w.explorationBox;
        return StaticCollisionChecker(one).overlaps(center, size, yaw);
    };
    for (std::size_t i = 0; i < w.boxes.size(); ++i) {
        WorldSpec one;
        one.boxes.push_back(w.boxes[i]);
        if (hits(one))
            return "boxes[" + std::to_string(i) + "]" + quotedName(w.boxes[i].name);
    }
    for (std::size_t i = 0; i < w.cylinders.size(); ++i) {
        WorldSpec one;
        one.cylinders.push_back(w.cylinders[i]);
        if (hits(one))
            return "cylinders[" + std::to_string(i) + "]" + quotedName(w.cylinders[i].name);
    }
    for (std::size_t i = 0; i < w.meshes.size(); ++i) {
        WorldSpec one;
        one.meshes.push_back(w.meshes[i]);
        if (hits(one))
            return "meshes[" + std::to_string(i) + "]" + quotedName(w.meshes[i].name);
    }
    return "static geometry";
}

void checkStarts(const WorldSpec& w, const StaticCollisionChecker& statics) {
    const Eigen::Vector3d probe = Eigen::Vector3d::Constant(kStartProbe);
    for (std::size_t i = 0; i < w.starts.size(); ++i) {
        const Eigen::Vector3d center = w.starts[i] + Eigen::Vector3d(0, 0, 0.6 * kStartProbe);
        if (statics.overlaps(center, probe, 0.0))
            fail(w, "starts[" + std::to_string(i) + "] " + formatPoint(w.starts[i]) +
                        ": the start lies inside " + shapeHit(w, center, probe, 0.0));
    }
}

/** A person walks leg a -> b facing along it: sweep their footprint at body height. */
void checkLeg(const WorldSpec& w, const StaticCollisionChecker& statics, std::size_t person,
              std::size_t leg, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector3d body(kPersonFootprint, kPersonFootprint, kPersonTop - kPersonBottom);
    const double z = 0.5 * (kPersonBottom + kPersonTop);
    const double length = (b - a).norm();
    const double yaw = length > 0 ? std::atan2(b.y() - a.y(), b.x() - a.x()) : 0.0;
    const int steps = std::max(1, static_cast<int>(std::ceil(length / kRouteStep)));
    for (int s = 0; s <= steps; ++s) {
        const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(s) / steps);
        const Eigen::Vector3d center(p.x(), p.y(), z);
        if (!statics.overlaps(center, body, yaw))
            continue;
        const PersonRoute& r = w.people[person];
        fail(w, "people[" + std::to_string(person) + "]" + quotedName(r.name) + ": leg " +
                    std::to_string(leg) + " " + formatPoint(a) + " -> " + formatPoint(b) +
                    " runs into " + shapeHit(w, center, body, yaw) + " at " + formatPoint(p));
    }
}

void checkRoutes(const WorldSpec& w, const StaticCollisionChecker& statics) {
    for (std::size_t i = 0; i < w.people.size(); ++i) {
        const auto& wps = w.people[i].waypoints;
        for (std::size_t j = 0; j < wps.size(); ++j)  // the last leg walks back to the first
            checkLeg(w, statics, i, j, wps[j], wps[(j + 1) % wps.size()]);
    }
}

}  // namespace

void validateWorld(const WorldSpec& world) {
    checkCoordinates(world);
    const StaticCollisionChecker statics(world);
    checkStarts(world, statics);
    checkRoutes(world, statics);
}

}  // namespace daep::world
