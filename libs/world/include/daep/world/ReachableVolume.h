#pragma once

#include <Eigen/Core>
#include <cstddef>

#include "daep/world/WorldSpec.h"

namespace daep::world {

/** The run's parameters that bound what it can observe. */
struct ReachParams {
    double resolution = 0.2;   ///< [map] resolution: the OctoMap cell size, m
    double robotRadius = 0.3;  ///< [planning] robot_radius, m
    double climb = 1.0;        ///< [experiment] climb_m: the take-off climb above the start, m
    /** Grid beyond the box's cells and their one-cell ring, m (0: rays need no more, see below). */
    double margin = 0.0;
};

/** The most of the exploration box a run from one start can observe. */
struct ReachableVolume {
    /** Observable cells in the box x res^3 / WorldSpec::explorationVolume(), in %, <= 100. */
    double reachablePercent = 0.0;
    double observableVolume = 0.0;  ///< m^3 of observable cells whose centre lies in the box
    double dronePercent = 0.0;      ///< the same for the cells the drone itself can reach
    double droneVolume = 0.0;
    std::size_t observableCells = 0;
    std::size_t droneCells = 0;
    std::size_t gridCells = 0;
    Eigen::Vector3d seed = Eigen::Vector3d::Zero();  ///< centre of the cell the fills began in
    /** The spawn cell met the drone's clearance (else the fill began there all the same). */
    bool seedClear = true;
    /** The spawn cell overlapped geometry: the fills began at the nearest non-solid cell. */
    bool seedMoved = false;
};

/**
 * Upper bound of a run's coverage from `start`, on the map's cell grid (cells
 * [k res, (k+1) res), in the box when the centre lies in [min, max) on every axis, as
 * ExplorationMap counts them).
 *
 * - Solid: the cell's box (less 1e-6 res on each side, so that touching is not overlapping)
 *   overlaps static geometry (the ground slab included when the world has one).
 * - Drone cells: a 6-connected fill from the cell of start + (0, 0, climb) over cells whose
 *   centre lies in the box shrunk by robotRadius (where the planners sample) and with no solid
 *   cell box closer than robotRadius to the centre. Strictly closer: so a drone passes a gap of
 *   n free cells when n res > 2 robotRadius, as the planners' continuous positions do when
 *   robotRadius is a multiple of res / 2 (the default). The spawn cell begins the fill even
 *   when it is not clear (the drone is there); when it is solid, the nearest non-solid cell
 *   does.
 * - Observable: every non-solid cell 6-connected through non-solid cells to a drone cell, and
 *   every solid cell sharing a face, edge or corner with those (the surfaces rays end on: a
 *   solid cell's free part may lie next to a free cell's edge only). A ray is a straight line
 *   from the camera (in the box) to a cell in the box, so it never leaves the box, whose cells
 *   form a convex block: the grid holds those cells and one ring of cells around them (plus
 *   `margin`); more grid only loosens the bound.
 *
 * Not a strict bound where free space runs through solid (partly covered) cells only: a gap
 * narrower than a cell whose every cell overlaps geometry lets rays pass, not the fill, and
 * a solid cell whose free part is reached that way only is not counted. Deterministic. Throws
 * InputError for bad parameters or when no grid cell is free.
 */
ReachableVolume computeReachableVolume(const WorldSpec& world, const Eigen::Vector3d& start,
                                       const ReachParams& params = {});

}  // namespace daep::world
