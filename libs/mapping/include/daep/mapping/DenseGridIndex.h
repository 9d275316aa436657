#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>

namespace daep::mapping {

/** floor(v) as an int, without the libm call; v must lie within int's range. */
inline int floorToInt(double v) {
    const int t = int(v);
    return t - (double(t) > v);
}

/**
 * Point to cell index on the map's dense grid: the octree's key formula floor(p / resolution)
 * + offset, computed without the libm floor call. Inline, so that the planners' point queries
 * (millions per plan) cost an array lookup.
 */
struct DenseGridIndex {
    double scale = 0.0;  ///< 1 / resolution, as the octree's own factor
    /// Grid bounds in scaled coordinates (coordinate * scale): [low, high).
    std::array<int, 3> low{}, high{};
    std::array<int, 3> dims{};

    DenseGridIndex() = default;
    DenseGridIndex(double scale, const std::array<int, 3>& low, const std::array<int, 3>& dims)
        : scale(scale), low(low), dims(dims) {
        for (std::size_t a = 0; a < 3; ++a) {
            high[a] = low[a] + dims[a];
            lowBound_[a] = low[a];
            highBound_[a] = high[a];
        }
    }

    /** Index of the cell containing p, or -1 outside the grid (also for NaN). */
    std::int64_t operator()(const Eigen::Vector3d& p) const {
        std::array<int, 3> i{};
        for (std::size_t a = 0; a < 3; ++a) {
            const double v = p[Eigen::Index(a)] * scale;
            if (!(v >= lowBound_[a] && v < highBound_[a]))
                return -1;
            i[a] = floorToInt(v) - low[a];
        }
        return linear(i);
    }

    /**
     * operator()'s index for a point known to lie on the grid. Points p + r * d of one ray
     * (r ascending) are computed monotonically on each axis, so when the first and the last lie
     * on the grid, all between do.
     */
    std::int64_t onGrid(const Eigen::Vector3d& p) const {
        std::array<int, 3> i{};
        for (std::size_t a = 0; a < 3; ++a)
            i[a] = floorToInt(p[Eigen::Index(a)] * scale) - low[a];
        return linear(i);
    }

    /**
     * onGrid(p) through std::floor, the same index: in code built for SSE4.1 the floor is one
     * instruction (roundsd) where floorToInt takes four.
     */
    std::int64_t onGridFloored(const Eigen::Vector3d& p) const {
        std::array<int, 3> i{};
        for (std::size_t a = 0; a < 3; ++a)
            i[a] = int(std::floor(p[Eigen::Index(a)] * scale)) - low[a];
        return linear(i);
    }

private:
    /** The index of grid cell i (x fastest). */
    std::int64_t linear(const std::array<int, 3>& i) const {
        return i[0] + std::int64_t(dims[0]) * (i[1] + std::int64_t(dims[1]) * i[2]);
    }

    std::array<double, 3> lowBound_{}, highBound_{};  ///< low and high, converted once
};

}  // namespace daep::mapping
