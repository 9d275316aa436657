#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "daep/world/People.h"
#include "daep/world/WorldSpec.h"

namespace daep::world {

/**
 * Embree scene of the world's static geometry plus one box per person (updated with
 * setPeople). Thread-compatible: casting is const, setPeople is not.
 */
class RayCaster {
public:
    explicit RayCaster(const WorldSpec& world);
    ~RayCaster();
    RayCaster(const RayCaster&) = delete;
    RayCaster& operator=(const RayCaster&) = delete;

    /** Moves the person boxes (size from params.bodySize) to the given states. */
    void setPeople(const std::vector<PersonState>& people, const Eigen::Vector3d& bodySize);

    /** Distance to the first hit along the unit direction, or +inf when none within maxRange. */
    float castRay(const Eigen::Vector3f& origin, const Eigen::Vector3f& unitDir,
                  float maxRange) const;

    /** Index of the person the ray hits first within maxRange, or -1 (static geometry or none). */
    int firstPersonHit(const Eigen::Vector3f& origin, const Eigen::Vector3f& unitDir,
                       float maxRange) const;

    /**
     * Casts many rays from one origin; out[i] = hit distance or +inf. Uses packets: this is
     * the depth camera's hot path.
     */
    void castRays(const Eigen::Vector3f& origin, const std::vector<Eigen::Vector3f>& unitDirs,
                  float maxRange, std::vector<float>& out) const;

    /** A turn about the z axis by the angle whose cosine and sine these are. */
    struct YawTurn {
        float cos, sin;
    };
    /**
     * castRays of the directions turned by `turn` about z, each as it is put into its packet:
     * (cos x - sin y, sin x + cos y, z), in float. A camera's fixed pixel rays need no turned
     * copy each frame.
     */
    void castRays(const Eigen::Vector3f& origin, const std::vector<Eigen::Vector3f>& unitDirs,
                  YawTurn turn, float maxRange, std::vector<float>& out) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

/**
 * Exact overlap test of an oriented box (centre, full size, yaw about z) with the static
 * geometry (boxes, cylinders, mesh triangles).
 */
class StaticCollisionChecker {
public:
    explicit StaticCollisionChecker(const WorldSpec& world);
    ~StaticCollisionChecker();

    bool overlaps(const Eigen::Vector3d& center, const Eigen::Vector3d& size, double yaw) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace daep::world
