#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

#include "daep/planning/Planner.h"

namespace daep::planning {

/** A roadmap vertex: a viewpoint with its gain per heading bin. */
struct RoadmapNode {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    std::vector<double> binGains;  ///< gain per yaw bin; empty until evaluated
    int bestBin = 0;
    double bestGain = 0.0;
    std::uint64_t gainRevision = 0;  ///< map revision the gains were computed at
    bool hasGain = false;
    std::uint64_t spentColumns = 0;  ///< azimuth sectors that kept their gain when looked at
    std::size_t spentKnown = 0;      ///< known cells in the map when they were marked
    bool anchor = false;             ///< a drone position, not a sample: its own ball may be unseen
};

/** An undirected edge as seen from one end; `checked`/`blocked` are shared via the edge id. */
struct RoadmapLink {
    int to = -1;
    int edge = -1;
};

struct RoadmapEdge {
    int a = -1;
    int b = -1;
    double length = 0.0;
    std::uint64_t checkedRevision = 0;  ///< map revision of the last collision check
    bool blocked = false;               ///< result of that check
};

/**
 * A probabilistic roadmap that only grows: nodes and edges are appended, indices stay valid.
 * A uniform hash grid answers radius queries. Edges carry the result of their last collision
 * check together with the map revision it was made at, so searches can skip edges known to be
 * blocked now and re-check lazily the ones checked against an older map.
 */
class Roadmap {
public:
    /** Edge check used by lazy searches: true when the segment between nodes a and b is safe. */
    using EdgeCheck = std::function<bool(int a, int b)>;

    explicit Roadmap(double cellSize = 1.5);

    int addNode(const Eigen::Vector3d& position);
    /** Drops the newest node; it must have no edges yet. */
    void removeLastNode();
    /** Adds edge a-b (checked at `revision`); returns its id, or the existing edge's id. */
    int addEdge(int a, int b, std::uint64_t revision);

    /** Nodes within `radius` of p, nearest first (ties by index). */
    std::vector<int> within(const Eigen::Vector3d& p, double radius) const;
    /** Nearest node, or -1 when empty. */
    int nearest(const Eigen::Vector3d& p) const;
    /** Distance from p to the nearest node (infinity when empty). */
    double nearestDistance(const Eigen::Vector3d& p) const;

    /** Dijkstra from start; edges blocked at `revision` are skipped. */
    struct Paths {
        std::vector<double> cost;  ///< infinity when unreachable
        std::vector<int> previous;
    };
    Paths shortestPaths(int start, std::uint64_t revision) const;
    /** Node sequence start..goal along the Dijkstra tree (empty when unreachable). */
    static std::vector<int> pathTo(const Paths& paths, int start, int goal);

    /** A* from start to goal; edges blocked at `revision` are skipped. Empty when unreachable. */
    std::vector<int> aStar(int start, int goal, std::uint64_t revision) const;

    /**
     * Lazy shortest path: A* treating every edge not known blocked at `revision` as free, then
     * checking only the edges of the found path that were not checked at `revision`; a blocked
     * edge is marked and the search repeats. Returns a path whose edges all passed a check at
     * `revision`, or empty when none exists. `checks` (optional) counts the checks made.
     */
    std::vector<int> lazyPath(int start, int goal, std::uint64_t revision, const EdgeCheck& check,
                              int* checks = nullptr);

    double pathLength(const std::vector<int>& path) const;

    int size() const { return static_cast<int>(nodes_.size()); }
    int edgeCount() const { return static_cast<int>(edges_.size()); }
    const RoadmapNode& node(int i) const { return nodes_[i]; }
    RoadmapNode& node(int i) { return nodes_[i]; }
    const RoadmapEdge& edge(int e) const { return edges_[e]; }
    RoadmapEdge& edge(int e) { return edges_[e]; }
    const std::vector<RoadmapLink>& links(int i) const { return links_[i]; }
    /** Id of edge a-b, or -1. */
    int findEdge(int a, int b) const;
    std::vector<TreeEdge> treeEdges() const;

private:
    using CellKey = std::int64_t;
    CellKey keyOf(const Eigen::Vector3i& c) const;
    Eigen::Vector3i cellOf(const Eigen::Vector3d& p) const;
    bool usable(const RoadmapEdge& e, std::uint64_t revision) const {
        return !(e.blocked && e.checkedRevision == revision);
    }

    double cellSize_;
    std::vector<RoadmapNode> nodes_;
    std::vector<std::vector<RoadmapLink>> links_;
    std::vector<RoadmapEdge> edges_;
    std::unordered_map<CellKey, std::vector<int>> grid_;
};

}  // namespace daep::planning
