#include "daep/planning/TreeParts.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "daep/mapping/ExplorationMap.h"
#include "daep/planning/FlightSpace.h"
#include "daep/planning/GainCache.h"
#include "daep/planning/GaussianProcess.h"

namespace daep::planning {

void PathSpaceValidator::bind(const mapping::ExplorationMap& map, double robotRadius,
                              double bodyHalfHeight, bool crossUnknown) {
    map_ = &map;
    robotRadius_ = robotRadius;
    bodyHalfHeight_ = bodyHalfHeight;
    crossUnknown_ = crossUnknown;
}

bool PathSpaceValidator::staticValid(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                     bool leavingBlocked) const {
    if (crossUnknown_)
        return map_->isSegmentFreeOrUnknown(a, b, robotRadius_);
    return segmentFlyable(*map_, a, b, robotRadius_, bodyHalfHeight_, leavingBlocked);
}

double AepScore::score(double parentScore, double gain, double edge, const Eigen::Vector3d&) const {
    return parentScore + gain * std::exp(-lambda_ * edge);
}

CachedView::CachedView(const CachedViewParams& params, const GainEvaluator& gain, GainCache& cache,
                       GaussianProcess& gp, AepStats& stats)
    : params_(params), gain_(gain), cache_(cache), gp_(gp), stats_(stats) {}

YawGain CachedView::estimate(const mapping::ExplorationMap& map, const Eigen::Vector3d& p) {
    const std::vector<int> ids =
        cache_.near(p, params_.gpRadius, static_cast<std::size_t>(params_.gpMaxNeighbours));
    if (!ids.empty()) {
        std::vector<Eigen::Vector3d> x;
        std::vector<double> y;
        for (int id : ids) {
            x.push_back(cache_.entry(id).position);
            y.push_back(cache_.entry(id).gain);
        }
        gp_.fit(x, y);
        const GpPrediction g = gp_.predict(p);
        if (g.sigma < params_.sigmaThreshold) {
            ++stats_.gpPredictions;
            return {cache_.entry(ids.front()).yaw, std::max(0.0, g.mean)};
        }
    }
    const YawGain view = rayCast(map, p);
    remember(p, view);
    return view;
}

YawGain CachedView::rayCast(const mapping::ExplorationMap& map, const Eigen::Vector3d& p,
                            const std::vector<BodyOccluder>* occluders) {
    ++stats_.rayCasts;
    return gain_.bestYaw(map, p, occluders);
}

std::vector<double> CachedView::rayCastColumns(const Eigen::Vector3d& p,
                                               const std::vector<BodyOccluder>* occluders) {
    ++stats_.rayCasts;
    return gain_.columns(*map_, p, occluders);
}

GainEvaluator::ColumnViews CachedView::rayCastColumnsOpenAndOccluded(
    const Eigen::Vector3d& p, const std::vector<BodyOccluder>& occluders) {
    stats_.rayCasts += 2;
    return gain_.columnsOpenAndOccluded(*map_, p, occluders);
}

void CachedView::remember(const Eigen::Vector3d& p, const YawGain& view) {
    if (view.gain > params_.cacheThreshold)
        cache_.insert(p, view.yaw, view.gain);
}

YawGain CachedView::viewOnArrival(const Eigen::Vector3d&, const Eigen::Vector3d& p, double,
                                  bool rayCastAlways) {
    return rayCastAlways ? rayCast(*map_, p) : estimate(*map_, p);
}

}  // namespace daep::planning
