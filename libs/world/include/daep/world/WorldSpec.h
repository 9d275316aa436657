#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "daep/common/Types.h"

namespace daep::world {

/** Solid box: `pose` places its centre, `size` is the full extent along its own axes. */
struct BoxShape {
    std::string name;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    Eigen::Vector3d size = Eigen::Vector3d::Ones();
};

/** Solid upright-in-its-frame cylinder: axis along the local z, centred on `pose`. */
struct CylinderShape {
    std::string name;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    double radius = 0.5;
    double length = 1.0;
};

/** Triangle mesh already transformed into the world frame. */
struct TriangleMesh {
    std::string name;
    std::string source;  ///< file it was loaded from, for messages
    std::vector<Eigen::Vector3f> vertices;
    std::vector<Eigen::Vector3i> triangles;
};

/**
 * Solid axis-aligned boxes from a voxel map: an OctoMap's occupied leaves or a voxelised point
 * cloud, in world coordinates. Neighbouring cells are merged into larger boxes where they line
 * up, so a map of many cells stays a moderate number of boxes.
 */
struct VoxelMap {
    std::string name;
    std::string source;       ///< file it was loaded from, for messages
    double resolution = 0.0;  ///< the map's finest cell size, m
    std::size_t cells = 0;    ///< occupied cells of that size the boxes cover
    std::vector<Aabb> boxes;
};

/** A person walks its waypoints in order, then back to the first, forever. */
struct PersonRoute {
    std::string name;
    std::vector<Eigen::Vector2d> waypoints;
};

/** Everything the simulator needs to know about one benchmark world. */
struct WorldSpec {
    std::string name;
    std::string description;
    std::string sourceFile;
    Aabb explorationBox;
    std::vector<BoxShape> boxes;
    std::vector<CylinderShape> cylinders;
    std::vector<TriangleMesh> meshes;
    std::vector<VoxelMap> voxelMaps;      ///< `octomap` and `point_cloud` geometry
    std::vector<Eigen::Vector3d> starts;  ///< spawn positions (the drone then climbs 1 m)
    std::vector<PersonRoute> people;      ///< empty routes in static mode
    /** `exploration_volume` from the world file (m^3), 0 when absent. */
    double declaredVolume = 0.0;

    /** Bounds of all static geometry and the exploration box. */
    Aabb bounds() const;

    /**
     * Volume that normalises coverage: the declared volume when given (Cafe: 510 m^3 as in
     * the benchmark config and the paper, while its box holds 517.5), else the box's volume.
     */
    double explorationVolume() const {
        return declaredVolume > 0.0 ? declaredVolume : explorationBox.volume();
    }
};

/**
 * Loads a world file (YAML, format in README.md). Mesh paths are relative to the world file.
 * Throws InputError naming the file and, where known, the line.
 */
WorldSpec loadWorldFile(const std::string& path);

/** A built-in world name ("exhibition") or a path to a world file -> the world file's path. */
std::string resolveWorldPath(const std::string& nameOrPath);

/** Names of the worlds in share/daep/worlds, sorted. */
std::vector<std::string> builtinWorldNames();

}  // namespace daep::world
