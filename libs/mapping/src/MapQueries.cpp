#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "MapImpl.h"

namespace daep::mapping {
namespace {

struct Interval {
    double lo, hi;
    bool empty() const { return lo > hi; }
};

/** Parameters t in [0, 1] where a + t d (one axis) lies in [lo, hi]. */
Interval paramsInside(double a, double d, double lo, double hi) {
    if (std::abs(d) < 1e-12) {
        return (a >= lo && a <= hi) ? Interval{0.0, 1.0} : Interval{1.0, 0.0};
    }
    double t0 = (lo - a) / d, t1 = (hi - a) / d;
    if (t0 > t1) {
        std::swap(t0, t1);
    }
    return {std::max(0.0, t0), std::min(1.0, t1)};
}

/**
 * Exact squared distance between segment a + t d (t in [0, 1]) and the box [lo, hi]. The
 * squared distance is convex and piecewise quadratic in t, with breaks where the segment
 * crosses a slab plane; each piece is minimised in closed form.
 */
double segmentBoxDistance2(const Eigen::Vector3d& a, const Eigen::Vector3d& d,
                           const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    // Unused slots stay at 1 and only add empty pieces.
    std::array<double, 8> breaks{};
    breaks.fill(1.0);
    breaks[0] = 0.0;
    std::size_t n = 1;
    for (int i = 0; i < 3; ++i) {
        if (d[i] == 0.0) {
            continue;
        }
        for (double plane : {lo[i], hi[i]}) {
            const double t = (plane - a[i]) / d[i];
            if (t > 0.0 && t < 1.0) {
                breaks[n++] = t;
            }
        }
    }
    std::sort(breaks.begin(), breaks.end());

    double best = std::numeric_limits<double>::infinity();
    for (std::size_t s = 0; s + 1 < breaks.size(); ++s) {
        const double t0 = breaks[s], t1 = breaks[s + 1];
        const double tm = 0.5 * (t0 + t1);
        // On this piece each axis is below, inside or above its slab: sum of (e + t d)^2.
        double qa = 0.0, qb = 0.0, qc = 0.0;
        for (int i = 0; i < 3; ++i) {
            const double pm = a[i] + tm * d[i];
            const double bound = pm < lo[i] ? lo[i] : (pm > hi[i] ? hi[i] : pm);
            if (bound == pm) {
                continue;
            }
            const double e = a[i] - bound;
            qa += d[i] * d[i];
            qb += 2.0 * e * d[i];
            qc += e * e;
        }
        double t = qa > 0.0 ? -qb / (2.0 * qa) : t0;
        t = std::clamp(t, t0, t1);
        best = std::min(best, std::max(0.0, (qa * t + qb) * t + qc));
    }
    return best;
}

/** The first x in [from, to] whose bit is 0, else to + 1. */
int firstClearBit(const std::uint64_t* bits, int from, int to) {
    for (int w = from >> 6; (w << 6) <= to; ++w) {
        std::uint64_t clear = ~bits[w];
        if ((w << 6) < from)
            clear &= ~std::uint64_t(0) << (from & 63);
        if (clear != 0) {
            const int x = (w << 6) + __builtin_ctzll(clear);
            return x <= to ? x : to + 1;
        }
    }
    return to + 1;
}

/** Whether f(key) holds for every cell from lo to hi (keys, inclusive); stops at the first no. */
template <typename F>
bool everyCell(const octomap::OcTreeKey& lo, const octomap::OcTreeKey& hi, F&& f) {
    octomap::OcTreeKey k;
    for (int z = lo[2]; z <= hi[2]; ++z) {
        k[2] = octomap::key_type(z);
        for (int y = lo[1]; y <= hi[1]; ++y) {
            k[1] = octomap::key_type(y);
            for (int x = lo[0]; x <= hi[0]; ++x) {
                k[0] = octomap::key_type(x);
                if (!f(k))
                    return false;
            }
        }
    }
    return true;
}

}  // namespace

bool ExplorationMap::isBoxFree(const Eigen::Vector3d& center,
                               const Eigen::Vector3d& halfExtents) const {
    const Impl& m = *impl_;
    octomap::OcTreeKey lo, hi;
    if (!m.keyOf(center - halfExtents.cwiseAbs(), lo) ||
        !m.keyOf(center + halfExtents.cwiseAbs(), hi)) {
        return false;
    }
    return everyCell(lo, hi,
                     [&m](const octomap::OcTreeKey& k) { return m.stateAt(k) == CellState::Free; });
}

const std::uint64_t* ExplorationMap::Impl::passRow(int y, int z) const {
    const std::size_t row = std::size_t(y) + std::size_t(dims[1]) * std::size_t(z);
    std::uint64_t* bits = passBits.data() + row * std::size_t(passWords);
    if (!passStale[row])
        return bits;
    std::fill(bits, bits + passWords, 0);
    const std::int64_t first = std::int64_t(dims[0]) * std::int64_t(row);
    octomap::OcTreeKey k(0, octomap::key_type(gridMin[1] + y), octomap::key_type(gridMin[2] + z));
    for (int x = 1; x + 1 < dims[0]; ++x) {
        const std::size_t i = std::size_t(first + x);
        if (cells[i] != std::uint8_t(CellState::Free))
            continue;
        k[0] = octomap::key_type(gridMin[0] + x);
        if (guardGrazed && (flags[i] & kEverHit) && grazedSurface(k))
            continue;
        bits[x >> 6] |= std::uint64_t(1) << (x & 63);
    }
    passStale[row] = 0;
    return bits;
}

void ExplorationMap::Impl::passCellChanged(std::int64_t i) {
    const std::int64_t row = i / dims[0];
    const int y = int(row % dims[1]), z = int(row / dims[1]);
    passStale[std::size_t(row)] = 1;
    if (y > 0)
        passStale[std::size_t(row - 1)] = 1;
    if (y + 1 < dims[1])
        passStale[std::size_t(row + 1)] = 1;
    if (z > 0)
        passStale[std::size_t(row - dims[1])] = 1;
    if (z + 1 < dims[2])
        passStale[std::size_t(row + dims[1])] = 1;
}

void ExplorationMap::Impl::setGuardGrazed(bool guard) {
    if (guard != guardGrazed)
        std::fill(passStale.begin(), passStale.end(), 1);
    guardGrazed = guard;
}

/**
 * True when every cell whose box comes within `radius` of segment a-b is passable.
 * Walks the rows of cells along x; each row only scans the x range the capsule can reach, and
 * the exact cell-to-segment distance is computed only for cells that are not passable (for
 * isSegmentFree, the passing cells are skipped a word of pass bits at a time).
 *
 * The last cell that blocked a capsule is tried first: a planner's samples that fail, fail
 * mostly on the same obstacle (a tree stuck beside it tries thousands). It is tried only when
 * the scan would reach it, so the answer is the scan's.
 */
template <ExplorationMap::Impl::Passable P>
bool ExplorationMap::Impl::capsuleCellsAllowed(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                               double radius) const {
    const Impl& m = *this;
    const auto allowed = [&m](CellState s, std::int64_t i) {
        switch (P) {
            case Passable::Free:
                return s == CellState::Free;
            case Passable::NotOccupied:
                return s != CellState::Occupied;
            case Passable::FreeOrImprint:
                break;
        }
        return s == CellState::Free || (i >= 0 && m.isImprint(i));
    };
    const double r = std::max(0.0, radius);
    const double res = m.tree.getResolution();
    const Eigen::Vector3d d = b - a;
    octomap::OcTreeKey lo, hi;
    if (!m.keyOf(a.cwiseMin(b).array() - r, lo) || !m.keyOf(a.cwiseMax(b).array() + r, hi)) {
        return false;
    }
    const double r2 = r * r;
    // The x keys the scan visits in row (y, z); false when the capsule misses the row.
    const auto layerSpan = [&](int z) {
        const double z0 = m.cellLow(octomap::key_type(z));
        return paramsInside(a.z(), d.z(), z0 - r, z0 + res + r);
    };
    const auto rowSpan = [&](const Interval& tz, int y, int& xFirst, int& xLast, bool& offTree) {
        const double y0 = m.cellLow(octomap::key_type(y));
        const Interval ty = paramsInside(a.y(), d.y(), y0 - r, y0 + res + r);
        const Interval t{std::max(tz.lo, ty.lo), std::min(tz.hi, ty.hi)};
        if (t.empty())
            return false;
        const double xa = a.x() + t.lo * d.x(), xb = a.x() + t.hi * d.x();
        octomap::key_type x0, x1;
        if (!m.axisKeyOf(std::min(xa, xb) - r, x0) || !m.axisKeyOf(std::max(xa, xb) + r, x1)) {
            offTree = true;
            return false;
        }
        xFirst = std::max<int>(x0, lo[0]);
        xLast = std::min<int>(x1, hi[0]);
        return xFirst <= xLast;
    };
    const auto blocks = [&](const octomap::OcTreeKey& k, std::int64_t i) {
        const CellState state = i >= 0 ? CellState(m.cells[std::size_t(i)]) : m.stateAt(k);
        if (allowed(state, i) &&
            !(m.guardGrazed && (i < 0 || (m.flags[std::size_t(i)] & kEverHit)) &&
              m.grazedSurface(k, P == Passable::FreeOrImprint)))
            return false;
        const Eigen::Vector3d cellLo(m.cellLow(k[0]), m.cellLow(k[1]), m.cellLow(k[2]));
        return segmentBoxDistance2(a, d, cellLo, cellLo.array() + res) <= r2;
    };

    thread_local std::optional<octomap::OcTreeKey> lastBlocker;  // one per Passable
    if (lastBlocker) {
        const octomap::OcTreeKey& k = *lastBlocker;
        int xFirst = 0, xLast = -1;
        bool offTree = false;
        if (k[1] >= lo[1] && k[1] <= hi[1] && k[2] >= lo[2] && k[2] <= hi[2] &&
            rowSpan(layerSpan(k[2]), k[1], xFirst, xLast, offTree) && k[0] >= xFirst &&
            k[0] <= xLast && blocks(k, m.gridIndex(k)))
            return false;
    }
    octomap::OcTreeKey k;
    for (int z = lo[2]; z <= hi[2]; ++z) {
        k[2] = octomap::key_type(z);
        const Interval tz = layerSpan(z);
        if (tz.empty())
            continue;
        for (int y = lo[1]; y <= hi[1]; ++y) {
            k[1] = octomap::key_type(y);
            int xFirst = 0, xLast = -1;
            bool offTree = false;
            if (!rowSpan(tz, y, xFirst, xLast, offTree)) {
                if (offTree)
                    return false;
                continue;
            }
            // Dense indices along the row when all of it lies on the grid (both of its ends).
            k[0] = octomap::key_type(xLast);
            const bool lastOnGrid = m.gridIndex(k) >= 0;
            k[0] = octomap::key_type(xFirst);
            const std::int64_t rowStart = lastOnGrid ? m.gridIndex(k) : -1;
            const bool rowOnGrid = rowStart >= 0;
            const int gy = y - int(m.gridMin[1]), gz = z - int(m.gridMin[2]);
            if (P == Passable::Free && rowOnGrid && m.keepsPassBits(gy, gz)) {
                const std::uint64_t* bits = m.passRow(gy, gz);
                const int x0 = xFirst - int(m.gridMin[0]), x1 = xLast - int(m.gridMin[0]);
                for (int x = firstClearBit(bits, x0, x1); x <= x1;
                     x = firstClearBit(bits, x + 1, x1)) {
                    k[0] = octomap::key_type(x + int(m.gridMin[0]));
                    if (blocks(k, rowStart + (x - x0))) {
                        lastBlocker = k;
                        return false;
                    }
                }
                continue;
            }
            for (int x = xFirst; x <= xLast; ++x) {
                k[0] = octomap::key_type(x);
                if (blocks(k, rowOnGrid ? rowStart + (x - xFirst) : m.gridIndex(k))) {
                    lastBlocker = k;
                    return false;
                }
            }
        }
    }
    return true;
}

bool ExplorationMap::Impl::grazedSurface(const octomap::OcTreeKey& key, bool imprintsPass) const {
    const std::int64_t i = gridIndex(key);
    if (i < 0 || !(flags[std::size_t(i)] & kEverHit) || (flags[std::size_t(i)] & kFlown) ||
        cells[std::size_t(i)] != std::uint8_t(CellState::Free))
        return false;
    bool interior = true;  // all six neighbours on the grid: read them off it
    for (int axis = 0; axis < 3; ++axis) {
        const int c = int(key[axis]) - int(gridMin[axis]);
        interior = interior && c > 0 && c + 1 < dims[axis];
    }
    if (interior) {
        const auto surface = [&](std::int64_t j) {
            return cells[std::size_t(j)] != std::uint8_t(CellState::Free) &&
                   !(imprintsPass && isImprint(j));
        };
        const std::int64_t plane = std::int64_t(dims[0]) * dims[1];
        for (const std::int64_t step : {std::int64_t(1), std::int64_t(dims[0]), plane})
            if (surface(i - step) || surface(i + step))
                return true;
        return false;
    }
    for (int axis = 0; axis < 3; ++axis) {
        for (const int step : {-1, 1}) {
            octomap::OcTreeKey n = key;
            n[axis] = octomap::key_type(int(n[axis]) + step);
            if (stateAt(n) != CellState::Free)
                return true;
        }
    }
    return false;
}

bool ExplorationMap::isSegmentFree(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   double radius) const {
    return impl_->capsuleCellsAllowed<Impl::Passable::Free>(a, b, radius);
}

bool ExplorationMap::isSegmentFreeOrUnknown(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                            double radius) const {
    return impl_->capsuleCellsAllowed<Impl::Passable::NotOccupied>(a, b, radius);
}

bool ExplorationMap::isSegmentFreeThroughImprints(const Eigen::Vector3d& a,
                                                  const Eigen::Vector3d& b, double radius) const {
    return impl_->capsuleCellsAllowed<Impl::Passable::FreeOrImprint>(a, b, radius);
}

bool ExplorationMap::isSweptBoxClearOfNew(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& halfExtents) const {
    const Impl& m = *impl_;
    const Eigen::Vector3d h = halfExtents.cwiseAbs();
    octomap::OcTreeKey lo, hi;
    if (!m.keyOf(a.cwiseMin(b) - h, lo) || !m.keyOf(a.cwiseMax(b) + h, hi))
        return false;
    const double res = m.tree.getResolution();
    const Eigen::Vector3d d = b - a;
    return everyCell(lo, hi, [&](const octomap::OcTreeKey& k) {
        if (m.stateAt(k) != CellState::Occupied)
            return true;
        // The box meets a cell where the segment meets the cell grown by the box.
        const Eigen::Vector3d cellLo(m.cellLow(k[0]), m.cellLow(k[1]), m.cellLow(k[2]));
        const Eigen::Vector3d grownLo = cellLo - h, grownHi = cellLo.array() + res + h.array();
        const bool metAtStart =
            (a.array() >= grownLo.array()).all() && (a.array() <= grownHi.array()).all();
        return metAtStart || segmentBoxDistance2(a, d, grownLo, grownHi) > 0.0;
    });
}

double ExplorationMap::castRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& unitDir,
                               double maxRange) const {
    const Impl& m = *impl_;
    octomap::OcTreeKey key;
    const double norm = unitDir.norm();
    if (!m.keyOf(origin, key) || !(norm > 0.0) || !(maxRange > 0.0)) {
        return std::max(0.0, maxRange);
    }
    if (m.stateAt(key) == CellState::Occupied) {
        return 0.0;
    }
    const Eigen::Vector3d dir = unitDir / norm;
    const double res = m.tree.getResolution();
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::array<int, 3> step{};
    std::array<double, 3> tNext{}, tDelta{};
    for (int i = 0; i < 3; ++i) {
        const double low = m.cellLow(key[i]);
        if (dir[i] > 0.0) {
            step[std::size_t(i)] = 1;
            tNext[std::size_t(i)] = (low + res - origin[i]) / dir[i];
        } else if (dir[i] < 0.0) {
            step[std::size_t(i)] = -1;
            tNext[std::size_t(i)] = (low - origin[i]) / dir[i];
        } else {
            tNext[std::size_t(i)] = kInf;
        }
        tDelta[std::size_t(i)] = dir[i] != 0.0 ? res / std::abs(dir[i]) : kInf;
    }
    constexpr int kKeyMax = std::numeric_limits<octomap::key_type>::max();
    for (;;) {
        const std::size_t axis =
            std::size_t(std::min_element(tNext.begin(), tNext.end()) - tNext.begin());
        const double t = tNext[axis];
        if (t > maxRange) {
            return maxRange;
        }
        const int next = int(key[axis]) + step[axis];
        if (next < 0 || next > kKeyMax) {
            return maxRange;
        }
        key[axis] = octomap::key_type(next);
        tNext[axis] += tDelta[axis];
        if (m.stateAt(key) == CellState::Occupied) {
            return std::max(0.0, t);
        }
    }
}

}  // namespace daep::mapping
