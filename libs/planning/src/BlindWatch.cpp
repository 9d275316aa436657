#include "daep/planning/BlindWatch.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace daep::planning {

BlindWatch::BlindWatch(const FrequencyMap& layout, const BlindWatchParams& params)
    : params_(params),
      origin_(layout.origin()),
      cellSize_(layout.cellSize()),
      nx_(layout.width()),
      ny_(layout.height()),
      lastSeen_(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_),
                -std::numeric_limits<double>::infinity()) {}

Eigen::Vector2d BlindWatch::center(int ix, int iy) const {
    return origin_ + cellSize_ * Eigen::Vector2d(ix + 0.5, iy + 0.5);
}

void BlindWatch::see(const FlatPose& camera, double hfov, double t) {
    const Eigen::Vector2d eye = camera.position.head<2>();
    for (int iy = 0; iy < ny_; ++iy)
        for (int ix = 0; ix < nx_; ++ix) {
            const Eigen::Vector2d d = center(ix, iy) - eye;
            const double distance = d.norm();
            if (distance > params_.range || distance < 1e-6 ||
                std::abs(wrapAngle(std::atan2(d.y(), d.x()) - camera.yaw)) > 0.5 * hfov)
                continue;
            lastSeen_[static_cast<std::size_t>(iy * nx_ + ix)] = t;
        }
}

double BlindWatch::lastSeen(const Eigen::Vector2d& xy) const {
    const Eigen::Vector2d local = (xy - origin_) / cellSize_;
    const int ix = static_cast<int>(std::floor(local.x()));
    const int iy = static_cast<int>(std::floor(local.y()));
    if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_)
        return -std::numeric_limits<double>::infinity();
    return lastSeen_[static_cast<std::size_t>(iy * nx_ + ix)];
}

BlindThreat BlindWatch::worstThreat(const FrequencyMap& dfm, const Eigen::Vector2d& p, double now,
                                    double until, double keepOut) const {
    BlindThreat worst;
    worst.excess = -std::numeric_limits<double>::infinity();
    const double reachMax = keepOut + params_.walkSpeed * (until - now + params_.maxAge);
    for (int iy = 0; iy < ny_; ++iy)
        for (int ix = 0; ix < nx_; ++ix) {
            const Eigen::Vector2d c = center(ix, iy);
            const double distance = (c - p).norm();
            if (distance > reachMax || dfm.value(c) < params_.busyThreshold)
                continue;
            // Seen just now and empty: whoever comes is in another cell, counted there.
            const double unseen = now - lastSeen_[static_cast<std::size_t>(iy * nx_ + ix)];
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
