#include "daep/world/ReachableVolume.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include "Shapes.h"
#include "daep/common/Error.h"
#include "daep/world/RayCaster.h"

namespace daep::world {
namespace {

constexpr double kTouch = 1e-6;  ///< of a cell: a cell that only touches geometry is not solid
constexpr double kTol = 1e-9;    ///< m: centres on a bound are inside it
constexpr std::size_t kMaxCells = std::size_t(1) << 30;

enum Flag : std::uint8_t {
    kSolid = 1,
    kCandidate = 2,  ///< inside the bounds of a shape that needs the exact test
    kDrone = 4,
    kBlocked = 8,  ///< tested for the drone and not clear
    kSeen = 16,    ///< free and connected to the drone cells
};

/** One axis of the grid: the cells with keys first .. first + count - 1. */
struct Axis {
    std::int64_t first = 0;
    int count = 0;
    std::vector<char> inBox;       ///< centre in [min, max)
    std::vector<char> inSampling;  ///< centre in the box shrunk by the robot radius
};

/** Cell range [lo, hi] along one axis (lo > hi when empty). */
struct Span {
    int lo = 0, hi = -1;
};

Axis makeAxis(double min, double max, double res, double ring, double radius) {
    Axis a;
    const double lo = min - ring, hi = max + ring;
    const auto centre = [res](std::int64_t k) { return (double(k) + 0.5) * res; };
    a.first = std::int64_t(std::floor(lo / res)) - 1;
    while (centre(a.first) < lo)
        ++a.first;
    while (centre(a.first + a.count) < hi)
        ++a.count;
    // As the planners' shrink(): a box thinner than twice the radius shrinks to its middle.
    double sLo = min + radius, sHi = max - radius;
    if (sLo > sHi)
        sLo = sHi = 0.5 * (min + max);
    for (int i = 0; i < a.count; ++i) {
        const double c = centre(a.first + i);
        a.inBox.push_back(c >= min && c < max);
        a.inSampling.push_back(c >= sLo - kTol && c <= sHi + kTol);
    }
    return a;
}

class Grid {
public:
    Grid(const Aabb& box, const ReachParams& p) : res_(p.resolution) {
        for (int a = 0; a < 3; ++a)
            axes_[a] = makeAxis(box.min[a], box.max[a], res_, res_ + p.margin, p.robotRadius);
        const std::size_t n =
            std::size_t(axes_[0].count) * std::size_t(axes_[1].count) * std::size_t(axes_[2].count);
        if (n > kMaxCells) {
            std::ostringstream err;
            err << "reachable volume: the box needs " << n << " cells at resolution " << res_
                << " m, more than " << kMaxCells;
            throw InputError(err.str());
        }
        flags_.assign(n, 0);
    }

    std::size_t size() const { return flags_.size(); }
    int count(int axis) const { return axes_[axis].count; }
    double res() const { return res_; }

    std::size_t index(const Eigen::Vector3i& c) const {
        return std::size_t(c.x()) +
               std::size_t(axes_[0].count) *
                   (std::size_t(c.y()) + std::size_t(axes_[1].count) * std::size_t(c.z()));
    }
    Eigen::Vector3i cell(std::size_t i) const {
        const auto nx = std::size_t(axes_[0].count), ny = std::size_t(axes_[1].count);
        return {int(i % nx), int((i / nx) % ny), int(i / (nx * ny))};
    }
    bool contains(const Eigen::Vector3i& c) const {
        for (int a = 0; a < 3; ++a)
            if (c[a] < 0 || c[a] >= axes_[a].count)
                return false;
        return true;
    }
    Eigen::Vector3d centre(const Eigen::Vector3i& c) const {
        Eigen::Vector3d p;
        for (int a = 0; a < 3; ++a)
            p[a] = (double(axes_[a].first + c[a]) + 0.5) * res_;
        return p;
    }
    /** The cell holding p, as octomap keys it (it may lie outside the grid). */
    Eigen::Vector3i cellOf(const Eigen::Vector3d& p) const {
        Eigen::Vector3i c;
        for (int a = 0; a < 3; ++a)
            c[a] = int(std::int64_t(std::floor(p[a] * (1.0 / res_))) - axes_[a].first);
        return c;
    }
    bool inBox(const Eigen::Vector3i& c) const {
        return axes_[0].inBox[c.x()] && axes_[1].inBox[c.y()] && axes_[2].inBox[c.z()];
    }
    bool inSampling(const Eigen::Vector3i& c) const {
        return axes_[0].inSampling[c.x()] && axes_[1].inSampling[c.y()] &&
               axes_[2].inSampling[c.z()];
    }

    /** The cells whose box overlaps (lo, hi) by more than touching, along one axis. */
    Span span(int axis, double lo, double hi) const {
        const double e = kTouch * res_;
        const Axis& a = axes_[axis];
        Span s;
        s.lo = int(std::max<std::int64_t>(std::int64_t(std::floor((lo + e) / res_)) - a.first, 0));
        s.hi = int(std::min<std::int64_t>(std::int64_t(std::ceil((hi - e) / res_)) - 1 - a.first,
                                          a.count - 1));
        return s;
    }

    /** Sets `flag` on every cell that overlaps the axis-aligned box. */
    void mark(const Eigen::AlignedBox3d& b, std::uint8_t flag) {
        const Span x = span(0, b.min().x(), b.max().x());
        const Span y = span(1, b.min().y(), b.max().y());
        const Span z = span(2, b.min().z(), b.max().z());
        for (int k = z.lo; k <= z.hi; ++k)
            for (int j = y.lo; j <= y.hi; ++j)
                for (int i = x.lo; i <= x.hi; ++i)
                    flags_[index({i, j, k})] |= flag;
    }

    /** The cell's box, less the touching margin, along one axis. */
    std::pair<double, double> bounds(int axis, int i) const {
        const double lo = double(axes_[axis].first + i) * res_, e = kTouch * res_;
        return {lo + e, lo + res_ - e};
    }

    std::uint8_t& operator[](std::size_t i) { return flags_[i]; }
    std::uint8_t operator[](std::size_t i) const { return flags_[i]; }
    bool has(std::size_t i, std::uint8_t flag) const { return (flags_[i] & flag) != 0; }

private:
    double res_;
    std::array<Axis, 3> axes_;
    std::vector<std::uint8_t> flags_;
};

const std::array<Eigen::Vector3i, 6> kFaceNeighbours = {
    Eigen::Vector3i(1, 0, 0),  Eigen::Vector3i(-1, 0, 0), Eigen::Vector3i(0, 1, 0),
    Eigen::Vector3i(0, -1, 0), Eigen::Vector3i(0, 0, 1),  Eigen::Vector3i(0, 0, -1)};

/** Rotation that maps the axes onto the axes: the box is its own bounding box. */
bool isAxisAligned(const Eigen::Matrix3d& r) {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const double v = std::abs(r(i, j));
            if (v > 1e-9 && v < 1.0 - 1e-9)
                return false;
        }
    return true;
}

Eigen::AlignedBox3d boxBounds(const BoxShape& b) {
    const Eigen::Vector3d reach = b.pose.linear().cwiseAbs() * (0.5 * b.size);
    return {b.pose.translation() - reach, b.pose.translation() + reach};
}

Eigen::AlignedBox3d cylinderBounds(const CylinderShape& c) {
    Eigen::AlignedBox3d b;
    for (const auto& v : cylinderPrismVertices(c, 1.0 / std::cos(M_PI / kCylinderSegments)))
        b.extend(v);
    return b;
}

double distanceToInterval(double x, const std::pair<double, double>& interval) {
    return std::max({interval.first - x, x - interval.second, 0.0});
}

/**
 * An upright cylinder's cells: solid where the cell comes closer to the axis than the radius,
 * candidates where it only meets the collision checker's circumscribed prism.
 */
void markUprightCylinder(const CylinderShape& c, Grid& grid) {
    const Eigen::AlignedBox3d b = cylinderBounds(c);
    const Span x = grid.span(0, b.min().x(), b.max().x());
    const Span y = grid.span(1, b.min().y(), b.max().y());
    const Span z = grid.span(2, b.min().z(), b.max().z());
    const double outer = c.radius / std::cos(M_PI / kCylinderSegments);
    const Eigen::Vector3d axis = c.pose.translation();
    for (int j = y.lo; j <= y.hi; ++j)
        for (int i = x.lo; i <= x.hi; ++i) {
            const double d = std::hypot(distanceToInterval(axis.x(), grid.bounds(0, i)),
                                        distanceToInterval(axis.y(), grid.bounds(1, j)));
            const std::uint8_t flag = d < c.radius ? kSolid : d <= outer ? kCandidate : 0;
            for (int k = z.lo; k <= z.hi && flag; ++k)
                grid[grid.index({i, j, k})] |= flag;
        }
}

bool isUpright(const CylinderShape& c) {
    return std::abs(c.pose.linear()(2, 2)) > 1.0 - 1e-12;
}

/**
 * Marks the solid cells: axis-aligned boxes (voxel maps' too) straight from their bounds, upright
 * cylinders from the distance to their axis, every other shape's bounds as candidates that the
 * exact overlap test then decides.
 */
void markSolid(const WorldSpec& world, Grid& grid) {
    for (const auto& b : world.boxes)
        grid.mark(boxBounds(b), isAxisAligned(b.pose.linear()) ? kSolid : kCandidate);
    for (const auto& c : world.cylinders) {
        if (isUpright(c))
            markUprightCylinder(c, grid);
        else
            grid.mark(cylinderBounds(c), kCandidate);
    }
    for (const auto& m : world.meshes)
        for (const auto& t : m.triangles) {
            Eigen::AlignedBox3d b;
            for (int v = 0; v < 3; ++v)
                b.extend(m.vertices[std::size_t(t[v])].cast<double>());
            grid.mark(b, kCandidate);
        }
    for (const auto& map : world.voxelMaps)
        for (const auto& b : map.boxes)
            grid.mark({b.min, b.max}, kSolid);
    const StaticCollisionChecker exact(world);
    const Eigen::Vector3d size = Eigen::Vector3d::Constant(grid.res() * (1.0 - 2.0 * kTouch));
    for (std::size_t i = 0; i < grid.size(); ++i)
        if ((grid[i] & (kSolid | kCandidate)) == kCandidate &&
            exact.overlaps(grid.centre(grid.cell(i)), size, 0.0))
            grid[i] |= kSolid;
}

/** Cell offsets whose box lies closer than `radius` to a cell's centre. */
std::vector<Eigen::Vector3i> clearanceOffsets(double radius, double res) {
    std::vector<Eigen::Vector3i> out;
    const int reach = int(std::ceil(radius / res + 0.5));
    for (int z = -reach; z <= reach; ++z)
        for (int y = -reach; y <= reach; ++y)
            for (int x = -reach; x <= reach; ++x) {
                const Eigen::Vector3d gap =
                    (Eigen::Vector3d(std::abs(x), std::abs(y), std::abs(z)).array() - 0.5)
                        .max(0.0) *
                    res;
                if (gap.norm() < radius - kTol)
                    out.emplace_back(x, y, z);
            }
    return out;
}

class DroneFill {
public:
    DroneFill(Grid& grid, double radius)
        : grid_(grid), offsets_(clearanceOffsets(radius, grid.res())) {
        for (const auto& d : offsets_) {
            reach_ = std::max(reach_, d.cwiseAbs().maxCoeff());
            steps_.push_back(std::ptrdiff_t(d.x()) +
                             std::ptrdiff_t(grid.count(0)) *
                                 (std::ptrdiff_t(d.y()) + std::ptrdiff_t(grid.count(1)) * d.z()));
        }
    }

    bool isClear(const Eigen::Vector3i& c) const {
        if (farFromTheEdge(c)) {  // the hot path: every offset lies in the grid
            const std::ptrdiff_t i = std::ptrdiff_t(grid_.index(c));
            for (const std::ptrdiff_t step : steps_)
                if (grid_.has(std::size_t(i + step), kSolid))
                    return false;
            return true;
        }
        for (const auto& d : offsets_) {
            const Eigen::Vector3i n = c + d;
            if (grid_.contains(n) && grid_.has(grid_.index(n), kSolid))
                return false;
        }
        return true;
    }

    /** Marks kDrone on the cells the drone reaches from `seed`; returns them in fill order. */
    std::vector<std::uint32_t> fill(const Eigen::Vector3i& seed) {
        std::vector<std::uint32_t> cells{std::uint32_t(grid_.index(seed))};
        grid_[cells[0]] |= kDrone;
        for (std::size_t head = 0; head < cells.size(); ++head) {
            const Eigen::Vector3i c = grid_.cell(cells[head]);
            for (const auto& d : kFaceNeighbours) {
                const Eigen::Vector3i n = c + d;
                if (!grid_.contains(n))
                    continue;
                const std::size_t i = grid_.index(n);
                if (grid_.has(i, kSolid | kDrone | kBlocked))
                    continue;
                if (grid_.inSampling(n) && isClear(n)) {
                    grid_[i] |= kDrone;
                    cells.push_back(std::uint32_t(i));
                } else {
                    grid_[i] |= kBlocked;
                }
            }
        }
        return cells;
    }

private:
    bool farFromTheEdge(const Eigen::Vector3i& c) const {
        for (int a = 0; a < 3; ++a)
            if (c[a] < reach_ || c[a] >= grid_.count(a) - reach_)
                return false;
        return true;
    }

    Grid& grid_;
    std::vector<Eigen::Vector3i> offsets_;
    std::vector<std::ptrdiff_t> steps_;  ///< the offsets as steps of the cell index
    int reach_ = 0;
};

/** Marks kSeen on every non-solid cell 6-connected to the given (non-solid) cells. */
void fillFree(Grid& grid, std::vector<std::uint32_t> cells) {
    for (const auto i : cells)
        grid[i] |= kSeen;
    for (std::size_t head = 0; head < cells.size(); ++head) {
        const Eigen::Vector3i c = grid.cell(cells[head]);
        for (const auto& d : kFaceNeighbours) {
            const Eigen::Vector3i n = c + d;
            if (!grid.contains(n))
                continue;
            const std::size_t i = grid.index(n);
            if (!grid.has(i, kSolid | kSeen)) {
                grid[i] |= kSeen;
                cells.push_back(std::uint32_t(i));
            }
        }
    }
}

/**
 * Whether a seen cell shares a face, edge or corner with the (solid) cell. Not faces only: a
 * solid cell is solid when geometry overlaps any part of it, and rays reach its free part
 * through the free parts of its solid face neighbours (a wall's cell in a corner, a cylinder's
 * cell inside its bounding square, whose corner is free).
 */
bool touchesSeen(const Grid& grid, const Eigen::Vector3i& c) {
    for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x) {
                const Eigen::Vector3i n = c + Eigen::Vector3i(x, y, z);
                if (grid.contains(n) && grid.has(grid.index(n), kSeen))
                    return true;
            }
    return false;
}

/** Counts the drone's and the observable cells whose centre lies in the box. */
void countInBox(const Grid& grid, ReachableVolume& out) {
    for (int k = 0; k < grid.count(2); ++k)
        for (int j = 0; j < grid.count(1); ++j)
            for (int i = 0; i < grid.count(0); ++i) {
                const Eigen::Vector3i c(i, j, k);
                if (!grid.inBox(c))
                    continue;
                const std::size_t at = grid.index(c);
                if (grid.has(at, kDrone))
                    ++out.droneCells;
                if (grid.has(at, kSeen) || (grid.has(at, kSolid) && touchesSeen(grid, c)))
                    ++out.observableCells;
            }
}

/** The nearest non-solid cell to p by centre distance (the lowest index on a tie). */
Eigen::Vector3i nearestFree(const Grid& grid, const Eigen::Vector3d& p) {
    double best = std::numeric_limits<double>::infinity();
    std::size_t bestIndex = grid.size();
    for (std::size_t i = 0; i < grid.size(); ++i) {
        if (grid.has(i, kSolid))
            continue;
        const double d = (grid.centre(grid.cell(i)) - p).squaredNorm();
        if (d < best)
            best = d, bestIndex = i;
    }
    if (bestIndex == grid.size())
        throw InputError("reachable volume: every cell of the exploration box is solid");
    return grid.cell(bestIndex);
}

void validate(const ReachParams& p, const Aabb& box) {
    if (!(p.resolution > 0.0) || !std::isfinite(p.resolution))
        throw InputError("reachable volume: resolution must be > 0");
    if (!(p.robotRadius >= 0.0) || !std::isfinite(p.robotRadius))
        throw InputError("reachable volume: robot radius must be >= 0");
    if (!std::isfinite(p.climb) || !(p.margin >= 0.0) || !std::isfinite(p.margin))
        throw InputError("reachable volume: climb must be finite and margin >= 0");
    if (!box.min.allFinite() || !box.max.allFinite() || !(box.max.array() > box.min.array()).all())
        throw InputError("reachable volume: the exploration box must have max > min");
}

}  // namespace

ReachableVolume computeReachableVolume(const WorldSpec& world, const Eigen::Vector3d& start,
                                       const ReachParams& params) {
    validate(params, world.explorationBox);
    Grid grid(world.explorationBox, params);
    markSolid(world, grid);

    ReachableVolume out;
    out.gridCells = grid.size();
    const Eigen::Vector3d spawn = start + Eigen::Vector3d(0.0, 0.0, params.climb);
    Eigen::Vector3i seed = grid.cellOf(spawn);
    if (!grid.contains(seed) || grid.has(grid.index(seed), kSolid)) {
        seed = nearestFree(grid, spawn);
        out.seedMoved = true;
    }
    out.seed = grid.centre(seed);

    DroneFill drone(grid, params.robotRadius);
    out.seedClear = grid.inSampling(seed) && drone.isClear(seed);
    fillFree(grid, drone.fill(seed));

    countInBox(grid, out);
    const double cellVolume = std::pow(params.resolution, 3);
    const double volume = world.explorationVolume();
    out.observableVolume = double(out.observableCells) * cellVolume;
    out.droneVolume = double(out.droneCells) * cellVolume;
    out.reachablePercent = std::min(100.0, 100.0 * out.observableVolume / volume);
    out.dronePercent = std::min(100.0, 100.0 * out.droneVolume / volume);
    return out;
}

}  // namespace daep::world
