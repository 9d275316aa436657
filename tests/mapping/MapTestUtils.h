#pragma once

#include <octomap/OcTree.h>

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "daep/mapping/ExplorationMap.h"

namespace daep::mapping::test {

/** Centre of the cell with integer index i (cells are [i res, (i + 1) res)). */
inline double centre(int i, double res) {
    return (i + 0.5) * res;
}

inline Eigen::Vector3d cellCentre(const Eigen::Vector3i& i, double res) {
    return {centre(i.x(), res), centre(i.y(), res), centre(i.z(), res)};
}

/** Marks exactly the cell containing p occupied (origin and end point in the same cell). */
inline void occupy(ExplorationMap& map, const Eigen::Vector3d& p) {
    map.insertPointCloud(p, {p.cast<float>()});
}

/**
 * Frees n cells along +x starting at cell `first`: a ray longer than maxRange clears exactly
 * maxRange / res cells when it starts at a cell centre. Requires maxRange = n * res.
 */
inline void freeRow(ExplorationMap& map, const Eigen::Vector3i& first) {
    const Eigen::Vector3d o = cellCentre(first, map.resolution());
    map.insertPointCloud(o, {(o + Eigen::Vector3d(1000.0, 0.0, 0.0)).cast<float>()});
}

/** The octree's own answer for the cell containing p. */
inline CellState octreeState(const octomap::OcTree& tree, const Eigen::Vector3d& p) {
    const octomap::OcTreeNode* node = tree.search(p.x(), p.y(), p.z());
    if (node == nullptr) {
        return CellState::Unknown;
    }
    return tree.isNodeOccupied(node) ? CellState::Occupied : CellState::Free;
}

}  // namespace daep::mapping::test
