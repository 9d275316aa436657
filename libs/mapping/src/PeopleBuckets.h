#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "daep/mapping/ExplorationMap.h"

namespace daep::mapping {

/**
 * Whether a point lies in a person's cylinder, asked for every pixel of a frame: the
 * footprints are bucketed on a coarse 2D grid, so a pixel tests only those near it. Buckets
 * hold every footprint whose square, grown by a margin far above float rounding, touches them,
 * so the answer is the one testing every footprint gives.
 */
class PeopleBuckets {
public:
    explicit PeopleBuckets(const std::vector<PersonFootprint>& people) : people_(people) {
        std::vector<int> reachable;
        Eigen::Array2f lo(std::numeric_limits<float>::max(), std::numeric_limits<float>::max());
        Eigen::Array2f hi = -lo;
        for (int i = 0; i < int(people.size()); ++i) {
            const PersonFootprint& f = people[std::size_t(i)];
            top_ = std::max(top_, f.top);
            if (!f.centre.allFinite() || !std::isfinite(f.radius)) {
                anywhere_.push_back(i);  // tested at every point: bounds would not hold it
                continue;
            }
            reachable.push_back(i);
            lo = lo.min(f.centre.array() - reach(f));
            hi = hi.max(f.centre.array() + reach(f));
        }
        if (reachable.empty())
            return;
        low_ = lo.matrix();
        bucket_ = std::max(kBucket, (hi - lo).maxCoeff() / kMaxSide);
        for (int a = 0; a < 2; ++a)
            dims_[a] = int((hi[a] - lo[a]) / bucket_) + 1;
        buckets_.resize(std::size_t(dims_[0] * dims_[1]));
        for (const int i : reachable) {
            const PersonFootprint& f = people[std::size_t(i)];
            const auto [x0, y0] = bucketOf(f.centre.array() - reach(f));
            const auto [x1, y1] = bucketOf(f.centre.array() + reach(f));
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x)
                    buckets_[std::size_t(x + dims_[0] * y)].push_back(i);
        }
    }

    bool contains(const Eigen::Vector3f& p) const {
        if (p.z() > top_)
            return false;
        for (const int i : anywhere_)
            if (holds(people_[std::size_t(i)], p))
                return true;
        const Eigen::Vector2f q = (p.head<2>() - low_) / bucket_;
        if (!(q.x() >= 0.0f && q.y() >= 0.0f && q.x() < float(dims_[0]) && q.y() < float(dims_[1])))
            return false;
        for (const int i : buckets_[std::size_t(int(q.x()) + dims_[0] * int(q.y()))])
            if (holds(people_[std::size_t(i)], p))
                return true;
        return false;
    }

private:
    static constexpr float kBucket = 1.0f;  ///< m, unless the people spread over more buckets
    static constexpr float kMargin = 0.01f;
    static constexpr float kMaxSide = 1024.0f;  ///< buckets

    static bool holds(const PersonFootprint& f, const Eigen::Vector3f& p) {
        return p.z() <= f.top && (p.head<2>() - f.centre).squaredNorm() <= f.radius * f.radius;
    }

    /** How far from its centre a footprint may hold a point, with the margin. */
    static float reach(const PersonFootprint& f) { return std::abs(f.radius) + kMargin; }

    std::pair<int, int> bucketOf(const Eigen::Array2f& p) const {
        const Eigen::Array2f q = (p - low_.array()) / bucket_;
        return {std::clamp(int(q.x()), 0, dims_[0] - 1), std::clamp(int(q.y()), 0, dims_[1] - 1)};
    }

    const std::vector<PersonFootprint>& people_;
    Eigen::Vector2f low_ = Eigen::Vector2f::Zero();
    float bucket_ = kBucket;
    float top_ = -std::numeric_limits<float>::infinity();
    int dims_[2] = {0, 0};
    std::vector<std::vector<int>> buckets_;
    std::vector<int> anywhere_;
};

}  // namespace daep::mapping
