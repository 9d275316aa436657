#include "daep/planning/WayOut.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "daep/mapping/ExplorationMap.h"
#include "daep/planning/DynamicObstacles.h"
#include "daep/planning/FlightSpace.h"

namespace daep::planning {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/** The lattice around the drone: n steps each way horizontally, one up and down. */
class Lattice {
public:
    Lattice(const Eigen::Vector3d& center, double spacing, double radius)
        : center_(center), spacing_(spacing), n_(static_cast<int>(radius / spacing)) {}

    int size() const { return side() * side() * 3; }
    int root() const { return index(0, 0, 0); }
    Eigen::Vector3d position(int i) const {
        const int k = i / (side() * side()) - 1;
        const int j = (i / side()) % side() - n_;
        const int l = i % side() - n_;
        return center_ + spacing_ * Eigen::Vector3d(l, j, k);
    }
    bool inReach(int i) const {
        const Eigen::Vector3d d = position(i) - center_;
        return d.head<2>().norm() <= n_ * spacing_ + 1e-9;
    }
    /** The up to 26 lattice neighbours of i. */
    template <typename Visit>
    void forEachNeighbour(int i, Visit&& visit) const {
        const int k = i / (side() * side()) - 1;
        const int j = (i / side()) % side() - n_;
        const int l = i % side() - n_;
        for (int dk = -1; dk <= 1; ++dk)
            for (int dj = -1; dj <= 1; ++dj)
                for (int dl = -1; dl <= 1; ++dl) {
                    if (dk == 0 && dj == 0 && dl == 0)
                        continue;
                    const int kk = k + dk, jj = j + dj, ll = l + dl;
                    if (std::abs(kk) > 1 || std::abs(jj) > n_ || std::abs(ll) > n_)
                        continue;
                    visit(index(ll, jj, kk));
                }
    }

private:
    int side() const { return 2 * n_ + 1; }
    int index(int l, int j, int k) const { return ((k + 1) * side() + (j + n_)) * side() + l + n_; }

    Eigen::Vector3d center_;
    double spacing_;
    int n_;
};

/** Pieces of this length (s) are judged one by one: a way is exposed while in a body. */
constexpr double kPiece = 0.4;

/** What flying or hovering through a stretch costs: time inside a body, least gap outside. */
struct Exposure {
    double time = 0.0;
    double gap = kInf;
    double deepest = kInf;  ///< least gap, inside bodies too, once under way

    void add(const Exposure& o) {
        time += o.time;
        gap = std::min(gap, o.gap);
        deepest = std::min(deepest, o.deepest);
    }
    bool betterThan(const Exposure& o, double length, double otherLength) const {
        if (std::abs(time - o.time) > 1e-9)
            return time < o.time;
        if (std::abs(gap - o.gap) > 1e-9)
            return gap > o.gap;
        return length < otherLength - 1e-9;
    }
};

/**
 * The straight flight a -> b from `start` (or a hover at a, when b == a) for `duration` s.
 * The piece starting at `now`, where every way starts, does not count for the depth.
 */
Exposure exposureOf(const DynamicObstacles& bodies, const Eigen::Vector3d& a,
                    const Eigen::Vector3d& b, double start, double duration, double now) {
    Exposure e;
    const int pieces = std::max(1, static_cast<int>(std::ceil(duration / kPiece - 1e-9)));
    for (int k = 0; k < pieces; ++k) {
        TimedSegment piece;
        piece.from = a + (b - a) * (static_cast<double>(k) / pieces);
        piece.to = a + (b - a) * (static_cast<double>(k + 1) / pieces);
        piece.start = start + duration * k / pieces;
        (piece.from == piece.to ? piece.turnTime : piece.flyTime) = duration / pieces;
        const double gap = bodies.clearance(piece);
        if (piece.start > now + 1e-9)
            e.deepest = std::min(e.deepest, gap);
        if (gap <= 0.0)
            e.time += duration / pieces;
        else
            e.gap = std::min(e.gap, gap);
    }
    return e;
}

/** Hovering at p from `arrival` until `hoverUntil`, judged for at least one piece. */
Exposure hoverExposure(const DynamicObstacles& bodies, const Eigen::Vector3d& p, double arrival,
                       double hoverUntil, double now) {
    return exposureOf(bodies, p, p, arrival, std::max(kPiece, hoverUntil - arrival), now);
}

/** The best way found to a lattice point: its exposure, length, where from. */
struct Label {
    Exposure exposure{kInf, -kInf};
    double length = kInf;
    int previous = -1;
    bool settled = false;
};

}  // namespace

WayOut judgeWay(const DynamicObstacles& bodies, const Eigen::Vector3d& from, double time,
                std::vector<Eigen::Vector3d> path, const MotionLimits& motion, double hoverUntil) {
    Exposure e;
    Eigen::Vector3d at = from;
    double length = 0.0;
    for (const Eigen::Vector3d& p : path) {
        const double leg = (p - at).norm();
        e.add(exposureOf(bodies, at, p, time + length / motion.speed, leg / motion.speed, time));
        length += leg;
        at = p;
    }
    e.add(hoverExposure(bodies, at, time + length / motion.speed, hoverUntil, time));
    return {std::move(path), length, e.time, e.gap, e.deepest};
}

std::optional<WayOut> findWayOut(const mapping::ExplorationMap& map, const Aabb& box,
                                 const DynamicObstacles& bodies, const FlatPose& from, double time,
                                 const MotionLimits& motion, double hoverUntil,
                                 const WayOutParams& params) {
    const Lattice lattice(from.position, params.spacing, params.radius);
    const Aabb inside = shrink(box, params.robotRadius);
    const bool leavingBlocked =
        !map.isSegmentFree(from.position, from.position, params.robotRadius);
    std::vector<Label> labels(static_cast<std::size_t>(lattice.size()));
    std::vector<signed char> usable(labels.size(), -1);  // -1: not looked at yet
    auto isUsable = [&](int i) {
        signed char& u = usable[static_cast<std::size_t>(i)];
        if (u < 0) {
            const Eigen::Vector3d p = lattice.position(i);
            u = lattice.inReach(i) && inside.contains(p) &&
                map.isSegmentFree(p, p, params.robotRadius);
        }
        return u > 0;
    };
    // ((-exposure time, gap), -length) ordered, so the queue's top is the best label.
    using Entry = std::pair<std::pair<std::pair<double, double>, double>, int>;
    std::priority_queue<Entry> open;
    const int root = lattice.root();
    labels[static_cast<std::size_t>(root)] = {Exposure{}, 0.0, -1, false};
    open.push({{{0.0, kInf}, 0.0}, root});
    while (!open.empty()) {
        const int a = open.top().second;
        open.pop();
        Label& at = labels[static_cast<std::size_t>(a)];
        if (at.settled)
            continue;
        at.settled = true;
        const Eigen::Vector3d pa = lattice.position(a);
        lattice.forEachNeighbour(a, [&](int b) {
            Label& next = labels[static_cast<std::size_t>(b)];
            if (next.settled || !isUsable(b))
                return;
            const Eigen::Vector3d pb = lattice.position(b);
            const double length = at.length + (pb - pa).norm();
            if (!at.exposure.betterThan(next.exposure, length, next.length))
                return;  // even a clear move would not improve on what b has
            if (!segmentFlyable(map, pa, pb, params.robotRadius, params.bodyHalfHeight,
                                a == root && leavingBlocked))
                return;
            Exposure e = at.exposure;
            e.add(exposureOf(bodies, pa, pb, time + at.length / motion.speed,
                             (pb - pa).norm() / motion.speed, time));
            if (!e.betterThan(next.exposure, length, next.length))
                return;
            next = {e, length, a, false};
            open.push({{{-e.time, e.gap}, -length}, b});
        });
    }
    std::optional<WayOut> best;
    Exposure bestExposure;
    for (int g = 0; g < lattice.size(); ++g) {
        const Label& l = labels[static_cast<std::size_t>(g)];
        if (g == root || !l.settled)
            continue;
        Exposure e = l.exposure;
        e.add(hoverExposure(bodies, lattice.position(g), time + l.length / motion.speed, hoverUntil,
                            time));
        if (best && !e.betterThan(bestExposure, l.length, best->length))
            continue;
        WayOut way;
        way.exposure = e.time;
        way.gap = e.gap;
        way.deepest = e.deepest;
        way.length = l.length;
        for (int q = g; q != root; q = labels[static_cast<std::size_t>(q)].previous)
            way.path.push_back(lattice.position(q));
        std::reverse(way.path.begin(), way.path.end());
        best = std::move(way);
        bestExposure = e;
    }
    return best;
}

}  // namespace daep::planning
