#include "CellBoxes.h"

#include <algorithm>
#include <tuple>

namespace daep::world {
namespace {

/** Sort key for merging along `axis`: the extents across it, then the start along it. */
auto crossSectionThenStart(const CellBox& b, int axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    return std::make_tuple(b.lo[u], b.hi[u], b.lo[v], b.hi[v], b.lo[axis]);
}

std::vector<CellBox> mergeAlong(std::vector<CellBox> boxes, int axis) {
    std::sort(boxes.begin(), boxes.end(), [axis](const CellBox& a, const CellBox& b) {
        return crossSectionThenStart(a, axis) < crossSectionThenStart(b, axis);
    });
    std::vector<CellBox> out;
    out.reserve(boxes.size());
    for (const CellBox& b : boxes) {
        if (!out.empty()) {
            CellBox& last = out.back();
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const bool sameSection = last.lo[u] == b.lo[u] && last.hi[u] == b.hi[u] &&
                                     last.lo[v] == b.lo[v] && last.hi[v] == b.hi[v];
            if (sameSection && last.hi[axis] == b.lo[axis]) {
                last.hi[axis] = b.hi[axis];
                continue;
            }
        }
        out.push_back(b);
    }
    return out;
}

}  // namespace

std::vector<CellBox> mergeCellBoxes(std::vector<CellBox> boxes) {
    for (int axis = 0; axis < 3; ++axis)
        boxes = mergeAlong(std::move(boxes), axis);
    return boxes;
}

std::vector<Aabb> toMetres(const std::vector<CellBox>& boxes, double res,
                           const Eigen::Vector3d& offset) {
    std::vector<Aabb> out;
    out.reserve(boxes.size());
    for (const CellBox& b : boxes) {
        Aabb a;
        for (int k = 0; k < 3; ++k) {
            a.min[k] = offset[k] + double(b.lo[k]) * res;
            a.max[k] = offset[k] + double(b.hi[k]) * res;
        }
        out.push_back(a);
    }
    return out;
}

}  // namespace daep::world
