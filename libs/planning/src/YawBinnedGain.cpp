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
using detail::tileCount;

YawBinnedGain::YawBinnedGain(const GainParams& params, int bins, const CellWeights& weights)
    : params_(params), weights_(weights), bins_(bins) {
    if (bins < 1 || bins > 64)
        throw std::invalid_argument("YawBinnedGain: bins must be in [1, 64]");
    binWidth_ = kTwoPi / bins_;
    rings_ = tileCount(params.vfov, params.dphi);
    const int shells = tileCount(params.range, params.dr);
    const double dphi = params.vfov / rings_;
    const double dr = params.range / shells;
    const double phiMin = 0.5 * (M_PI - params.vfov);
    std::vector<double> phis(rings_);
    for (int j = 0; j < rings_; ++j) {
        phis[j] = phiMin + (j + 0.5) * dphi;
        ringWeights_.push_back(binWidth_ * 2.0 * std::sin(phis[j]) * std::sin(0.5 * dphi));
    }
    for (int i = 0; i < bins_; ++i) {
        const double theta = binYaw(i);  // column i spans theta +- binWidth/2
        for (int j = 0; j < rings_; ++j)
            directions_.emplace_back(std::sin(phis[j]) * std::cos(theta),
                                     std::sin(phis[j]) * std::sin(theta), std::cos(phis[j]));
    }
    for (int k = 0; k < shells; ++k) {
        const double r = (k + 0.5) * dr;
        radii_.push_back(r);
        shellWeights_.push_back(r * r * dr + dr * dr * dr / 12.0);
    }
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
    for (int j = 0; j < rings_; ++j) {
        const Eigen::Vector3d& dir = directions_[column * rings_ + j];
        const double exit = exitDistance(box, p, dir);
        double ray = 0.0;
        for (std::size_t k = 0; k < radii_.size() && radii_[k] <= exit; ++k) {
            const Eigen::Vector3d q = p + radii_[k] * dir;
            const mapping::CellState s = map.state(q);
            if (s == mapping::CellState::Occupied)
                break;
            if (s == mapping::CellState::Unknown)
                ray += shellWeights_[k] * cellWeight(map, q);
        }
        gain += ringWeights_[j] * ray;
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
