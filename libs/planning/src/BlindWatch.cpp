#include "daep/planning/BlindWatch.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace daep::planning {

BlindWatch::BlindWatch(const DynamicFrequencyMap& layout, const BlindWatchParams& params)
    : params_(params),
      grid_(layout.grid()),
      lastSeen_(grid_.size(), -std::numeric_limits<double>::infinity()) {}

void BlindWatch::see(const FlatPose& camera, double hfov, double t) {
    const Eigen::Vector2d eye = camera.position.head<2>();
    for (int iy = 0; iy < grid_.ny; ++iy)
        for (int ix = 0; ix < grid_.nx; ++ix) {
            const Eigen::Vector2d d = grid_.center(ix, iy) - eye;
            const double distance = d.norm();
            if (distance > params_.range || distance < 1e-6 ||
                std::abs(wrapAngle(std::atan2(d.y(), d.x()) - camera.yaw)) > 0.5 * hfov)
                continue;
            lastSeen_[static_cast<std::size_t>(iy * grid_.nx + ix)] = t;
        }
}

double BlindWatch::lastSeen(const Eigen::Vector2d& xy) const {
    const int i = grid_.index(xy);
    return i < 0 ? -std::numeric_limits<double>::infinity()
                 : lastSeen_[static_cast<std::size_t>(i)];
}

BlindThreat BlindWatch::worstThreat(const DynamicFrequencyMap& dfm, const Eigen::Vector2d& p,
                                    double now, double until, double keepOut) const {
    BlindThreat worst;
    worst.excess = -std::numeric_limits<double>::infinity();
    const double reachMax = keepOut + params_.walkSpeed * (until - now + params_.maxAge);
    for (int iy = 0; iy < grid_.ny; ++iy)
        for (int ix = 0; ix < grid_.nx; ++ix) {
            const Eigen::Vector2d c = grid_.center(ix, iy);
            const double distance = (c - p).norm();
            if (distance > reachMax || dfm.value(c) < params_.busyThreshold)
                continue;
            // Seen just now and empty: whoever comes is in another cell, counted there.
            const double unseen = now - lastSeen_[static_cast<std::size_t>(iy * grid_.nx + ix)];
            if (unseen < params_.freshness)
                continue;
            const double age = std::min(params_.maxAge, unseen) + (until - now);
            const double excess = keepOut + params_.walkSpeed * age - distance;
            if (excess > worst.excess)
                worst = {excess, c};
        }
    return worst;
}

}  // namespace daep::planning
