#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace daep::world {

/**
 * The x, y, z of every vertex of a PLY file (ascii, binary_little_endian, binary_big_endian).
 * Throws InputError("<path>: <what is wrong>").
 */
std::vector<Eigen::Vector3d> readPlyPoints(const std::string& path);

/** Writes the points as a binary little-endian PLY of float x, y, z. Throws on I/O errors. */
void writePlyPoints(const std::string& path, const std::vector<Eigen::Vector3f>& points,
                    const std::string& comment);

}  // namespace daep::world
