#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "daep/common/Types.h"
#include "daep/mapping/DenseGridIndex.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace mrpt::obs {
class CObservation3DRangeScan;
}
namespace octomap {
class OcTree;
}

namespace daep::mapping {

struct SensorFrame;

enum class CellState : std::uint8_t { Unknown = 0, Free = 1, Occupied = 2 };

/**
 * Where a person stands, as a vertical cylinder from the floor: depth points inside it are
 * the person, not the static world.
 */
struct PersonFootprint {
    Eigen::Vector2f centre = Eigen::Vector2f::Zero();
    float radius = 0.0f;
    float top = 0.0f;  ///< world z of the cylinder's top
};

struct MapParams {
    double resolution = 0.2;
    double maxRange = 5.0;  ///< longer rays clear space up to this range only
    double probHit = 0.7;
    double probMiss = 0.4;
    double clampMin = 0.12;
    double clampMax = 0.97;
    /**
     * Pixels with no return (nothing within the camera's range, which must exceed maxRange)
     * clear their ray up to maxRange: outdoors the open sky is otherwise never known.
     */
    bool noReturnIsFree = true;
    /**
     * The drone's own body, a box (half extents, in its frame, centred on its position).
     * Returns inside it are not mapped: only the drone itself, or a person it is inside, can
     * be there. Zero: no body. By default the [drone] box of defaults.ini, halved.
     */
    Eigen::Vector3d bodyHalfExtents{0.2, 0.2, 0.05};

    /** Reads and validates [map]; throws InputError naming the key. */
    static MapParams fromConfig(const mrpt::config::CConfigFileBase& cfg);
};

/**
 * The exploration map: an octomap::OcTree (the map of record, saved as .bt) mirrored into a
 * dense grid of cell states over the exploration box plus a margin, so that the planners'
 * millions of point queries are array lookups. Coverage is kept incrementally.
 *
 * Cells are the octree's leaf voxels at `resolution`; a cell belongs to the exploration box
 * when its centre lies in [min, max) on every axis. The half-open interval matters when a
 * box face falls exactly on cell centres: a closed one would count one extra layer and let
 * coverage pass 100 %.
 */
class ExplorationMap {
public:
    ExplorationMap(const MapParams& params, const Aabb& explorationBox);
    ~ExplorationMap();
    ExplorationMap(const ExplorationMap&) = delete;
    ExplorationMap& operator=(const ExplorationMap&) = delete;

    /** Integrates points (world frame) seen from origin: ray clearing + endpoint hits. */
    void insertPointCloud(const Eigen::Vector3d& origin,
                          const std::vector<Eigen::Vector3f>& points);

    /**
     * Unprojects a depth observation with MRPT (honouring its sensorPose) placed at the robot
     * pose, and integrates it.
     */
    void insertObservation(const mrpt::obs::CObservation3DRangeScan& obs, const FlatPose& robot);
    /**
     * The same, but a return on one of `people` clears its ray up to the person and marks
     * nothing occupied: people are not walls, and a person mapped as one would close a door
     * long after they walked through it.
     */
    void insertObservation(const mrpt::obs::CObservation3DRangeScan& obs, const FlatPose& robot,
                           const std::vector<PersonFootprint>& people);

    CellState state(const Eigen::Vector3d& p) const {
        const std::int64_t i = gridIndex_(p);
        return i >= 0 ? CellState(gridCells_[i]) : stateOffGrid(p);
    }
    /** Whether p lies on the dense grid, where stateOnGrid(p) may be asked. */
    bool onGrid(const Eigen::Vector3d& p) const { return gridIndex_(p) >= 0; }
    /** state(p) of a point on the dense grid (see DenseGridIndex::onGrid). */
    CellState stateOnGrid(const Eigen::Vector3d& p) const {
        return CellState(gridCells_[gridIndex_.onGrid(p)]);
    }
    /** stateOnGrid(p) through DenseGridIndex::onGridFloored. */
    CellState stateOnGridFloored(const Eigen::Vector3d& p) const {
        return CellState(gridCells_[gridIndex_.onGridFloored(p)]);
    }
    bool isFree(const Eigen::Vector3d& p) const { return state(p) == CellState::Free; }
    bool isOccupied(const Eigen::Vector3d& p) const { return state(p) == CellState::Occupied; }
    bool isUnknown(const Eigen::Vector3d& p) const { return state(p) == CellState::Unknown; }
    /**
     * Whether a return has ended in p's cell (on the dense grid) while the map held it surely
     * free (at the free clamping threshold): something moved into known free space, as walls
     * do not. A person the camera's people input missed leaves such cells behind.
     */
    bool movedIn(const Eigen::Vector3d& p) const;

    /**
     * Whether people can enter this map as occupied cells (default: no). Then clearance
     * checks stop treating grazed surfaces as occupied (see isSegmentFree): the trail a mapped
     * person leaves beside a wall, or beside what is left of their own imprint, looks the same
     * and would close corridors.
     */
    void setPeopleMapped(bool mapped);

    /** All cells touching the axis-aligned box (centre, half extents) are known free. */
    bool isBoxFree(const Eigen::Vector3d& center, const Eigen::Vector3d& halfExtents) const;

    /**
     * The capsule of `radius` around segment a-b lies in known free space. A free cell that
     * rays ended in, beside a cell that is not free, counts as occupied (a grazed surface) unless
     * people are mapped.
     */
    bool isSegmentFree(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius) const;

    /** Like isSegmentFree but only occupied cells block (unknown space allowed). */
    bool isSegmentFreeOrUnknown(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                double radius) const;

    /**
     * Like isSegmentFree, but an occupied cell something moved into (movedIn: the imprint of a
     * person the people input missed) does not block, nor does one the drone's centre has
     * been in (markFlown: no wall is there; a person who walked into the drone may be).
     */
    bool isSegmentFreeThroughImprints(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                      double radius) const;

    /**
     * No occupied cell enters the axis-aligned box (half extents) swept from a to b, but for
     * those the box already meets at a. Unknown space is allowed, as in isSegmentFreeOrUnknown.
     */
    bool isSweptBoxClearOfNew(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                              const Eigen::Vector3d& halfExtents) const;

    /**
     * Walks from origin along unitDir; returns the distance to the first occupied cell, or
     * maxRange if none.
     */
    double castRay(const Eigen::Vector3d& origin, const Eigen::Vector3d& unitDir,
                   double maxRange) const;

    /**
     * Viewpoints on the map's frontier, nearest first: the known free cells inside the box
     * that the drone reaches from `from` through cells where it is `usable` (face neighbours;
     * its clearance, say), and from which an unknown cell inside the box lies within `reach`
     * cells along an axis with free cells between. At least `spacing` apart; at most
     * `maxViewpoints`. What is left to see, whatever a planner's samples found.
     */
    std::vector<Eigen::Vector3d> frontierViewpoints(
        const Eigen::Vector3d& from, const std::function<bool(const Eigen::Vector3d&)>& usable,
        int reach, double spacing, std::size_t maxViewpoints) const;

    /**
     * Whether a march out of p (inside the box) could meet an unknown cell inside the box
     * before an occupied one, when its samples lie within `range` of p and each is less than a
     * cell from the one before on every axis (the first less than a cell from p): the first
     * unknown sample is then next to p's cell, or a frontier cell (unknown, with a free cell
     * among its 26 neighbours). False is sure; true may be wrong, and is the answer for p
     * outside the box. Blocks of 8 x 8 x 8 cells remember whether they hold a frontier cell, so
     * an answer costs a few hundred lookups, and a block changed since it was last asked is
     * scanned again (512 cells and the neighbours of its unknown ones).
     */
    bool mayMeetUnknown(const Eigen::Vector3d& p, double range) const;

    /**
     * The fewest face steps from `from` to a cell whose centre `isGoal` accepts, through the
     * cells frontierViewpoints walks (known free, inside the box, `usable` at the centre):
     * `from`, then the cells' centres. Empty when no such cell is reached. What a sampled
     * tree's budget can miss (a narrow doorway far off), searched exhaustively.
     */
    std::vector<Eigen::Vector3d> freeCellPath(
        const Eigen::Vector3d& from, const std::function<bool(const Eigen::Vector3d&)>& usable,
        const std::function<bool(const Eigen::Vector3d&)>& isGoal) const;

    /** Known (free or occupied) cells whose centre lies inside the exploration box. */
    std::size_t knownCellsInBox() const { return knownInBox_; }
    double knownVolumeInBox() const;
    /** Known volume / box volume, in [0, 1]. */
    double coverage() const;

    double resolution() const { return params_.resolution; }
    const MapParams& params() const { return params_; }
    const Aabb& explorationBox() const { return box_; }
    /**
     * The map as an OctoMap tree, the very tree OctoMap's own updates would have built. The
     * dense grid's cells reach it when it is asked for, so this call writes to it: not to be
     * made from two threads at once, nor while another thread reads the tree.
     */
    const octomap::OcTree& octree() const;

    /** Centre of the cell that contains p. */
    Eigen::Vector3d cellCenter(const Eigen::Vector3d& p) const;

    /** Writes the octree as a binary .bt file (octovis). Returns false on I/O failure. */
    bool writeBinary(const std::string& path) const;

    /**
     * The drone's centre is at `position`: its cell counts as no grazed surface from now on (a
     * surface in it would lie inside the drone). insertObservation marks the robot's position.
     */
    void markFlown(const Eigen::Vector3d& position);

    /** Number of insertions so far; planners use it to know the map changed. */
    std::uint64_t revision() const { return revision_; }

private:
    /** With noReturnIsFree: end points beyond maxRange for the pixels with no return. */
    void addNoReturnRays(const mrpt::obs::CObservation3DRangeScan& obs, const SensorFrame& frame);

    /** state() of a point outside the dense grid: the octree's answer. */
    CellState stateOffGrid(const Eigen::Vector3d& p) const;

    struct Impl;
    std::unique_ptr<Impl> impl_;
    DenseGridIndex gridIndex_;                 ///< a copy of the dense grid's
    const std::uint8_t* gridCells_ = nullptr;  ///< the dense grid's cell states
    MapParams params_;
    Aabb box_;
    std::size_t knownInBox_ = 0;
    std::uint64_t revision_ = 0;
};

}  // namespace daep::mapping
