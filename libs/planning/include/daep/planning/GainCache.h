#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace daep::planning {

/** A viewpoint whose gain was ray cast, with its best yaw. */
struct CachedGain {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    double yaw = 0.0;
    double gain = 0.0;
    bool alive = true;
};

/**
 * AEP's gain cache: viewpoints with high gain in a uniform hash grid (cells of `cellSize`), so
 * radius queries touch only the few cells around the query. Ids are stable; removal marks an
 * entry dead and unlinks it from the grid. Query results are ordered by distance, then id, so
 * they are deterministic. While the cache holds fewer entries than a query has cells to look
 * up, the query scans the live entries instead, keeping those in the cells it would look up:
 * the same entries, without the hash lookups.
 */
class GainCache {
public:
    explicit GainCache(double cellSize = 1.0);

    int insert(const Eigen::Vector3d& position, double yaw, double gain);
    void remove(int id);
    void update(int id, double yaw, double gain);

    /** Live entries within `radius` of p, nearest first, at most `maxCount` of them. */
    std::vector<int> near(const Eigen::Vector3d& p, double radius,
                          std::size_t maxCount = SIZE_MAX) const;

    /** Ids of all live entries, in insertion order. */
    std::vector<int> liveIds() const;

    const CachedGain& entry(int id) const { return entries_[static_cast<std::size_t>(id)]; }
    std::size_t size() const { return live_.size(); }
    void clear();

private:
    using Key = std::uint64_t;
    Key keyOf(const Eigen::Vector3i& cell) const;
    Eigen::Vector3i cellOf(const Eigen::Vector3d& p) const;

    double cellSize_;
    std::vector<CachedGain> entries_;
    std::vector<Eigen::Vector3i> cells_;  ///< each entry's grid cell
    std::unordered_map<Key, std::vector<int>> grid_;
    std::vector<int> live_;          ///< live ids, in no particular order
    std::vector<std::size_t> slot_;  ///< where each live id sits in live_
};

}  // namespace daep::planning
