#include "daep/planning/Roadmap.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>
#include <utility>

namespace daep::planning {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/** Min-heap entry: (priority, node); ties resolved by node index for determinism. */
using QueueEntry = std::pair<double, int>;
using MinQueue = std::priority_queue<QueueEntry, std::vector<QueueEntry>, std::greater<>>;

}  // namespace

Roadmap::Roadmap(double cellSize) : cellSize_(cellSize) {}

Eigen::Vector3i Roadmap::cellOf(const Eigen::Vector3d& p) const {
    return (p / cellSize_).array().floor().cast<int>();
}

Roadmap::CellKey Roadmap::keyOf(const Eigen::Vector3i& c) const {
    constexpr CellKey kSpan = 1 << 20;  // cell coordinates within +-2^19 (+-786 km at 1.5 m)
    const auto wrap = [](int v) { return CellKey(v) + kSpan / 2; };
    return (wrap(c.x()) * kSpan + wrap(c.y())) * kSpan + wrap(c.z());
}

int Roadmap::addNode(const Eigen::Vector3d& position) {
    const int i = size();
    RoadmapNode n;
    n.position = position;
    nodes_.push_back(n);
    links_.emplace_back();
    grid_[keyOf(cellOf(position))].push_back(i);
    return i;
}

void Roadmap::removeLastNode() {
    if (nodes_.empty() || !links_.back().empty())
        throw std::logic_error("Roadmap::removeLastNode: no node, or it has edges");
    grid_[keyOf(cellOf(nodes_.back().position))].pop_back();
    nodes_.pop_back();
    links_.pop_back();
}

int Roadmap::findEdge(int a, int b) const {
    for (const RoadmapLink& l : links_[a])
        if (l.to == b)
            return l.edge;
    return -1;
}

int Roadmap::addEdge(int a, int b, std::uint64_t revision) {
    const int existing = findEdge(a, b);
    if (existing >= 0)
        return existing;
    RoadmapEdge e;
    e.a = a;
    e.b = b;
    e.length = (nodes_[a].position - nodes_[b].position).norm();
    e.checkedRevision = revision;
    const int id = edgeCount();
    edges_.push_back(e);
    links_[a].push_back({b, id});
    links_[b].push_back({a, id});
    return id;
}

std::vector<int> Roadmap::within(const Eigen::Vector3d& p, double radius) const {
    std::vector<std::pair<double, int>> found;
    const Eigen::Vector3i lo = cellOf(p.array() - radius);
    const Eigen::Vector3i hi = cellOf(p.array() + radius);
    const double r2 = radius * radius;
    for (int x = lo.x(); x <= hi.x(); ++x) {
        for (int y = lo.y(); y <= hi.y(); ++y) {
            for (int z = lo.z(); z <= hi.z(); ++z) {
                const auto it = grid_.find(keyOf({x, y, z}));
                if (it == grid_.end())
                    continue;
                for (int i : it->second) {
                    const double d2 = (nodes_[i].position - p).squaredNorm();
                    if (d2 <= r2)
                        found.emplace_back(d2, i);
                }
            }
        }
    }
    std::sort(found.begin(), found.end());
    std::vector<int> result;
    result.reserve(found.size());
    for (const auto& f : found)
        result.push_back(f.second);
    return result;
}

int Roadmap::nearest(const Eigen::Vector3d& p) const {
    int best = -1;
    double bestD2 = kInf;
    for (int i = 0; i < size(); ++i) {
        const double d2 = (nodes_[i].position - p).squaredNorm();
        if (d2 < bestD2) {
            bestD2 = d2;
            best = i;
        }
    }
    return best;
}

double Roadmap::nearestDistance(const Eigen::Vector3d& p) const {
    const int i = nearest(p);
    return i < 0 ? kInf : (nodes_[i].position - p).norm();
}

Roadmap::Paths Roadmap::shortestPaths(int start, std::uint64_t revision) const {
    Paths paths;
    paths.cost.assign(nodes_.size(), kInf);
    paths.previous.assign(nodes_.size(), -1);
    MinQueue open;
    paths.cost[start] = 0.0;
    open.push({0.0, start});
    while (!open.empty()) {
        const auto [cost, u] = open.top();
        open.pop();
        if (cost > paths.cost[u])
            continue;
        for (const RoadmapLink& l : links_[u]) {
            const RoadmapEdge& e = edges_[l.edge];
            const double c = cost + e.length;
            if (usable(e, revision) && c < paths.cost[l.to]) {
                paths.cost[l.to] = c;
                paths.previous[l.to] = u;
                open.push({c, l.to});
            }
        }
    }
    return paths;
}

std::vector<int> Roadmap::pathTo(const Paths& paths, int start, int goal) {
    if (!std::isfinite(paths.cost[goal]))
        return {};
    std::vector<int> path;
    for (int v = goal; v != start; v = paths.previous[v])
        path.push_back(v);
    path.push_back(start);
    std::reverse(path.begin(), path.end());
    return path;
}

std::vector<int> Roadmap::aStar(int start, int goal, std::uint64_t revision) const {
    Paths paths;
    paths.cost.assign(nodes_.size(), kInf);
    paths.previous.assign(nodes_.size(), -1);
    std::vector<char> closed(nodes_.size(), 0);
    const Eigen::Vector3d& target = nodes_[goal].position;
    const auto h = [&](int v) { return (nodes_[v].position - target).norm(); };
    MinQueue open;
    paths.cost[start] = 0.0;
    open.push({h(start), start});
    while (!open.empty()) {
        const int u = open.top().second;
        open.pop();
        if (u == goal)
            return pathTo(paths, start, goal);
        if (closed[u])
            continue;
        closed[u] = 1;
        for (const RoadmapLink& l : links_[u]) {
            const RoadmapEdge& e = edges_[l.edge];
            const double c = paths.cost[u] + e.length;
            if (usable(e, revision) && c < paths.cost[l.to]) {
                paths.cost[l.to] = c;
                paths.previous[l.to] = u;
                open.push({c + h(l.to), l.to});
            }
        }
    }
    return {};
}

std::vector<int> Roadmap::lazyPath(int start, int goal, std::uint64_t revision,
                                   const EdgeCheck& check, int* checks) {
    // Every failed round marks one more edge blocked at `revision`, so this terminates.
    while (true) {
        std::vector<int> path = aStar(start, goal, revision);
        bool valid = true;
        for (std::size_t i = 0; valid && i + 1 < path.size(); ++i) {
            RoadmapEdge& e = edges_[findEdge(path[i], path[i + 1])];
            if (e.checkedRevision == revision)
                continue;
            if (checks)
                ++*checks;
            e.checkedRevision = revision;
            e.blocked = !check(path[i], path[i + 1]);
            valid = !e.blocked;
        }
        if (valid)
            return path;
    }
}

double Roadmap::pathLength(const std::vector<int>& path) const {
    double length = 0.0;
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
        length += (nodes_[path[i + 1]].position - nodes_[path[i]].position).norm();
    return length;
}

std::vector<TreeEdge> Roadmap::treeEdges() const {
    std::vector<TreeEdge> result;
    result.reserve(edges_.size());
    for (const RoadmapEdge& e : edges_)
        result.push_back({nodes_[e.a].position, nodes_[e.b].position});
    return result;
}

}  // namespace daep::planning
