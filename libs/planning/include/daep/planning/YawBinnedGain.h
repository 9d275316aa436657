#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

#include "daep/planning/GainEvaluator.h"

namespace daep::mapping {
class ExplorationMap;
}

namespace daep::planning {

/** How unknown cells are weighted by what lies next to them (6-neighbourhood). */
struct CellWeights {
    double unknown = 1.0;   ///< an unknown cell with no known neighbour
    double frontier = 2.0;  ///< an unknown cell next to a free cell
    double surface = 4.0;   ///< an unknown cell next to both a free and an occupied cell
};

/**
 * DEP's gain: for each of `bins` headings (bin b faces yaw b * 2pi / bins), the weighted unknown
 * volume inside the camera's field of view centred on that heading, up to the gain range.
 *
 * Same ray cubature as GainEvaluator (rays on an azimuth x elevation grid, marched in radial
 * steps until an occupied cell or the exploration box stops them, each sample adding the exact
 * volume of its spherical shell element), but with one azimuth column per heading bin and each
 * unknown sample scaled by its CellWeights class: unknown cells bordering free space (frontier)
 * and cells bordering free and occupied space (likely unseen surface) are worth more.
 * With every cell unknown the gain of each bin is exactly range^3/3 * hfov * (cos phi_min -
 * cos phi_max).
 */
class YawBinnedGain {
public:
    YawBinnedGain(const GainParams& params, int bins, const CellWeights& weights);

    /** Gain per heading bin at p; columns set in `ignoredColumns` (bit k: column k) add 0. */
    std::vector<double> evaluate(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                                 std::uint64_t ignoredColumns = 0) const;

    /** Columns (one per bin, centred on its heading) at least half inside the view at `bin`. */
    std::uint64_t columnsSeenFrom(int bin) const;

    /** Weight of the cell containing q: 0 when known, else its CellWeights class. */
    double cellWeight(const mapping::ExplorationMap& map, const Eigen::Vector3d& q) const;

    int bins() const { return bins_; }
    double binYaw(int bin) const;
    /** The bin whose heading is closest to yaw. */
    int binOf(double yaw) const;

private:
    double columnGain(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                      int column) const;

    GainParams params_;
    CellWeights weights_;
    int bins_ = 32;
    double binWidth_ = 0.0;
    RayCubature cubature_;
    /** Field-of-view window: fraction of column (bin + offset) seen at a bin's heading. */
    std::vector<std::pair<int, double>> window_;
};

}  // namespace daep::planning
