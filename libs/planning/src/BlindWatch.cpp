#include "daep/planning/BlindWatch.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "daep/mapping/ExplorationMap.h"

namespace daep::planning {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

double BlindWatch::walkTime(double distance) const {
    return params_.walkSpeed > 0.0 ? distance / params_.walkSpeed : kInf;
}

BlindWatch::BlindWatch(const DynamicFrequencyMap& layout, const BlindWatchParams& params)
    : params_(params),
      grid_(layout.grid()),
      lastSeen_(grid_.size(), -kInf),
      unseenFrom_(grid_.size(), -kInf),
      leftAt_(grid_.size(), kInf),
      personSeen_(grid_.size(), -kInf),
      lostFrom_(grid_.size(), kInf),
      lostSince_(grid_.size(), -kInf) {}

void BlindWatch::see(const FlatPose& camera, double hfov, double t, const DynamicFrequencyMap& dfm,
                     const std::vector<Eigen::Vector2d>& people,
                     const mapping::ExplorationMap* map) {
    markView(camera, hfov, t, map);
    for (const Eigen::Vector2d& person : people)
        markLeft(person, t);
    spread(dfm, t);
}

BlindWatch BlindWatch::afterLook(const FlatPose& camera, double hfov, double t,
                                 const DynamicFrequencyMap& dfm,
                                 const mapping::ExplorationMap* map) const {
    BlindWatch looked = *this;
    looked.see(camera, hfov, t, dfm, {}, map);
    return looked;
}

void BlindWatch::markView(const FlatPose& camera, double hfov, double t,
                          const mapping::ExplorationMap* map) {
    const Eigen::Vector2d eye = camera.position.head<2>();
    for (int iy = 0; iy < grid_.ny; ++iy)
        for (int ix = 0; ix < grid_.nx; ++ix) {
            const Eigen::Vector2d d = grid_.center(ix, iy) - eye;
            const double distance = d.norm();
            if (distance > params_.range || distance < 1e-6 ||
                std::abs(wrapAngle(std::atan2(d.y(), d.x()) - camera.yaw)) > 0.5 * hfov)
                continue;
            if (map && map->castRay(camera.position, {d.x() / distance, d.y() / distance, 0.0},
                                    distance) < distance - 0.5 * grid_.cellSize)
                continue;  // behind a wall
            const auto i = static_cast<std::size_t>(iy * grid_.nx + ix);
            lastSeen_[i] = t;
            unseenFrom_[i] = leftAt_[i] = lostFrom_[i] = kInf;
        }
}

void BlindWatch::markLeft(const Eigen::Vector2d& person, double t) {
    const int at = grid_.index(person);
    if (at < 0)
        return;
    personSeen_[static_cast<std::size_t>(at)] = t;
    const int px = at % grid_.nx, py = at / grid_.nx;
    for (int iy = std::max(0, py - 1); iy <= std::min(grid_.ny - 1, py + 1); ++iy)
        for (int ix = std::max(0, px - 1); ix <= std::min(grid_.nx - 1, px + 1); ++ix) {
            const auto i = static_cast<std::size_t>(iy * grid_.nx + ix);
            if (lastSeen_[i] == t)
                continue;  // in view: whoever walks in is seen there
            const double walk =
                ix == px && iy == py ? 0.0 : walkTime((grid_.center(ix, iy) - person).norm());
            const double from = std::max(lastSeen_[i], t + walk);
            leftAt_[i] = std::min(leftAt_[i], from);
            offerLost(i, from, t);
        }
}

bool BlindWatch::busy(const DynamicFrequencyMap& dfm, std::size_t i) const {
    return dfm.maxCount() > 0 && dfm.value(i) >= params_.busyThreshold;
}

bool BlindWatch::walkway(const DynamicFrequencyMap& dfm, int ix, int iy) const {
    const auto busyAt = [&](int x, int y) {
        return grid_.contains(x, y) && busy(dfm, static_cast<std::size_t>(y * grid_.nx + x));
    };
    if (busyAt(ix, iy))
        return true;
    // A quiet cell between two busy ones: people walked across it, only not while the camera
    // looked (the frequency map counts people where they were seen).
    constexpr int kHalfLines[4][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
    for (const auto& d : kHalfLines)
        if (busyAt(ix - d[0], iy - d[1]) && busyAt(ix + d[0], iy + d[1]))
            return true;
    return false;
}

template <typename Relax>
void BlindWatch::walkSweeps(const Relax& relax) const {
    // Two chamfer sweeps: from the cells before each cell in raster order, then from those
    // after it; relax(i, j, walk) offers cell i what its neighbour j holds, walk s away.
    const int nx = grid_.nx, ny = grid_.ny;
    const double side = walkTime(grid_.cellSize);
    const double diagonal = walkTime(std::sqrt(2.0) * grid_.cellSize);
    const auto visit = [&](int ix, int iy, const int(&steps)[4][2]) {
        const auto i = static_cast<std::size_t>(iy * nx + ix);
        for (const auto& s : steps) {
            const int jx = ix + s[0], jy = iy + s[1];
            if (grid_.contains(jx, jy))
                relax(i, static_cast<std::size_t>(jy * nx + jx),
                      s[0] != 0 && s[1] != 0 ? diagonal : side);
        }
    };
    constexpr int kBefore[4][2] = {{-1, 0}, {-1, -1}, {0, -1}, {1, -1}};
    constexpr int kAfter[4][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 1}};
    for (int iy = 0; iy < ny; ++iy)
        for (int ix = 0; ix < nx; ++ix)
            visit(ix, iy, kBefore);
    for (int iy = ny - 1; iy >= 0; --iy)
        for (int ix = nx - 1; ix >= 0; --ix)
            visit(ix, iy, kAfter);
}

void BlindWatch::spread(const DynamicFrequencyMap& dfm, double t) {
    const int nx = grid_.nx;
    std::vector<char> onWalkway(grid_.size());
    for (std::size_t i = 0; i < onWalkway.size(); ++i) {
        onWalkway[i] = walkway(dfm, static_cast<int>(i) % nx, static_cast<int>(i) / nx);
        // Someone seen in a cell at its last look may still be there once the camera looks away.
        if (lastSeen_[i] < t && personSeen_[i] > -kInf && personSeen_[i] >= lastSeen_[i]) {
            leftAt_[i] = std::min(leftAt_[i], lastSeen_[i]);
            offerLost(i, lastSeen_[i], personSeen_[i]);
        }
        if (onWalkway[i])
            unseenFrom_[i] = std::min(unseenFrom_[i], leftAt_[i]);
    }
    // Off the walkways only the people just seen walk, from where they were.
    const auto from = [&](std::size_t j) { return onWalkway[j] ? unseenFrom_[j] : leftAt_[j]; };
    walkSweeps([&](std::size_t i, std::size_t j, double walk) {
        if (lastSeen_[i] != t && onWalkway[i])
            unseenFrom_[i] = std::min(unseenFrom_[i], std::max(lastSeen_[i], from(j) + walk));
    });
    spreadLost(t);
}

void BlindWatch::offerLost(std::size_t i, double from, double since) {
    if (params_.lostTime > 0.0 && from < lostFrom_[i]) {
        lostFrom_[i] = from;
        lostSince_[i] = since;
    }
}

bool BlindWatch::followed(std::size_t i, double now) const {
    return lostFrom_[i] < kInf && now - lostSince_[i] <= params_.lostTime;
}

void BlindWatch::spreadLost(double t) {
    if (params_.lostTime <= 0.0)
        return;
    for (std::size_t i = 0; i < lostFrom_.size(); ++i)
        if (!followed(i, t))
            lostFrom_[i] = kInf;  // followed long enough: along the walkways alone from now on
    walkSweeps([&](std::size_t i, std::size_t j, double walk) {
        if (lastSeen_[i] != t && lostFrom_[j] < kInf)
            offerLost(i, std::max(lastSeen_[i], lostFrom_[j] + walk), lostSince_[j]);
    });
}

double BlindWatch::lastSeen(const Eigen::Vector2d& xy) const {
    return atCell(lastSeen_, xy);
}

double BlindWatch::unseenFrom(const Eigen::Vector2d& xy) const {
    return atCell(unseenFrom_, xy);
}

double BlindWatch::lostFrom(const Eigen::Vector2d& xy, double now) const {
    const int i = grid_.index(xy);
    return i >= 0 && followed(static_cast<std::size_t>(i), now)
               ? lostFrom_[static_cast<std::size_t>(i)]
               : kInf;
}

bool BlindWatch::walkwayAt(const DynamicFrequencyMap& dfm, const Eigen::Vector2d& xy) const {
    const int i = grid_.index(xy);
    return i >= 0 && walkway(dfm, i % grid_.nx, i / grid_.nx);
}

double BlindWatch::atCell(const std::vector<double>& times, const Eigen::Vector2d& xy) const {
    const int i = grid_.index(xy);
    return i < 0 ? -kInf : times[static_cast<std::size_t>(i)];
}

BlindThreat BlindWatch::worstThreat(const DynamicFrequencyMap& dfm, const Eigen::Vector2d& p,
                                    double now, double until, double keepOut) const {
    BlindThreat worst;
    worst.excess = -kInf;
    const double reachMax = keepOut + params_.walkSpeed * (until - now);
    for (int iy = 0; iy < grid_.ny; ++iy)
        for (int ix = 0; ix < grid_.nx; ++ix) {
            const auto i = static_cast<std::size_t>(iy * grid_.nx + ix);
            const Eigen::Vector2d c = grid_.center(ix, iy);
            const double distance = (c - p).norm();
            if (distance > reachMax)
                continue;
            const double unseen = walkway(dfm, ix, iy) ? unseenFrom_[i] : kInf;
            const double lost = followed(i, now) ? lostFrom_[i] : kInf;
            const double from = std::max(std::min(unseen, lost), now);
            if (from >= until)
                continue;
            const double excess = keepOut + params_.walkSpeed * (until - from) - distance;
            if (excess > worst.excess)
                worst = {excess, c, lost < unseen};
        }
    return worst;
}

}  // namespace daep::planning
