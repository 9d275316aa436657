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

bool ExplorationMap::Impl::isFrontierCell(int x, int y, int z) const {
    const auto at = [this](int cx, int cy, int cz) { return cells[cellIndex(cx, cy, cz)]; };
    if (at(x, y, z) != std::uint8_t(CellState::Unknown) || !touchesBox[0][std::size_t(x)] ||
        !touchesBox[1][std::size_t(y)] || !touchesBox[2][std::size_t(z)])
        return false;
    for (int cz = std::max(z - 1, 0); cz <= std::min(z + 1, dims[2] - 1); ++cz)
        for (int cy = std::max(y - 1, 0); cy <= std::min(y + 1, dims[1] - 1); ++cy)
            for (int cx = std::max(x - 1, 0); cx <= std::min(x + 1, dims[0] - 1); ++cx)
                if (at(cx, cy, cz) == std::uint8_t(CellState::Free))
                    return true;
    return false;
}

bool ExplorationMap::Impl::blockHasFrontier(int bx, int by, int bz) const {
    std::uint8_t& block = blocks[blockIndex(bx, by, bz)];
    if (!(block & kBlockStale))
        return block & kBlockHasFrontier;
    const auto span = [this](int b, std::size_t a) {
        return std::make_pair(b << kBlockShift, std::min((b + 1) << kBlockShift, dims[a]));
    };
    const auto [x0, x1] = span(bx, 0);
    const auto [y0, y1] = span(by, 1);
    const auto [z0, z1] = span(bz, 2);
    block = 0;
    for (int z = z0; z < z1; ++z)
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x)
                if (isFrontierCell(x, y, z)) {
                    block = kBlockHasFrontier;
                    return true;
                }
    return false;
}

void ExplorationMap::Impl::frontierCellChanged(std::int64_t i) {
    const std::array<int, 3> c = cellOfIndex(i);
    std::array<int, 3> lo{}, hi{};
    for (std::size_t a = 0; a < 3; ++a) {
        lo[a] = std::max(c[a] - 1, 0) >> kBlockShift;
        hi[a] = std::min(c[a] + 1, dims[a] - 1) >> kBlockShift;
    }
    for (int bz = lo[2]; bz <= hi[2]; ++bz)
        for (int by = lo[1]; by <= hi[1]; ++by)
            for (int bx = lo[0]; bx <= hi[0]; ++bx)
                blocks[blockIndex(bx, by, bz)] |= kBlockStale;
}

bool ExplorationMap::mayMeetUnknown(const Eigen::Vector3d& p, double range) const {
    const Impl& m = *impl_;
    // From outside the box a ray may cross unknown cells there before it enters: unsure.
    if (!box_.contains(p) || gridIndex_(p) < 0)
        return true;
    // Grid coordinates of the cell holding v on axis a, clamped to the grid.
    const auto cellOf = [&m](double v, std::size_t a) {
        const int c = floorToInt(v * m.pointIndex.scale) - m.pointIndex.low[a];
        return std::clamp(c, 0, m.dims[a] - 1);
    };
    std::array<int, 3> lo{}, hi{};
    for (std::size_t a = 0; a < 3; ++a) {
        const int own = cellOf(p[Eigen::Index(a)], a);
        lo[a] = std::max(own - 1, 0);
        hi[a] = std::min(own + 1, m.dims[a] - 1);
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
        for (int y = lo[1]; y <= hi[1]; ++y)
            for (int x = lo[0]; x <= hi[0]; ++x)
                if (m.cells[m.cellIndex(x, y, z)] == std::uint8_t(CellState::Unknown))
                    return true;
    // The samples lie in the box and within range: the blocks of their cells, grown by a cell
    // for rounding.
    for (std::size_t a = 0; a < 3; ++a) {
        const Eigen::Index e = Eigen::Index(a);
        lo[a] = std::max(cellOf(std::max(p[e] - range, box_.min[e]), a) - 1, 0);
        hi[a] = std::min(cellOf(std::min(p[e] + range, box_.max[e]), a) + 1, m.dims[a] - 1);
        lo[a] >>= Impl::kBlockShift;
        hi[a] >>= Impl::kBlockShift;
    }
    // Blocks farther from p than the range hold no sample (in cells, with two of slack).
    std::array<double, 3> u{};
    for (std::size_t a = 0; a < 3; ++a)
        u[a] = p[Eigen::Index(a)] * m.pointIndex.scale - m.pointIndex.low[a];
    const double reach = range * m.pointIndex.scale + 2.0;
    const auto gap = [&u](int b, std::size_t a) {
        const double low = double(b << Impl::kBlockShift), high = low + (1 << Impl::kBlockShift);
        const double d = std::max({low - u[a], 0.0, u[a] - high});
        return d * d;
    };
    for (int bz = lo[2]; bz <= hi[2]; ++bz)
        for (int by = lo[1]; by <= hi[1]; ++by)
            for (int bx = lo[0]; bx <= hi[0]; ++bx)
                if (gap(bx, 0) + gap(by, 1) + gap(bz, 2) <= reach * reach &&
                    m.blockHasFrontier(bx, by, bz))
                    return true;
    return false;
}

}  // namespace daep::mapping
