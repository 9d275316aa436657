#pragma once

// Private to libs/eval: the drawing surface behind Plot and Figure.

#include <functional>
#include <string>
#include <vector>

#include "daep/eval/Plot.h"

namespace daep::eval::detail {

struct Pt {
    double x, y;
};

enum class Anchor { Start, Middle, End };

struct TextStyle {
    double size = 12.0;
    bool bold = false;
    Anchor anchor = Anchor::Start;
    bool vertical = false;  ///< rotated 90 degrees counter-clockwise about (x, y)
    Rgb color{};
};

/** The family asked for; fontconfig substitutes a sans-serif font if it is missing. */
inline constexpr const char* kFontFamily = "DejaVu Sans";

/** Drawing primitives in page units (y down); text is placed on its baseline. */
class Canvas {
public:
    virtual ~Canvas() = default;
    virtual void polyline(const std::vector<Pt>& pts, Rgb color, double width) = 0;
    virtual void fillPolygon(const std::vector<Pt>& pts, Rgb color, double alpha) = 0;
    virtual void fillRect(double x, double y, double w, double h, Rgb color,
                          double alpha = 1.0) = 0;
    virtual void strokeRect(double x, double y, double w, double h, Rgb color, double width) = 0;
    virtual void text(const std::string& s, double x, double y, const TextStyle& style) = 0;
    /** Clips what follows to the rectangle until endClip(). */
    virtual void beginClip(double x, double y, double w, double h) = 0;
    virtual void endClip() = 0;
    /** The advance width of `s` in the plot font at `size`. */
    virtual double textWidth(const std::string& s, double size, bool bold = false) const = 0;
};

/**
 * Calls `draw` on a white width x height page and writes it to `path` as PNG, SVG or PDF by its
 * extension; creates missing directories. Throws std::invalid_argument for another extension,
 * std::runtime_error naming the path when it cannot be written.
 */
void renderToFile(const std::string& path, int width, int height,
                  const std::function<void(Canvas&)>& draw);

}  // namespace daep::eval::detail
