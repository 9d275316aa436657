#pragma once

#include <Eigen/Core>
#include <array>
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

    /** Index of the cell containing p, or -1 outside the grid (also for NaN). */
    std::int64_t operator()(const Eigen::Vector3d& p) const {
        std::array<int, 3> i{};
        for (std::size_t a = 0; a < 3; ++a) {
            const double v = p[Eigen::Index(a)] * scale;
            if (!(v >= low[a] && v < high[a]))
                return -1;
            i[a] = floorToInt(v) - low[a];
        }
        return i[0] + std::int64_t(dims[0]) * (i[1] + std::int64_t(dims[1]) * i[2]);
    }
};

}  // namespace daep::mapping
