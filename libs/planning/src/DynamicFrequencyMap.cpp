#include "daep/planning/DynamicFrequencyMap.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace daep::planning {

XyGrid::XyGrid(const Aabb& box, double cellSize) : origin(box.min.head<2>()), cellSize(cellSize) {
    if (!(cellSize > 0.0))
        throw std::invalid_argument("DynamicFrequencyMap: cell size must be > 0");
    nx = std::max(1, static_cast<int>(std::ceil(box.size().x() / cellSize - 1e-9)));
    ny = std::max(1, static_cast<int>(std::ceil(box.size().y() / cellSize - 1e-9)));
}

int XyGrid::index(const Eigen::Vector2d& xy) const {
    const Eigen::Vector2d local = (xy - origin) / cellSize;
    const int ix = static_cast<int>(std::floor(local.x()));
    const int iy = static_cast<int>(std::floor(local.y()));
    if (!contains(ix, iy))
        return -1;
    return iy * nx + ix;
}

Eigen::Vector2d XyGrid::center(int ix, int iy) const {
    return origin + cellSize * Eigen::Vector2d(ix + 0.5, iy + 0.5);
}

DynamicFrequencyMap::DynamicFrequencyMap(const Aabb& box, double cellSize)
    : grid_(box, cellSize), counts_(grid_.size(), 0) {}

void DynamicFrequencyMap::add(const Eigen::Vector2d& xy) {
    const int i = grid_.index(xy);
    if (i < 0)
        return;
    long& c = counts_[static_cast<std::size_t>(i)];
    maxCount_ = std::max(maxCount_, ++c);
}

double DynamicFrequencyMap::value(const Eigen::Vector2d& xy) const {
    const int i = grid_.index(xy);
    return i < 0 ? 0.0 : value(static_cast<std::size_t>(i));
}

double DynamicFrequencyMap::value(std::size_t cell) const {
    if (maxCount_ == 0)
        return 0.0;
    return static_cast<double>(counts_[cell]) / static_cast<double>(maxCount_);
}

}  // namespace daep::planning
