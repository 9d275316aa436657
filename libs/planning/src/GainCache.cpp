#include "daep/planning/GainCache.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace daep::planning {

GainCache::GainCache(double cellSize) : cellSize_(cellSize) {
    if (!(cellSize > 0.0))
        throw std::invalid_argument("GainCache: cell size must be > 0");
}

GainCache::Key GainCache::keyOf(const Eigen::Vector3i& cell) const {
    // 21 bits per axis (offset to non-negative) covers +-1e6 cells.
    constexpr std::int64_t kOffset = 1 << 20;
    constexpr std::uint64_t kMask = (1u << 21) - 1;
    auto part = [&](int v) { return static_cast<std::uint64_t>(v + kOffset) & kMask; };
    return part(cell.x()) | (part(cell.y()) << 21) | (part(cell.z()) << 42);
}

Eigen::Vector3i GainCache::cellOf(const Eigen::Vector3d& p) const {
    return (p / cellSize_).array().floor().cast<int>();
}

int GainCache::insert(const Eigen::Vector3d& position, double yaw, double gain) {
    const int id = static_cast<int>(entries_.size());
    entries_.push_back({position, yaw, gain, true});
    cells_.push_back(cellOf(position));
    grid_[keyOf(cells_.back())].push_back(id);
    slot_.push_back(live_.size());
    live_.push_back(id);
    return id;
}

void GainCache::remove(int id) {
    CachedGain& e = entries_[static_cast<std::size_t>(id)];
    if (!e.alive)
        return;
    e.alive = false;
    std::vector<int>& bucket = grid_[keyOf(cells_[static_cast<std::size_t>(id)])];
    bucket.erase(std::find(bucket.begin(), bucket.end(), id));
    const std::size_t at = slot_[static_cast<std::size_t>(id)];
    live_[at] = live_.back();
    slot_[static_cast<std::size_t>(live_[at])] = at;
    live_.pop_back();
}

void GainCache::update(int id, double yaw, double gain) {
    CachedGain& e = entries_[static_cast<std::size_t>(id)];
    e.yaw = yaw;
    e.gain = gain;
}

std::vector<int> GainCache::near(const Eigen::Vector3d& p, double radius,
                                 std::size_t maxCount) const {
    std::vector<std::pair<double, int>> found;
    const Eigen::Vector3i lo = cellOf(p - Eigen::Vector3d::Constant(radius));
    const Eigen::Vector3i hi = cellOf(p + Eigen::Vector3d::Constant(radius));
    const double r2 = radius * radius;
    const auto consider = [&](int id) {
        const double d2 = (entry(id).position - p).squaredNorm();
        if (d2 <= r2)
            found.emplace_back(d2, id);
    };
    const Eigen::Vector3i span = hi - lo + Eigen::Vector3i::Ones();
    const double cellsToLookUp = double(span.x()) * double(span.y()) * double(span.z());
    if (double(live_.size()) < cellsToLookUp) {
        for (int id : live_) {
            const Eigen::Vector3i& c = cells_[static_cast<std::size_t>(id)];
            if ((c.array() >= lo.array()).all() && (c.array() <= hi.array()).all())
                consider(id);
        }
    } else {
        for (int x = lo.x(); x <= hi.x(); ++x)
            for (int y = lo.y(); y <= hi.y(); ++y)
                for (int z = lo.z(); z <= hi.z(); ++z) {
                    const auto it = grid_.find(keyOf({x, y, z}));
                    if (it == grid_.end())
                        continue;
                    for (int id : it->second)
                        consider(id);
                }
    }
    std::sort(found.begin(), found.end());
    std::vector<int> ids;
    for (std::size_t i = 0; i < found.size() && i < maxCount; ++i)
        ids.push_back(found[i].second);
    return ids;
}

std::vector<int> GainCache::liveIds() const {
    std::vector<int> ids;
    ids.reserve(live_.size());
    for (std::size_t i = 0; i < entries_.size(); ++i)
        if (entries_[i].alive)
            ids.push_back(static_cast<int>(i));
    return ids;
}

void GainCache::clear() {
    entries_.clear();
    cells_.clear();
    grid_.clear();
    live_.clear();
    slot_.clear();
}

}  // namespace daep::planning
