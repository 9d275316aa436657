#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "daep/world/WorldSpec.h"

namespace daep::world {

/**
 * Loads an OctoMap file, .bt (binary) or .ot (full: OcTree, ColorOcTree or OcTreeStamped), told
 * apart by the file's first line. Its occupied leaves (the tree's own occupancy threshold)
 * become solid boxes shifted by `offset`; free and unknown space stays free. Throws InputError
 * naming the file when it is missing, not an OctoMap, unreadable or has no occupied cell.
 */
VoxelMap loadOctomap(const std::string& path, const Eigen::Vector3d& offset);

/**
 * Loads the vertices of a PLY file (ascii, binary_little_endian or binary_big_endian; faces and
 * other elements are ignored) and makes every cell of a `voxelSize` grid (cells
 * [k voxelSize, (k + 1) voxelSize) in the file's frame) that holds at least one point solid,
 * then shifts the boxes by `offset`. Non-finite points are skipped. Throws InputError naming
 * the file for a missing or malformed file, or one without points.
 */
VoxelMap voxelisePointCloud(const std::string& path, double voxelSize,
                            const Eigen::Vector3d& offset);

/** A simulated terrestrial laser scanner, to make maps of a world as a scan of it would. */
struct LaserScanParams {
    std::vector<Eigen::Vector3d> stations;  ///< scanner positions
    double resolution = 0.1;                ///< OctoMap cell size (.bt / .ot), m
    double stepDeg = 0.5;                   ///< angular step in azimuth and elevation
    double maxRange = 30.0;                 ///< m; farther returns are dropped
};

struct LaserScanSummary {
    std::size_t rays = 0;
    std::size_t returns = 0;         ///< rays that hit the world within range
    std::size_t nodes = 0;           ///< OctoMap nodes written (0 for a point cloud)
    std::size_t occupiedLeaves = 0;  ///< of them, occupied leaves
};

/**
 * Scans the world's static geometry from each station (full sphere) and writes the result by
 * the extension of `outPath`: `.bt` a pruned max-likelihood OctoMap, `.ot` a full OctoMap with
 * occupancy probabilities, `.ply` the returns as a binary point cloud. Each return lies 1 mm
 * behind the surface it hit, inside the solid, as a real return is. Deterministic.
 */
LaserScanSummary scanWorldToFile(const WorldSpec& world, const LaserScanParams& params,
                                 const std::string& outPath);

}  // namespace daep::world
