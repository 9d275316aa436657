#pragma once

#include <octomap/OcTree.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "OctreeKeys.h"
#include "daep/mapping/DenseGridIndex.h"
#include "daep/mapping/ExplorationMap.h"

namespace daep::mapping {

struct DepthRow;
struct PixelTests;

/**
 * The octree plus its dense mirror. Dense-grid indices are derived from octree keys only, so
 * the grid and the tree agree on which cell contains a point.
 */
struct ExplorationMap::Impl {
    Impl(const MapParams& params, const Aabb& box);

    mutable octomap::OcTree tree;  ///< behind the grid's cells until flushTree()
    octomap::OcTreeKey gridMin;    ///< key of the grid's first cell on each axis
    std::array<int, 3> dims{};
    std::vector<std::uint8_t> cells;
    /// Per dense cell: kEverHit once any frame ended a ray in it (see grazedSurface); whether
    /// its log-odds sit at a clamping threshold (an update towards it changes nothing); and the
    /// marks of the frame being integrated.
    std::vector<std::uint8_t> flags;
    static constexpr std::uint8_t kEverHit = 1, kFreeNow = 2, kOccupiedNow = 4, kEndNow = 8;
    static constexpr std::uint8_t kFrameMarks = kFreeNow | kOccupiedNow | kEndNow;
    static constexpr std::uint8_t kClampedFree = 16, kClampedOccupied = 32;
    /// The drone's centre has been in the cell: whatever rays ended in it, no wall grazes it.
    static constexpr std::uint8_t kFlown = 64;
    /// A return ended in the cell while it was clamped free: something moved in (see movedIn).
    static constexpr std::uint8_t kMovedIn = 128;
    /// Per dense cell: its log-odds, as OctoMap's updates would leave them (0 while unknown).
    /// The octree takes the cells that changed only when it is read (flushTree): a cell is
    /// updated several times before it clamps, and the tree's search, expansion and pruning
    /// each time cost more than the grid's own update. Kept per block of the frontier blocks'
    /// size, allocated when a cell in it is first updated: a world's grid holds much that is
    /// never seen (under the ground, inside walls, beyond the box's walls).
    std::vector<std::unique_ptr<float[]>> logOddsBlocks;
    /** Grid cell (x, y, z)'s log-odds, its block allocated if need be. */
    float& logOddsAt(int x, int y, int z) {
        std::unique_ptr<float[]>& block =
            logOddsBlocks[blockIndex(x >> kBlockShift, y >> kBlockShift, z >> kBlockShift)];
        if (!block)
            block = std::make_unique<float[]>(std::size_t(1) << (3 * kBlockShift));  // zeros
        return block[inBlock(x, y, z)];
    }
    /** The log-odds of a grid cell that has been updated (its block exists). */
    float updatedLogOdds(int x, int y, int z) const {
        return logOddsBlocks[blockIndex(x >> kBlockShift, y >> kBlockShift, z >> kBlockShift)]
                            [inBlock(x, y, z)];
    }
    static std::size_t inBlock(int x, int y, int z) {
        constexpr int kMask = (1 << kBlockShift) - 1;
        return std::size_t((x & kMask) + ((y & kMask) << kBlockShift) +
                           ((z & kMask) << (2 * kBlockShift)));
    }
    /// One bit per dense cell: changed since the tree last took it (the list holds each once).
    mutable std::vector<std::uint64_t> treeStale;
    mutable std::vector<std::int64_t> treeStaleCells;
    /** Gives the octree every dense cell changed since it was last read. */
    void flushTree() const;
    /// Per axis, whether the cell with that key offset has its centre inside the box.
    std::array<std::vector<std::uint8_t>, 3> inBox;
    /// Per axis, whether the cell with that key offset overlaps the box at all (its centre may
    /// lie outside), with a tolerance far above rounding: where a point inside the box, or on
    /// its face give or take rounding, may fall.
    std::array<std::vector<std::uint8_t>, 3> touchesBox;

    /// The frame's end cells, each once (marked kEndNow when added); scratch buffers reused
    /// between insertions.
    std::vector<octomap::OcTreeKey> ends;
    octomap::KeySet personKeys;        ///< cells of returns on people: cleared up to, not marked
    std::vector<std::int64_t> marked;  ///< dense cells with frame marks
    /// The frame's marks on cells outside the dense grid, one set per mark.
    octomap::KeySet freeOutside, occupiedOutside, endsOutside;
    std::vector<std::uint64_t> rowAbove;  ///< packed keys of the previous image row

    /** Key of the cell containing p; false if p is not finite or outside the tree. */
    template <class Point>  // Eigen::Vector3d or octomap::point3d
    bool keyOf(const Point& p, octomap::OcTreeKey& key) const {
        return axisKeyOf(p.x(), key[0]) && axisKeyOf(p.y(), key[1]) && axisKeyOf(p.z(), key[2]);
    }
    /** OctoMap's coordToKeyChecked, bit for bit, and faster (octreeAxisKey). */
    bool axisKeyOf(double c, octomap::key_type& k) const {
        return octreeAxisKey(pointIndex.scale, c, k);
    }

    /// Point to dense index; its scale is the octree's private resolution_factor.
    DenseGridIndex pointIndex;

    /**
     * Dense index of the cell containing p, or -1 outside the grid. The tests check it against
     * octree search on and off cell boundaries.
     */
    std::int64_t gridIndex(const Eigen::Vector3d& p) const { return pointIndex(p); }

    /** The dense index of grid cell (x, y, z). */
    std::size_t cellIndex(int x, int y, int z) const {
        return std::size_t(x + std::int64_t(dims[0]) * (y + std::int64_t(dims[1]) * z));
    }
    /** The grid cell of a dense index (the inverse of cellIndex). */
    std::array<int, 3> cellOfIndex(std::int64_t i) const {
        const std::int64_t plane = std::int64_t(dims[0]) * dims[1];
        return {int(i % dims[0]), int(i % plane / dims[0]), int(i / plane)};
    }

    /** Dense index of key, or -1 when the key lies outside the dense grid. */
    std::int64_t gridIndex(const octomap::OcTreeKey& key) const {
        const int x = int(key[0]) - int(gridMin[0]);
        const int y = int(key[1]) - int(gridMin[1]);
        const int z = int(key[2]) - int(gridMin[2]);
        if (x < 0 || y < 0 || z < 0 || x >= dims[0] || y >= dims[1] || z >= dims[2]) {
            return -1;
        }
        return std::int64_t(cellIndex(x, y, z));
    }

    /** The key of a dense index (the inverse of gridIndex). */
    octomap::OcTreeKey keyOfIndex(std::int64_t i) const { return keyOfCell(cellOfIndex(i)); }
    /** The key of grid cell (x, y, z). */
    octomap::OcTreeKey keyOfCell(const std::array<int, 3>& c) const {
        return octomap::OcTreeKey(octomap::key_type(gridMin[0] + c[0]),
                                  octomap::key_type(gridMin[1] + c[1]),
                                  octomap::key_type(gridMin[2] + c[2]));
    }

    Eigen::Vector3d cellCentre(std::int64_t i) const;
    /** Whether the dense cell's centre lies inside the exploration box (see inBox). */
    bool indexInBox(std::int64_t i) const;

    std::int64_t walkFreeCells(std::int64_t start,
                               const std::function<bool(const Eigen::Vector3d&)>& usable,
                               const std::function<bool(std::int64_t)>& visit,
                               std::vector<std::int64_t>* parents = nullptr) const;

    CellState stateAt(const octomap::OcTreeKey& key) const {
        const std::int64_t i = gridIndex(key);
        return i >= 0 ? CellState(cells[std::size_t(i)]) : treeState(key);
    }

    CellState treeState(const octomap::OcTreeKey& key) const;

    /**
     * A free cell that rays have ended in, beside a cell that is not free: the face of a
     * surface a few cm into the cell (a post's side; a wall whose inside stays unknown), which
     * rays grazing the cell's free part have cleared. Clearance checks treat it as occupied,
     * or the drone could brush the surface.
     */
    bool grazedSurface(const octomap::OcTreeKey& key, bool imprintsPass = false) const;
    /**
     * Dense cell i is occupied, but by no wall: something moved in after it was surely free,
     * or the drone's centre has been in it. With `imprintsPass`, grazedSurface does not count
     * such a neighbour as a surface.
     */
    bool isImprint(std::int64_t i) const {
        return cells[std::size_t(i)] == std::uint8_t(CellState::Occupied) &&
               (flags[std::size_t(i)] & (kMovedIn | kFlown));
    }
    bool guardGrazed = true;  ///< no person enters the map (setPeopleMapped)
    void setGuardGrazed(bool guard);

    /**
     * Per row of the grid (y + dims[1] * z), one bit per cell along x: whether the cell
     * passes isSegmentFree's cell test (free, and not a guarded grazed surface), so that a
     * capsule skips the passing cells of its rows a word at a time. Rows on the grid's outer
     * shell are not kept (their cells' neighbours lie in the octree), nor are the first and
     * last cell of a row (their bits stay 0, so they are tested one by one). A row is rebuilt
     * when it is asked for after a cell in it or beside it changed.
     */
    mutable std::vector<std::uint64_t> passBits;
    mutable std::vector<std::uint8_t> passStale;  ///< per row: rebuild before use
    int passWords = 0;                            ///< 64-bit words per row
    bool keepsPassBits(int y, int z) const {
        return y > 0 && y + 1 < dims[1] && z > 0 && z + 1 < dims[2];
    }
    /** The fresh pass bits of row (y, z), grid coordinates; keepsPassBits(y, z) must hold. */
    const std::uint64_t* passRow(int y, int z) const;
    /** A dense cell's state or hit flag changed: the rows its test, or its neighbours', read. */
    void passCellChanged(std::int64_t i);

    bool keyInBox(const octomap::OcTreeKey& key) const;

    /**
     * Per block of 8 x 8 x 8 dense cells: whether it holds a frontier cell (unknown, with a free
     * cell among its 26 neighbours). A block is worked out when it is asked for after a cell in
     * it or beside it changed state.
     */
    static constexpr int kBlockShift = 3;
    static constexpr std::uint8_t kBlockStale = 1, kBlockHasFrontier = 2;
    std::array<int, 3> blockDims{};
    mutable std::vector<std::uint8_t> blocks;
    std::size_t blockIndex(int bx, int by, int bz) const {
        return std::size_t(bx +
                           std::int64_t(blockDims[0]) * (by + std::int64_t(blockDims[1]) * bz));
    }
    /** Whether block (bx, by, bz) holds a frontier cell. */
    bool blockHasFrontier(int bx, int by, int bz) const;
    /** Dense cell (x, y, z) is unknown with a free cell among its 26 neighbours. */
    bool isFrontierCell(int x, int y, int z) const;
    /** A dense cell's state changed: the blocks holding it or its neighbours are stale. */
    void frontierCellChanged(std::int64_t i);

    /** Lower corner of the cell with this key along one axis. */
    double cellLow(octomap::key_type k) const {
        return tree.keyToCoord(k) - 0.5 * tree.getResolution();
    }

    /**
     * Which cells a capsule may touch: free ones (isSegmentFree), any not occupied, or free
     * ones and occupied ones something moved into or the drone has been in
     * (isSegmentFreeThroughImprints).
     */
    enum class Passable { Free, NotOccupied, FreeOrImprint };
    /** True when every cell whose box is within radius of segment a-b is passable. */
    template <Passable P>
    bool capsuleCellsAllowed(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             double radius) const;

    /** Adds the end cells of one image row's pixels that pass the frame's tests. */
    void addRowEnds(const DepthRow& row, const PixelTests& tests);
    template <bool kFloored>
    void addRowEnds(const DepthRow& row, const PixelTests& tests);
    __attribute__((target("sse4.1"))) void addRowEndsSse41(const DepthRow& row,
                                                           const PixelTests& tests);
    template <bool kFloored>
    bool pixelKey(const Eigen::Vector3f& p, octomap::OcTreeKey& key) const;

    /** Adds the cell of an end point to the frame's ends, unless it is there already. */
    void addEnd(const octomap::OcTreeKey& key) {
        if (mark(key, kEndNow))
            ends.push_back(key);
    }
    /** addEnd of the cell containing p, if p is finite and inside the tree. */
    void addEndPoint(const octomap::point3d& p) {
        octomap::OcTreeKey key;
        if (keyOf(p, key))
            addEnd(key);
    }

    /**
     * Integrates the frame's ends (world frame) seen from origin. Returns the number of cells
     * inside the box that went from Unknown to known.
     */
    std::size_t integrate(const octomap::point3d& origin, double maxRange);

    /** Gives a cell a frame mark; false when it had that mark already. */
    bool mark(const octomap::OcTreeKey& key, std::uint8_t mark);
    bool markOutside(const octomap::OcTreeKey& key, std::uint8_t mark);
    /** mark() of the dense cell i. */
    bool markCell(std::int64_t i, std::uint8_t m) {
        std::uint8_t& f = flags[std::size_t(i)];
        if (f & m)
            return false;
        if (!(f & kFrameMarks))
            marked.push_back(i);
        f |= m;
        return true;
    }
    void markRay(const octomap::point3d& origin, const octomap::point3d& end);
    /**
     * Whether a ray walk from cell `from` to cell `to` stays on the dense grid: their box, grown
     * by the one cell a walk may step past its end's cell on an axis (rounding, where the
     * segment's end lies on a cell face), lies on it.
     */
    bool walkStaysOnGrid(const octomap::OcTreeKey& from, const octomap::OcTreeKey& to) const;
    /** The map update of one marked cell; true when it went from unknown to known in the box. */
    bool applyUpdate(const octomap::OcTreeKey& key, bool hit);
};

}  // namespace daep::mapping
