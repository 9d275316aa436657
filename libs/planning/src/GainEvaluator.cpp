#include "daep/planning/GainEvaluator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ConfigChecks.h"
#include "RayGeometry.h"
#include "daep/common/Config.h"
#include "daep/common/Types.h"
#include "daep/mapping/ExplorationMap.h"

namespace daep::planning {
using detail::exitDistance;
using detail::kTwoPi;
using detail::tileCount;

GainParams GainParams::fromConfig(const mrpt::config::CConfigFileBase& config) {
    const ConfigReader r(config, "gain");
    GainParams g;
    g.hfov = requireInRange(r, "hfov_deg", 0.0, 360.0) * M_PI / 180.0;
    g.vfov = requireInRange(r, "vfov_deg", 0.0, 180.0) * M_PI / 180.0;
    g.range = requirePositive(r, "range");
    g.dr = requirePositive(r, "dr");
    g.dphi = requirePositive(r, "dphi_deg") * M_PI / 180.0;
    g.dtheta = requirePositive(r, "dtheta_deg") * M_PI / 180.0;
    return g;
}

RayCubature::RayCubature(const GainParams& params, const std::vector<double>& columnCentres) {
    const double columnWidth = kTwoPi / static_cast<double>(columnCentres.size());
    rings = tileCount(params.vfov, params.dphi);
    const int shells = tileCount(params.range, params.dr);
    const double dphi = params.vfov / rings;
    const double dr = params.range / shells;
    phiMin = 0.5 * (M_PI - params.vfov);
    phiMax = phiMin + params.vfov;
    std::vector<double> phis(rings);
    for (int j = 0; j < rings; ++j) {
        phis[j] = phiMin + (j + 0.5) * dphi;
        ringWeights.push_back(columnWidth * 2.0 * std::sin(phis[j]) * std::sin(0.5 * dphi));
    }
    for (const double theta : columnCentres)
        for (int j = 0; j < rings; ++j)
            directions.emplace_back(std::sin(phis[j]) * std::cos(theta),
                                    std::sin(phis[j]) * std::sin(theta), std::cos(phis[j]));
    for (int k = 0; k < shells; ++k) {
        const double r = (k + 0.5) * dr;
        radii.push_back(r);
        shellWeights.push_back(r * r * dr + dr * dr * dr / 12.0);
    }
}

GainEvaluator::GainEvaluator(const GainParams& params) : params_(params) {
    columns_ = tileCount(kTwoPi, params.dtheta);
    columnWidth_ = kTwoPi / columns_;
    std::vector<double> centres(columns_);
    for (int i = 0; i < columns_; ++i)
        centres[i] = (i + 0.5) * columnWidth_;
    cubature_ = RayCubature(params, centres);
}

double GainEvaluator::columnGain(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                                 int column) const {
    const Aabb& box = map.explorationBox();
    if (!box.contains(p))
        return 0.0;
    double gain = 0.0;
    for (int j = 0; j < cubature_.rings; ++j) {
        const Eigen::Vector3d& dir = cubature_.directions[column * cubature_.rings + j];
        const double exit = exitDistance(box, p, dir);
        double ray = 0.0;
        for (std::size_t k = 0; k < cubature_.radii.size() && cubature_.radii[k] <= exit; ++k) {
            const mapping::CellState s = map.state(p + cubature_.radii[k] * dir);
            if (s == mapping::CellState::Occupied)
                break;
            if (s == mapping::CellState::Unknown)
                ray += cubature_.shellWeights[k];
        }
        gain += cubature_.ringWeights[j] * ray;
    }
    return gain;
}

std::vector<double> GainEvaluator::columns(const mapping::ExplorationMap& map,
                                           const Eigen::Vector3d& p) const {
    std::vector<double> result(columns_);
    for (int i = 0; i < columns_; ++i)
        result[i] = columnGain(map, p, i);
    return result;
}

template <class ColumnFn>
double GainEvaluator::window(double yaw, const ColumnFn& columnGainOf) const {
    const double half = 0.5 * std::min(params_.hfov, kTwoPi);
    const double a = yaw - half;
    const double b = yaw + half;
    const auto first = static_cast<long>(std::floor(a / columnWidth_));
    const auto last = static_cast<long>(std::floor(b / columnWidth_));
    double gain = 0.0;
    for (long k = first; k <= last; ++k) {
        const double overlap = std::min(b, (k + 1) * columnWidth_) -
                               std::max(a, static_cast<double>(k) * columnWidth_);
        if (overlap <= 0.0)
            continue;
        const int index = static_cast<int>(((k % columns_) + columns_) % columns_);
        gain += overlap / columnWidth_ * columnGainOf(index);
    }
    return gain;
}

double GainEvaluator::gainAtYaw(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                                double yaw) const {
    return window(yaw, [&](int i) { return columnGain(map, p, i); });
}

double GainEvaluator::windowGain(const std::vector<double>& columns, double yaw) const {
    return window(yaw, [&](int i) { return columns[i]; });
}

YawGain GainEvaluator::bestYaw(const std::vector<double>& columns) const {
    YawGain best{0.0, -1.0};
    for (int deg = -179; deg <= 180; ++deg) {
        const double yaw = deg * M_PI / 180.0;
        const double gain = windowGain(columns, yaw);
        if (gain > best.gain)
            best = {yaw, gain};
    }
    return best;
}

YawGain GainEvaluator::bestYaw(const mapping::ExplorationMap& map, const Eigen::Vector3d& p) const {
    return bestYaw(columns(map, p));
}

}  // namespace daep::planning
