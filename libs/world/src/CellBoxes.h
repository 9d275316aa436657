#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "daep/world/WorldSpec.h"

namespace daep::world {

/** A box of whole cells: cells lo .. hi - 1 on each axis. */
struct CellBox {
    std::array<std::int64_t, 3> lo{}, hi{};
};

/**
 * Merges disjoint cell boxes that share a face of the same extent into one, along x, then y,
 * then z (a row of cells becomes a bar, bars a slab, ...). The union is unchanged.
 * Deterministic: the result does not depend on the input order.
 */
std::vector<CellBox> mergeCellBoxes(std::vector<CellBox> boxes);

/** The boxes in metres: cell k spans [offset + k res, offset + (k + 1) res). */
std::vector<Aabb> toMetres(const std::vector<CellBox>& boxes, double res,
                           const Eigen::Vector3d& offset);

}  // namespace daep::world
