#include "daep/planning/YawBinnedGain.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "RayGeometry.h"
#include "daep/common/Types.h"
#include "daep/mapping/ExplorationMap.h"

namespace daep::planning {
using detail::exitDistance;
using detail::kTwoPi;

YawBinnedGain::YawBinnedGain(const GainParams& params, int bins, const CellWeights& weights)
    : params_(params), weights_(weights), bins_(bins) {
    if (bins < 1 || bins > 64)
        throw std::invalid_argument("YawBinnedGain: bins must be in [1, 64]");
    binWidth_ = kTwoPi / bins_;
    std::vector<double> centres(bins_);
    for (int i = 0; i < bins_; ++i)
        centres[i] = binYaw(i);  // column i spans its heading +- binWidth/2
    cubature_ = RayCubature(params, centres);
    // Columns are centred on the bin headings: column k spans [(k - 0.5) w, (k + 0.5) w].
    const double half = 0.5 * std::min(params.hfov, kTwoPi) / binWidth_;  // in columns
    const int reach = static_cast<int>(std::ceil(half + 0.5));
    for (int k = -reach; k <= reach; ++k) {
        const double overlap = std::min(half, k + 0.5) - std::max(-half, k - 0.5);
        if (overlap > 0.0)
            window_.emplace_back(k, overlap);
    }
}

double YawBinnedGain::binYaw(int bin) const {
    return wrapAngle(bin * binWidth_);
}

int YawBinnedGain::binOf(double yaw) const {
    const long b = std::lround(wrapAngle(yaw) / binWidth_);
    return static_cast<int>(((b % bins_) + bins_) % bins_);
}

double YawBinnedGain::cellWeight(const mapping::ExplorationMap& map,
                                 const Eigen::Vector3d& q) const {
    if (map.state(q) != mapping::CellState::Unknown)
        return 0.0;
    const double res = map.resolution();
    bool free = false;
    bool occupied = false;
    for (int a = 0; a < 3; ++a) {
        for (double s : {-res, res}) {
            Eigen::Vector3d n = q;
            n[a] += s;
            const mapping::CellState state = map.state(n);
            free = free || state == mapping::CellState::Free;
            occupied = occupied || state == mapping::CellState::Occupied;
        }
    }
    if (free && occupied)
        return weights_.surface;
    return free ? weights_.frontier : weights_.unknown;
}

double YawBinnedGain::columnGain(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                                 int column) const {
    const Aabb& box = map.explorationBox();
    double gain = 0.0;
    for (int j = 0; j < cubature_.rings; ++j) {
        const Eigen::Vector3d& dir = cubature_.directions[column * cubature_.rings + j];
        const double exit = exitDistance(box, p, dir);
        double ray = 0.0;
        for (std::size_t k = 0; k < cubature_.radii.size() && cubature_.radii[k] <= exit; ++k) {
            const Eigen::Vector3d q = p + cubature_.radii[k] * dir;
            const mapping::CellState s = map.state(q);
            if (s == mapping::CellState::Occupied)
                break;
            if (s == mapping::CellState::Unknown)
                ray += cubature_.shellWeights[k] * cellWeight(map, q);
        }
        gain += cubature_.ringWeights[j] * ray;
    }
    return gain;
}

std::uint64_t YawBinnedGain::columnsSeenFrom(int bin) const {
    std::uint64_t mask = 0;
    for (const auto& [offset, fraction] : window_)
        if (fraction >= 0.5)
            mask |= std::uint64_t(1) << (((bin + offset) % bins_ + bins_) % bins_);
    return mask;
}

std::vector<double> YawBinnedGain::evaluate(const mapping::ExplorationMap& map,
                                            const Eigen::Vector3d& p,
                                            std::uint64_t ignoredColumns) const {
    std::vector<double> gains(bins_, 0.0);
    if (!map.explorationBox().contains(p))
        return gains;
    std::vector<double> columns(bins_);
    for (int i = 0; i < bins_; ++i)
        columns[i] = ((ignoredColumns >> i) & 1u) ? 0.0 : columnGain(map, p, i);
    for (int b = 0; b < bins_; ++b)
        for (const auto& [offset, fraction] : window_)
            gains[b] += fraction * columns[((b + offset) % bins_ + bins_) % bins_];
    return gains;
}

}  // namespace daep::planning
