#pragma once

namespace daep::world {

struct WorldSpec;

/**
 * Checks a parsed world for what parses but cannot be flown: coordinates that are not finite
 * or lie farther than kMaxCoordinate from the origin, an exploration box too large to map,
 * a start inside static geometry, and a person's route whose straight leg (between consecutive
 * waypoints, the last back to the first) crosses static geometry at body height. Throws
 * InputError naming the file and the item (starts[i], people[i] 'name' leg j, boxes[i] 'name').
 */
void validateWorld(const WorldSpec& world);

/** Farthest a coordinate may lie from the origin, m (the map's octree reaches +-6.5 km). */
constexpr double kMaxCoordinate = 5000.0;
/** Largest exploration box, m^3 (250 Villages; 1.25e9 cells at 0.2 m). */
constexpr double kMaxExplorationVolume = 1e7;

}  // namespace daep::world
