#pragma once

#include <Eigen/Core>
#include <vector>

#include "daep/common/Types.h"

namespace daep::planning {

/**
 * DAEP's Dynamic Frequency Map: a grid over the exploration box's x/y (square cells) counting
 * where people have been observed. value() is the count of a cell over the largest count,
 * in [0, 1] (0 everywhere before the first observation); outside the grid it is 0.
 */
class FrequencyMap {
public:
    FrequencyMap() = default;
    FrequencyMap(const Aabb& box, double cellSize);

    /** Counts one observation of a person standing at xy (ignored outside the grid). */
    void add(const Eigen::Vector2d& xy);

    double value(const Eigen::Vector2d& xy) const;

    double cellSize() const { return cellSize_; }
    /** The grid's lower x/y corner. */
    const Eigen::Vector2d& origin() const { return origin_; }
    int width() const { return nx_; }
    int height() const { return ny_; }
    long maxCount() const { return maxCount_; }
    long count(int ix, int iy) const { return counts_[static_cast<std::size_t>(iy * nx_ + ix)]; }

private:
    int cellIndex(const Eigen::Vector2d& xy) const;  ///< -1 outside

    Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
    double cellSize_ = 1.0;
    int nx_ = 0;
    int ny_ = 0;
    std::vector<long> counts_;
    long maxCount_ = 0;
};

}  // namespace daep::planning
