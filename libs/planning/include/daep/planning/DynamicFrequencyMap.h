#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "daep/common/Types.h"

namespace daep::planning {

/** Square cells over a box's x/y, numbered row by row from its lower corner. */
struct XyGrid {
    XyGrid() = default;
    XyGrid(const Aabb& box, double cellSize);

    /** The cell holding xy, or -1 outside the grid. */
    int index(const Eigen::Vector2d& xy) const;
    /** Whether cell (ix, iy) lies on the grid. */
    bool contains(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < nx && iy < ny; }
    Eigen::Vector2d center(int ix, int iy) const;
    std::size_t size() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny); }

    Eigen::Vector2d origin = Eigen::Vector2d::Zero();
    double cellSize = 1.0;
    int nx = 0;
    int ny = 0;
};

/**
 * DAEP's Dynamic Frequency Map: a grid over the exploration box's x/y (square cells) counting
 * where people have been observed. value() is the count of a cell over the largest count,
 * in [0, 1] (0 everywhere before the first observation); outside the grid it is 0.
 */
class DynamicFrequencyMap {
public:
    DynamicFrequencyMap() = default;
    DynamicFrequencyMap(const Aabb& box, double cellSize);

    /** Counts one observation of a person standing at xy (ignored outside the grid). */
    void add(const Eigen::Vector2d& xy);

    double value(const Eigen::Vector2d& xy) const;
    /** The same for a cell of grid(), numbered as XyGrid::index numbers them. */
    double value(std::size_t cell) const;

    const XyGrid& grid() const { return grid_; }
    double cellSize() const { return grid_.cellSize; }
    int width() const { return grid_.nx; }
    int height() const { return grid_.ny; }
    long maxCount() const { return maxCount_; }
    long count(int ix, int iy) const {
        return counts_[static_cast<std::size_t>(iy * grid_.nx + ix)];
    }

private:
    XyGrid grid_;
    std::vector<long> counts_;
    long maxCount_ = 0;
};

}  // namespace daep::planning
