#include <algorithm>
#include <array>
#include <cstdint>
#include <queue>

#include "MapImpl.h"

namespace daep::mapping {

/**
 * Breadth-first over the known free cells inside the box, by face steps from `start`: a cell
 * is entered when `usable` holds at its centre. Each entered cell is passed to `visit` (the
 * start first, whatever it holds) until `visit` returns true; returns that cell, or -1. With
 * `parents`, each entered cell's predecessor (the start's is itself).
 */
std::int64_t ExplorationMap::Impl::walkFreeCells(
    std::int64_t start, const std::function<bool(const Eigen::Vector3d&)>& usable,
    const std::function<bool(std::int64_t)>& visit, std::vector<std::int64_t>* parents) const {
    const std::array<std::int64_t, 3> size{dims[0], dims[1], dims[2]};
    const std::array<std::int64_t, 3> stride{1, size[0], size[0] * size[1]};
    if (parents != nullptr)
        parents->assign(cells.size(), -1);
    std::vector<bool> reached(cells.size(), false);
    std::queue<std::int64_t> open;
    reached[std::size_t(start)] = true;
    if (parents != nullptr)
        (*parents)[std::size_t(start)] = start;
    open.push(start);
    while (!open.empty()) {
        const std::int64_t i = open.front();
        open.pop();
        for (std::size_t a = 0; a < 3; ++a) {
            const std::int64_t c = i / stride[a] % size[a];
            for (const int dir : {-1, 1}) {
                if ((dir < 0 && c == 0) || (dir > 0 && c + 1 >= size[a]))
                    continue;
                const std::int64_t j = i + dir * stride[a];
                if (reached[std::size_t(j)] || !indexInBox(j) ||
                    CellState(cells[std::size_t(j)]) != CellState::Free)
                    continue;
                reached[std::size_t(j)] = true;
                if (!usable(cellCentre(j)))
                    continue;
                if (parents != nullptr)
                    (*parents)[std::size_t(j)] = i;
                open.push(j);
            }
        }
        if (visit(i))
            return i;
    }
    return -1;
}

bool ExplorationMap::Impl::indexInBox(std::int64_t i) const {
    const std::array<std::int64_t, 3> stride{1, dims[0], std::int64_t(dims[0]) * dims[1]};
    for (std::size_t a = 0; a < 3; ++a)
        if (!inBox[a][std::size_t(i / stride[a] % dims[a])])
            return false;
    return true;
}

Eigen::Vector3d ExplorationMap::Impl::cellCentre(std::int64_t i) const {
    const octomap::OcTreeKey k = keyOfIndex(i);
    return {tree.keyToCoord(k[0]), tree.keyToCoord(k[1]), tree.keyToCoord(k[2])};
}

std::vector<Eigen::Vector3d> ExplorationMap::frontierViewpoints(
    const Eigen::Vector3d& from, const std::function<bool(const Eigen::Vector3d&)>& usable,
    int reach, double spacing, std::size_t maxViewpoints) const {
    const Impl& m = *impl_;
    std::vector<Eigen::Vector3d> viewpoints;
    const std::int64_t start = m.gridIndex(from);
    if (start < 0 || maxViewpoints == 0)
        return viewpoints;
    const std::array<std::int64_t, 3> dims{m.dims[0], m.dims[1], m.dims[2]};
    const std::array<std::int64_t, 3> stride{1, dims[0], dims[0] * dims[1]};
    const auto stateOf = [&m](std::int64_t i) { return CellState(m.cells[std::size_t(i)]); };
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
                    if (s == CellState::Unknown && m.indexInBox(j))
                        return true;
                    if (s != CellState::Free)
                        break;
                }
            }
        return false;
    };
    m.walkFreeCells(start, usable, [&](std::int64_t i) {
        if (i == start || !seesUnknown(i))
            return false;
        const Eigen::Vector3d p = m.cellCentre(i);
        bool crowded = false;
        for (const Eigen::Vector3d& q : viewpoints)
            crowded = crowded || (q - p).norm() < spacing;
        if (!crowded)
            viewpoints.push_back(p);
        return viewpoints.size() >= maxViewpoints;
    });
    return viewpoints;
}

std::vector<Eigen::Vector3d> ExplorationMap::freeCellPath(
    const Eigen::Vector3d& from, const std::function<bool(const Eigen::Vector3d&)>& usable,
    const std::function<bool(const Eigen::Vector3d&)>& isGoal) const {
    const Impl& m = *impl_;
    std::vector<Eigen::Vector3d> path;
    const std::int64_t start = m.gridIndex(from);
    if (start < 0)
        return path;
    std::vector<std::int64_t> parents;
    std::int64_t i = m.walkFreeCells(
        start, usable, [&](std::int64_t c) { return c != start && isGoal(m.cellCentre(c)); },
        &parents);
    if (i < 0)
        return path;
    for (; i != start; i = parents[std::size_t(i)])
        path.push_back(m.cellCentre(i));
    path.push_back(from);
    std::reverse(path.begin(), path.end());
    return path;
}

}  // namespace daep::mapping
