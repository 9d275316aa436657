#pragma once

#include <string>
#include <utility>
#include <vector>

namespace daep::eval {

struct Rgb {
    unsigned char r = 0, g = 0, b = 0;
};

namespace detail {
class Canvas;
struct Frame;
}  // namespace detail

enum class LegendCorner { TopLeft, TopRight, BottomLeft, BottomRight };

/**
 * A small x/y chart: lines, translucent bands and highlighted x-intervals, axes with ticks and
 * labels, a title and a legend. Or, once timeline rows are added, a timeline: one labelled row
 * per entry with its [start, end] spans as bars (lines and bands are then not drawn).
 * Written as PNG, SVG or PDF (by the file's extension) with cairo and a real font (DejaVu Sans);
 * sizes are pixels in PNG and points in SVG and PDF.
 */
class Plot {
public:
    Plot(int width, int height);

    void setTitle(std::string title) { title_ = std::move(title); }
    /** A smaller line under the title (what bands or bars mean). */
    void setSubtitle(std::string subtitle) { subtitle_ = std::move(subtitle); }
    void setXLabel(std::string label) { xLabel_ = std::move(label); }
    void setYLabel(std::string label) { yLabel_ = std::move(label); }
    /** Fixes the y range (otherwise taken from the data). */
    void setYRange(double lo, double hi);
    /** Fixes the x range (otherwise taken from the data), e.g. to align stacked panels. */
    void setXRange(double lo, double hi);
    void setLegendCorner(LegendCorner corner) { legendCorner_ = corner; }

    /** A polyline; a non-empty label adds a legend entry. */
    void addLine(std::vector<double> x, std::vector<double> y, Rgb color, std::string label = "");
    /** The area between lo(x) and hi(x), blended with the given opacity. */
    void addBand(std::vector<double> x, std::vector<double> lo, std::vector<double> hi, Rgb color,
                 double alpha = 0.25);
    /** Marks [start, end] x-intervals as thick segments along the bottom of the plot area. */
    void addIntervals(std::vector<std::pair<double, double>> intervals, Rgb color,
                      std::string label = "");
    /** A timeline row (top to bottom in call order): its label and its spans drawn as bars. */
    void addTimelineRow(std::string label, std::vector<std::pair<double, double>> spans, Rgb color);
    /** More spans, in another colour, on the last timeline row (throws if there is none). */
    void addTimelineSpans(std::vector<std::pair<double, double>> spans, Rgb color);
    /** A legend entry drawn as a filled square, for colours not tied to a line. */
    void addLegendEntry(std::string label, Rgb color);

    /**
     * Renders and writes PATH as PNG, SVG or PDF, chosen by its extension (.png, .svg, .pdf);
     * creates missing directories. Throws std::invalid_argument for another extension and
     * std::runtime_error naming the path when it cannot be written.
     */
    void save(const std::string& path) const;
    /** Writes STEM.<ext> for each extension (default png, svg, pdf); returns the paths. */
    std::vector<std::string> saveAs(const std::string& stem,
                                    const std::vector<std::string>& extensions = {"png", "svg",
                                                                                  "pdf"}) const;

    int width() const { return width_; }
    int height() const { return height_; }

private:
    friend class Figure;
    struct Line {
        std::vector<double> x, y;
        Rgb color;
        std::string label;
    };
    struct Band {
        std::vector<double> x, lo, hi;
        Rgb color;
        double alpha;
    };
    struct Intervals {
        std::vector<std::pair<double, double>> spans;
        Rgb color;
        std::string label;
    };
    struct Row {
        std::string label;
        std::vector<Intervals> layers;
    };
    struct Range {
        double x0, x1, y0, y1;
    };
    Range dataRange() const;
    bool isTimeline() const { return !rows_.empty(); }
    /** The left margin this plot needs for its y tick labels or row labels. */
    double leftMargin(const detail::Canvas& canvas) const;
    /** Draws the plot with its top-left corner at (0, top) and the plot area from x = left. */
    void draw(detail::Canvas& canvas, double top, double left) const;
    void drawSeries(detail::Canvas& canvas, const detail::Frame& f) const;
    void drawTimeline(detail::Canvas& canvas, const detail::Frame& f) const;
    void drawLegend(detail::Canvas& canvas, const detail::Frame& f) const;

    int width_, height_;
    std::string title_, subtitle_, xLabel_, yLabel_;
    bool fixedX_ = false, fixedY_ = false;
    double xLo_ = 0.0, xHi_ = 1.0, yLo_ = 0.0, yHi_ = 1.0;
    LegendCorner legendCorner_ = LegendCorner::TopLeft;
    std::vector<Line> lines_;
    std::vector<Band> bands_;
    std::vector<Intervals> intervals_;
    std::vector<Row> rows_;  ///< timeline rows
    std::vector<std::pair<std::string, Rgb>> legendEntries_;
};

/**
 * Plots stacked top to bottom under one title, their plot areas aligned on the left (the
 * figure is as wide as its widest panel). Saved like a Plot.
 */
class Figure {
public:
    explicit Figure(std::string title = "") : title_(std::move(title)) {}

    void addPanel(Plot panel) { panels_.push_back(std::move(panel)); }
    void save(const std::string& path) const;
    std::vector<std::string> saveAs(const std::string& stem,
                                    const std::vector<std::string>& extensions = {"png", "svg",
                                                                                  "pdf"}) const;
    int width() const;
    int height() const;

private:
    double titleHeight() const { return title_.empty() ? 0.0 : 34.0; }

    std::string title_;
    std::vector<Plot> panels_;
};

/** A distinct colour for series i (a fixed qualitative palette). */
Rgb seriesColor(std::size_t i);

/** The smallest of 1, 2, 2.5, 5 and 10 times a power of ten that is at least raw (> 0). */
double niceStep(double raw);
/** "Nice" tick values covering [lo, hi], about `count` of them. */
std::vector<double> niceTicks(double lo, double hi, int count = 6);

}  // namespace daep::eval
