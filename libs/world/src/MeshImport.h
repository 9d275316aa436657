#pragma once

#include <Eigen/Geometry>
#include <string>

#include "daep/world/WorldSpec.h"

namespace daep::world {

/**
 * Reads a mesh file with assimp (OBJ, STL, DAE, ...), applies the file's own node transforms
 * and units, then `transform`, and appends its triangles to `out`. Returns false with `error`
 * set when assimp cannot read it.
 */
bool importMesh(const std::string& file, const Eigen::Affine3d& transform, TriangleMesh& out,
                std::string& error);

}  // namespace daep::world
