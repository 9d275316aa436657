#pragma once

#include <string>

#include "daep/world/WorldSpec.h"

namespace daep::eval {

/**
 * Draws a top-down orthographic view of `world` into a `size` x `size` PNG: static geometry
 * footprints shaded by height, the exploration box, numbered starts, each person's route
 * (a coloured loop with arrows), a metre grid, a scale bar, a title and a legend.
 * Throws std::runtime_error when the PNG cannot be written.
 */
void renderWorldPng(const world::WorldSpec& world, const std::string& pngPath, int size);

}  // namespace daep::eval
