#pragma once

#include <string>
#include <utility>
#include <vector>

namespace daep::eval {

struct Rgb {
    unsigned char r = 0, g = 0, b = 0;
};

/**
 * A small x/y line chart written as PNG: lines, translucent bands and highlighted x-intervals,
 * axes with ticks and labels, a title and a legend.
 */
class Plot {
public:
    Plot(int width, int height);

    void setTitle(std::string title) { title_ = std::move(title); }
    void setXLabel(std::string label) { xLabel_ = std::move(label); }
    void setYLabel(std::string label) { yLabel_ = std::move(label); }
    /** Fixes the y range (otherwise taken from the data). */
    void setYRange(double lo, double hi);

    /** A polyline; a non-empty label adds a legend entry. */
    void addLine(std::vector<double> x, std::vector<double> y, Rgb color, std::string label = "");
    /** The area between lo(x) and hi(x), blended with the given opacity. */
    void addBand(std::vector<double> x, std::vector<double> lo, std::vector<double> hi, Rgb color,
                 double alpha = 0.25);
    /** Marks [start, end] x-intervals as thick segments along the bottom of the plot area. */
    void addIntervals(std::vector<std::pair<double, double>> intervals, Rgb color,
                      std::string label = "");

    /** Renders and writes the PNG; throws std::runtime_error naming the path on failure. */
    void save(const std::string& path) const;

    int width() const { return width_; }
    int height() const { return height_; }

private:
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
    struct Range {
        double x0, x1, y0, y1;
    };
    Range dataRange() const;

    int width_, height_;
    std::string title_, xLabel_, yLabel_;
    bool fixedY_ = false;
    double yLo_ = 0.0, yHi_ = 1.0;
    std::vector<Line> lines_;
    std::vector<Band> bands_;
    std::vector<Intervals> intervals_;
};

/** A distinct colour for series i (a fixed qualitative palette). */
Rgb seriesColor(std::size_t i);

/** "Nice" tick values covering [lo, hi], about `count` of them. */
std::vector<double> niceTicks(double lo, double hi, int count = 6);

}  // namespace daep::eval
