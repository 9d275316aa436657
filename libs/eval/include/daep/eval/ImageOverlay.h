#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "daep/eval/Plot.h"

namespace daep::eval {

/** One legend entry: a swatch of the given shape and colour, and its text. */
struct LegendSwatch {
    enum class Shape { Box, Line, Thin };
    std::string label;
    Rgb color;
    Shape shape = Shape::Box;
};

/** A colour ramp with its label and end values (e.g. voxel height). */
struct ColorBar {
    std::string label;
    std::vector<Rgb> stops;  ///< evenly spaced, low to high
    std::string lowText, highText;
};

/** What is drawn over a rendered image: a title, a legend box and optionally a scale bar. */
struct Overlay {
    std::string title;
    std::vector<LegendSwatch> legend;
    ColorBar colorBar;          ///< drawn when it has stops
    double metresPerPixel = 0;  ///< > 0: a scale bar in the lower left corner
};

/**
 * Writes the image (8-bit BGR, `stride` bytes per row, as OpenCV and MRPT store it) to PATH as a
 * PNG with the overlay drawn on it with cairo in a real font. Throws std::runtime_error naming the
 * path when it cannot be written.
 */
void writeAnnotatedPng(const unsigned char* bgr, int width, int height, std::size_t stride,
                       const Overlay& overlay, const std::string& path);

/** A "nice" scale bar length (1, 2 or 5 times a power of ten) near `target` metres. */
double scaleBarLength(double target);

}  // namespace daep::eval
