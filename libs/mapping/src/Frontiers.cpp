#include <array>
#include <cstdint>
#include <queue>

#include "MapImpl.h"

namespace daep::mapping {
namespace {

constexpr std::int64_t kNone = -1;

}  // namespace

std::vector<Eigen::Vector3d> ExplorationMap::frontierViewpoints(
    const Eigen::Vector3d& from, const std::function<bool(const Eigen::Vector3d&)>& usable,
    int maxBack, double spacing, std::size_t maxViewpoints) const {
    const Impl& m = *impl_;
    std::vector<Eigen::Vector3d> viewpoints;
    const std::int64_t start = m.gridIndex(from);
    if (start < 0)
        return viewpoints;
    const std::array<std::int64_t, 3> dims{m.dims[0], m.dims[1], m.dims[2]};
    const std::array<std::int64_t, 3> stride{1, dims[0], dims[0] * dims[1]};
    const auto inBox = [&m, &dims, &stride](std::int64_t i) {
        for (std::size_t a = 0; a < 3; ++a)
            if (!m.inBox[a][std::size_t(i / stride[a] % dims[a])])
                return false;
        return true;
    };
    const auto stateOf = [&m](std::int64_t i) { return CellState(m.cells[std::size_t(i)]); };
    const auto centre = [&m](std::int64_t i) {
        const octomap::OcTreeKey k = m.keyOfIndex(i);
        return Eigen::Vector3d(m.tree.keyToCoord(k[0]), m.tree.keyToCoord(k[1]),
                               m.tree.keyToCoord(k[2]));
    };
    // Face neighbours of i inside the grid, visited through f(j).
    const auto forNeighbours = [&dims, &stride](std::int64_t i, auto&& f) {
        for (std::size_t a = 0; a < 3; ++a) {
            const std::int64_t c = i / stride[a] % dims[a];
            if (c > 0)
                f(i - stride[a]);
            if (c + 1 < dims[a])
                f(i + stride[a]);
        }
    };
    std::vector<std::int64_t> parent(m.cells.size(), kNone - 1);  // kNone - 1: not reached
    std::queue<std::int64_t> open;
    parent[std::size_t(start)] = kNone;
    open.push(start);
    while (!open.empty() && viewpoints.size() < maxViewpoints) {
        const std::int64_t i = open.front();
        open.pop();
        bool frontier = false;
        forNeighbours(i, [&](std::int64_t j) {
            if (!inBox(j))
                return;
            const CellState s = stateOf(j);
            frontier = frontier || (s == CellState::Unknown && i != start);
            if (s == CellState::Free && parent[std::size_t(j)] == kNone - 1) {
                parent[std::size_t(j)] = i;
                open.push(j);
            }
        });
        if (!frontier)
            continue;
        std::int64_t v = i;
        for (int back = 0; back <= maxBack && v != kNone; ++back, v = parent[std::size_t(v)]) {
            const Eigen::Vector3d p = centre(v);
            if (!usable(p))
                continue;
            bool crowded = false;
            for (const Eigen::Vector3d& q : viewpoints)
                crowded = crowded || (q - p).norm() < spacing;
            if (!crowded)
                viewpoints.push_back(p);
            break;
        }
    }
    return viewpoints;
}

}  // namespace daep::mapping
