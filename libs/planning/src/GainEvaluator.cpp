#include "daep/planning/GainEvaluator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "RayGeometry.h"
#include "daep/common/Config.h"
#include "daep/common/ConfigChecks.h"
#include "daep/common/Types.h"
#include "daep/mapping/ExplorationMap.h"

namespace daep::planning {
using detail::exitDistance;
using detail::kTwoPi;
using detail::tileCount;

namespace {
constexpr int kSweepFirstDeg = -179, kSweepLastDeg = 180;  // bestYaw's candidate headings
double sweepYaw(int deg) {
    return deg * M_PI / 180.0;
}
}  // namespace

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
    for (int deg = kSweepFirstDeg; deg <= kSweepLastDeg; ++deg) {
        sweepStart_.push_back(sweepTerms_.size());
        windowTerms(sweepYaw(deg), [this](int column, double weight) {
            sweepTerms_.push_back({column, weight});
        });
    }
    sweepStart_.push_back(sweepTerms_.size());
    double longestStep = cubature_.radii.front();  // tileCount gives at least one shell
    for (std::size_t k = 1; k < cubature_.radii.size(); ++k)
        longestStep = std::max(longestStep, cubature_.radii[k] - cubature_.radii[k - 1]);
    double steepest = 0.0;
    for (const Eigen::Vector3d& dir : cubature_.directions)
        steepest = std::max(steepest, dir.cwiseAbs().maxCoeff());
    longestAxisStep_ = longestStep * steepest;
}

bool GainEvaluator::seesNoUnknown(const mapping::ExplorationMap& map,
                                  const Eigen::Vector3d& p) const {
    // A margin far above rounding: a step of a whole cell could skip a cell.
    return longestAxisStep_ < map.resolution() * (1.0 - 1e-6) &&
           !map.mayMeetUnknown(p, params_.range);
}

double rayEntry(const BodyOccluder& body, const Eigen::Vector3d& o, const Eigen::Vector3d& dir) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    double lo = 0.0, hi = kInf;
    // Height slab z in [0, height].
    if (std::abs(dir.z()) < 1e-12) {
        if (o.z() < 0.0 || o.z() > body.height)
            return kInf;
    } else {
        double a = (0.0 - o.z()) / dir.z(), b = (body.height - o.z()) / dir.z();
        if (a > b)
            std::swap(a, b);
        lo = std::max(lo, a);
        hi = std::min(hi, b);
    }
    // Disc in x/y: |o + t d - c|^2 <= r^2.
    const Eigen::Vector2d m = o.head<2>() - body.center;
    const Eigen::Vector2d d = dir.head<2>();
    const double a = d.squaredNorm();
    const double c = m.squaredNorm() - body.radius * body.radius;
    if (a < 1e-12) {
        if (c > 0.0)
            return kInf;
    } else {
        const double b = m.dot(d);
        const double disc = b * b - a * c;
        if (disc < 0.0)
            return kInf;
        const double root = std::sqrt(disc);
        lo = std::max(lo, (-b - root) / a);
        hi = std::min(hi, (-b + root) / a);
    }
    return lo <= hi ? lo : kInf;
}

void GainEvaluator::setYawAngleBooster(double alpha, double distance) {
    boostAlpha_ = alpha;
    boostDistance_ = distance;
}

double GainEvaluator::yawAngleBoost(const Aabb& box, const Eigen::Vector3d& s) const {
    const double toFace = std::min(
        {s.x() - box.min.x(), box.max.x() - s.x(), s.y() - box.min.y(), box.max.y() - s.y()});
    return toFace < boostDistance_ ? boostAlpha_ : 1.0;
}

double GainEvaluator::columnGain(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                                 int column, const std::vector<BodyOccluder>* occluders) const {
    const auto [open, occluded] = columnGains(map, p, column, occluders);
    return occluders ? occluded : open;
}

template <bool kFloored>
__attribute__((always_inline)) inline std::pair<double, double> GainEvaluator::columnGainsOn(
    const mapping::ExplorationMap& map, const Eigen::Vector3d& p, int column,
    const std::vector<BodyOccluder>* occluders) const {
    const Aabb& box = map.explorationBox();
    if (!box.contains(p))
        return {0.0, 0.0};
    const bool boosted = boostAlpha_ != 1.0 && boostDistance_ > 0.0;
    double gain = 0.0, occludedGain = 0.0;
    for (int j = 0; j < cubature_.rings; ++j) {
        const Eigen::Vector3d& dir = cubature_.directions[column * cubature_.rings + j];
        const double end = exitDistance(box, p, dir);
        double occludedEnd = end;
        if (occluders)
            for (const BodyOccluder& body : *occluders)
                occludedEnd = std::min(occludedEnd, rayEntry(body, p, dir));
        const std::vector<double>& radii = cubature_.radii;
        const std::size_t shells =
            std::size_t(std::upper_bound(radii.begin(), radii.end(), end) - radii.begin());
        double ray = 0.0, occludedRay = 0.0;
        bool stoppedByBody = false;
        const auto march = [&](const auto& stateAt) {
            for (std::size_t k = 0; k < shells; ++k) {
                if (!stoppedByBody && radii[k] > occludedEnd) {
                    occludedRay = ray;
                    stoppedByBody = true;
                }
                const Eigen::Vector3d s = p + radii[k] * dir;
                const mapping::CellState state = stateAt(s);
                if (state == mapping::CellState::Occupied)
                    break;
                if (state == mapping::CellState::Unknown)
                    ray += cubature_.shellWeights[k] * (boosted ? yawAngleBoost(box, s) : 1.0);
            }
        };
        // A ray whose first and last samples lie on the map's dense grid lies on it whole.
        if (shells > 0 && map.onGrid(p + radii[0] * dir) && map.onGrid(p + radii[shells - 1] * dir))
            march([&map](const Eigen::Vector3d& s) {
                return kFloored ? map.stateOnGridFloored(s) : map.stateOnGrid(s);
            });
        else
            march([&map](const Eigen::Vector3d& s) { return map.state(s); });
        gain += cubature_.ringWeights[j] * ray;
        occludedGain += cubature_.ringWeights[j] * (stoppedByBody ? occludedRay : ray);
    }
    return {gain, occludedGain};
}

std::pair<double, double> GainEvaluator::columnGains(
    const mapping::ExplorationMap& map, const Eigen::Vector3d& p, int column,
    const std::vector<BodyOccluder>* occluders) const {
    static const bool hasSse41 = __builtin_cpu_supports("sse4.1");
    return hasSse41 ? columnGainsSse41(map, p, column, occluders)
                    : columnGainsOn<false>(map, p, column, occluders);
}

std::pair<double, double> GainEvaluator::columnGainsSse41(
    const mapping::ExplorationMap& map, const Eigen::Vector3d& p, int column,
    const std::vector<BodyOccluder>* occluders) const {
    return columnGainsOn<true>(map, p, column, occluders);
}

std::vector<double> GainEvaluator::columns(const mapping::ExplorationMap& map,
                                           const Eigen::Vector3d& p,
                                           const std::vector<BodyOccluder>* occluders) const {
    std::vector<double> result(columns_);
    if (seesNoUnknown(map, p))
        return result;
    for (int i = 0; i < columns_; ++i)
        result[i] = columnGain(map, p, i, occluders);
    return result;
}

GainEvaluator::ColumnViews GainEvaluator::columnsOpenAndOccluded(
    const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
    const std::vector<BodyOccluder>& occluders) const {
    ColumnViews views{std::vector<double>(columns_), std::vector<double>(columns_)};
    if (seesNoUnknown(map, p))
        return views;
    for (int i = 0; i < columns_; ++i)
        std::tie(views.open[i], views.occluded[i]) = columnGains(map, p, i, &occluders);
    return views;
}

template <class TermFn>
void GainEvaluator::windowTerms(double yaw, const TermFn& term) const {
    const double half = 0.5 * std::min(params_.hfov, kTwoPi);
    const double a = yaw - half;
    const double b = yaw + half;
    const auto first = static_cast<long>(std::floor(a / columnWidth_));
    const auto last = static_cast<long>(std::floor(b / columnWidth_));
    for (long k = first; k <= last; ++k) {
        const double overlap = std::min(b, (k + 1) * columnWidth_) -
                               std::max(a, static_cast<double>(k) * columnWidth_);
        if (overlap <= 0.0)
            continue;
        term(static_cast<int>(((k % columns_) + columns_) % columns_), overlap / columnWidth_);
    }
}

template <class ColumnFn>
double GainEvaluator::window(double yaw, const ColumnFn& columnGainOf) const {
    double gain = 0.0;
    windowTerms(yaw, [&](int column, double weight) { gain += weight * columnGainOf(column); });
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
    for (int deg = kSweepFirstDeg; deg <= kSweepLastDeg; ++deg) {
        const std::size_t d = std::size_t(deg - kSweepFirstDeg);
        double gain = 0.0;
        for (std::size_t i = sweepStart_[d]; i < sweepStart_[d + 1]; ++i)
            gain += sweepTerms_[i].weight * columns[std::size_t(sweepTerms_[i].column)];
        if (gain > best.gain)
            best = {sweepYaw(deg), gain};
    }
    return best;
}

YawGain GainEvaluator::bestYaw(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                               const std::vector<BodyOccluder>* occluders) const {
    return bestYaw(columns(map, p, occluders));
}

}  // namespace daep::planning
