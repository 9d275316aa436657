#include <array>
#include <cstdint>
#include <queue>

#include "MapImpl.h"

namespace daep::mapping {

std::vector<Eigen::Vector3d> ExplorationMap::frontierViewpoints(
    const Eigen::Vector3d& from, const std::function<bool(const Eigen::Vector3d&)>& usable,
    int reach, double spacing, std::size_t maxViewpoints) const {
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
    // Whether an unknown cell inside the box lies within `reach` cells of i along an axis,
    // with free cells between: the camera at i sees into the unknown.
    const auto seesUnknown = [&](std::int64_t i) {
        for (std::size_t a = 0; a < 3; ++a)
            for (const int dir : {-1, 1}) {
                std::int64_t c = i / stride[a] % dims[a], j = i;
                for (int step = 1; step <= reach; ++step) {
                    c += dir;
                    if (c < 0 || c >= dims[a])
                        break;
                    j += dir * stride[a];
                    const CellState s = stateOf(j);
                    if (s == CellState::Unknown && inBox(j))
                        return true;
                    if (s != CellState::Free)
                        break;
                }
            }
        return false;
    };
    std::vector<bool> reached(m.cells.size(), false);
    std::queue<std::int64_t> open;
    reached[std::size_t(start)] = true;
    open.push(start);
    while (!open.empty() && viewpoints.size() < maxViewpoints) {
        const std::int64_t i = open.front();
        open.pop();
        forNeighbours(i, [&](std::int64_t j) {
            if (reached[std::size_t(j)] || !inBox(j) || stateOf(j) != CellState::Free)
                return;
            reached[std::size_t(j)] = true;
            if (usable(centre(j)))
                open.push(j);
        });
        if (i == start || !seesUnknown(i))
            continue;
        const Eigen::Vector3d p = centre(i);
        bool crowded = false;
        for (const Eigen::Vector3d& q : viewpoints)
            crowded = crowded || (q - p).norm() < spacing;
        if (!crowded)
            viewpoints.push_back(p);
    }
    return viewpoints;
}

}  // namespace daep::mapping
