#include "daep/planning/Tree.h"

#include <emmintrin.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace daep::planning {

void Tree::reset(const FlatPose& root) {
    nodes_.clear();
    xs_.clear();
    ys_.clear();
    zs_.clear();
    TreeNode node;
    node.position = root.position;
    node.yaw = root.yaw;
    append(node);
}

void Tree::append(const TreeNode& node) {
    nodes_.push_back(node);
    xs_.push_back(node.position.x());
    ys_.push_back(node.position.y());
    zs_.push_back(node.position.z());
}

int Tree::add(int parent, const Eigen::Vector3d& position, double yaw) {
    TreeNode node;
    node.position = position;
    node.yaw = yaw;
    node.parent = parent;
    node.cost = nodes_[parent].cost + (position - nodes_[parent].position).norm();
    append(node);
    return size() - 1;
}

namespace {

/** Squared distances of nodes i and i + 1 to (px, py, pz), in squaredDistance's order. */
inline __m128d squaredDistances(const double* xs, const double* ys, const double* zs, std::size_t i,
                                __m128d px, __m128d py, __m128d pz) {
    const __m128d dx = _mm_sub_pd(_mm_loadu_pd(xs + i), px);
    const __m128d dy = _mm_sub_pd(_mm_loadu_pd(ys + i), py);
    const __m128d dz = _mm_sub_pd(_mm_loadu_pd(zs + i), pz);
    return _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy)), _mm_mul_pd(dz, dz));
}

/** Where d is smaller than best, best takes d and bestIndex takes index. */
inline void keepCloser(__m128d d, __m128d index, __m128d& best, __m128d& bestIndex) {
    const __m128d closer = _mm_cmplt_pd(d, best);
    best = _mm_or_pd(_mm_and_pd(closer, d), _mm_andnot_pd(closer, best));
    bestIndex = _mm_or_pd(_mm_and_pd(closer, index), _mm_andnot_pd(closer, bestIndex));
}

}  // namespace

int Tree::nearest(const Eigen::Vector3d& p) const {
    // Four nodes at a time in four lanes (node i in lane i % 4), two independent pairs so the
    // loop does not wait on its own comparisons. Each lane keeps the first of its nodes at its
    // smallest distance; across lanes the lower index wins a tie, as a scan in order would.
    const __m128d px = _mm_set1_pd(p.x()), py = _mm_set1_pd(p.y()), pz = _mm_set1_pd(p.z());
    const __m128d far = _mm_set1_pd(std::numeric_limits<double>::infinity());
    __m128d bestA = far, bestB = far;
    __m128d indexA = _mm_set1_pd(-1.0), indexB = indexA;
    __m128d nextA = _mm_set_pd(1.0, 0.0), nextB = _mm_set_pd(3.0, 2.0);
    const __m128d four = _mm_set1_pd(4.0);
    const std::size_t quads = std::size_t(size()) / 4;
    for (std::size_t k = 0; k < quads; ++k) {
        const std::size_t i = 4 * k;
        keepCloser(squaredDistances(xs_.data(), ys_.data(), zs_.data(), i, px, py, pz), nextA,
                   bestA, indexA);
        keepCloser(squaredDistances(xs_.data(), ys_.data(), zs_.data(), i + 2, px, py, pz), nextB,
                   bestB, indexB);
        nextA = _mm_add_pd(nextA, four);
        nextB = _mm_add_pd(nextB, four);
    }
    alignas(16) double distances[4], indices[4];
    _mm_store_pd(distances, bestA);
    _mm_store_pd(distances + 2, bestB);
    _mm_store_pd(indices, indexA);
    _mm_store_pd(indices + 2, indexB);
    int best = -1;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (int lane = 0; lane < 4; ++lane) {
        const int i = int(indices[lane]);
        if (i >= 0 &&
            (distances[lane] < bestDistance || (distances[lane] == bestDistance && i < best))) {
            best = i;
            bestDistance = distances[lane];
        }
    }
    for (int i = int(4 * quads); i < size(); ++i) {
        const double d = squaredDistance(i, p);
        if (d < bestDistance) {
            bestDistance = d;
            best = i;
        }
    }
    return best;
}

int Tree::bestByScore() const {
    int best = -1;
    for (int i = 1; i < size(); ++i) {
        if (best < 0 || nodes_[i].score > nodes_[best].score)
            best = i;
    }
    return best;
}

std::vector<int> Tree::branch(int node) const {
    std::vector<int> path;
    for (int i = node; i > 0; i = nodes_[i].parent)
        path.push_back(i);
    std::reverse(path.begin(), path.end());
    return path;
}

std::vector<TreeEdge> Tree::edges() const {
    std::vector<TreeEdge> result;
    result.reserve(nodes_.size());
    for (const TreeNode& n : nodes_) {
        if (n.parent >= 0)
            result.push_back({nodes_[n.parent].position, n.position});
    }
    return result;
}

}  // namespace daep::planning
