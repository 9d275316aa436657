#include "daep/planning/FrequencyMap.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace daep::planning {

FrequencyMap::FrequencyMap(const Aabb& box, double cellSize)
    : origin_(box.min.head<2>()), cellSize_(cellSize) {
    if (!(cellSize > 0.0))
        throw std::invalid_argument("FrequencyMap: cell size must be > 0");
    nx_ = std::max(1, static_cast<int>(std::ceil(box.size().x() / cellSize - 1e-9)));
    ny_ = std::max(1, static_cast<int>(std::ceil(box.size().y() / cellSize - 1e-9)));
    counts_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), 0);
}

int FrequencyMap::cellIndex(const Eigen::Vector2d& xy) const {
    const Eigen::Vector2d local = (xy - origin_) / cellSize_;
    const int ix = static_cast<int>(std::floor(local.x()));
    const int iy = static_cast<int>(std::floor(local.y()));
    if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_)
        return -1;
    return iy * nx_ + ix;
}

void FrequencyMap::add(const Eigen::Vector2d& xy) {
    const int i = cellIndex(xy);
    if (i < 0)
        return;
    long& c = counts_[static_cast<std::size_t>(i)];
    maxCount_ = std::max(maxCount_, ++c);
}

double FrequencyMap::value(const Eigen::Vector2d& xy) const {
    const int i = cellIndex(xy);
    if (i < 0 || maxCount_ == 0)
        return 0.0;
    return static_cast<double>(counts_[static_cast<std::size_t>(i)]) /
           static_cast<double>(maxCount_);
}

}  // namespace daep::planning
