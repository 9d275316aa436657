#include "daep/eval/Plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "Canvas.h"

namespace daep::eval {

namespace detail {

/** Maps data coordinates into the plot area (page units, y down). */
struct Frame {
    double left, top, width, height;
    double x0, x1, y0, y1;

    Pt at(double x, double y) const {
        return {left + (x - x0) / (x1 - x0) * width, top + height - (y - y0) / (y1 - y0) * height};
    }
    double xAt(double x) const { return at(x, y0).x; }
    double bottom() const { return top + height; }
    double right() const { return left + width; }
};

}  // namespace detail

namespace {

using detail::Anchor;
using detail::Canvas;
using detail::Frame;
using detail::Pt;
using detail::TextStyle;

constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kDarkGrey{70, 70, 70};
constexpr Rgb kGrid{225, 225, 225};
constexpr double kTickFont = 11.0;
constexpr double kLabelFont = 13.0;
constexpr double kTitleFont = 15.0;
constexpr double kSubtitleFont = 11.5;
constexpr double kLegendFont = 12.0;
constexpr double kRightMargin = 20.0;
constexpr double kBottomMargin = 50.0;

std::string tickText(double v, double step) {
    char buf[32];
    const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step)));
    std::snprintf(buf, sizeof buf, "%.*f", decimals, std::abs(v) < 1e-12 ? 0.0 : v);
    return buf;
}

TextStyle style(double size, Anchor anchor = Anchor::Start, Rgb color = kBlack) {
    TextStyle s;
    s.size = size;
    s.anchor = anchor;
    s.color = color;
    return s;
}

double titleBand(const std::string& title, const std::string& subtitle) {
    return (title.empty() ? 14.0 : 36.0) + (subtitle.empty() ? 0.0 : 16.0);
}

void drawXAxis(Canvas& c, const Frame& f, const std::vector<double>& ticks) {
    for (double t : ticks) {
        const double x = f.xAt(t);
        c.polyline({{x, f.top}, {x, f.bottom()}}, kGrid, 1.0);
        c.text(tickText(t, ticks[1] - ticks[0]), x, f.bottom() + 15,
               style(kTickFont, Anchor::Middle, kDarkGrey));
    }
}

void drawYAxis(Canvas& c, const Frame& f, const std::vector<double>& ticks) {
    for (double t : ticks) {
        const double y = f.at(f.x0, t).y;
        c.polyline({{f.left, y}, {f.right(), y}}, kGrid, 1.0);
        c.text(tickText(t, ticks[1] - ticks[0]), f.left - 6, y + 4,
               style(kTickFont, Anchor::End, kDarkGrey));
    }
}

/** Saves one drawing once per extension under one stem; returns the paths written. */
template <class Drawing>
std::vector<std::string> saveEach(const Drawing& drawing, const std::string& stem,
                                  const std::vector<std::string>& extensions) {
    std::vector<std::string> written;
    for (const auto& ext : extensions) {
        drawing.save(stem + "." + ext);
        written.push_back(stem + "." + ext);
    }
    return written;
}

}  // namespace

Plot::Plot(int width, int height) : width_(width), height_(height) {
    if (width < 200 || height < 150)
        throw std::invalid_argument("Plot: image too small (at least 200 x 150)");
}

void Plot::setYRange(double lo, double hi) {
    fixedY_ = true;
    yLo_ = lo;
    yHi_ = hi;
}

void Plot::setXRange(double lo, double hi) {
    fixedX_ = true;
    xLo_ = lo;
    xHi_ = hi;
}

void Plot::addLine(std::vector<double> x, std::vector<double> y, Rgb color, std::string label) {
    lines_.push_back({std::move(x), std::move(y), color, std::move(label)});
}

void Plot::addBand(std::vector<double> x, std::vector<double> lo, std::vector<double> hi, Rgb color,
                   double alpha) {
    bands_.push_back({std::move(x), std::move(lo), std::move(hi), color, alpha});
}

void Plot::addIntervals(std::vector<std::pair<double, double>> intervals, Rgb color,
                        std::string label) {
    intervals_.push_back({std::move(intervals), color, std::move(label)});
}

void Plot::addTimelineRow(std::string label, std::vector<std::pair<double, double>> spans,
                          Rgb color) {
    rows_.push_back({std::move(label), {{std::move(spans), color, ""}}});
}

void Plot::addTimelineSpans(std::vector<std::pair<double, double>> spans, Rgb color) {
    if (rows_.empty())
        throw std::logic_error("Plot::addTimelineSpans: no timeline row yet");
    rows_.back().layers.push_back({std::move(spans), color, ""});
}

void Plot::addLegendEntry(std::string label, Rgb color) {
    legendEntries_.emplace_back(std::move(label), color);
}

Plot::Range Plot::dataRange() const {
    constexpr double inf = std::numeric_limits<double>::infinity();
    Range r{inf, -inf, inf, -inf};
    auto addX = [&r](double x) { r.x0 = std::min(r.x0, x), r.x1 = std::max(r.x1, x); };
    auto addY = [&r](double y) { r.y0 = std::min(r.y0, y), r.y1 = std::max(r.y1, y); };
    for (const auto& l : lines_) {
        std::for_each(l.x.begin(), l.x.end(), addX);
        std::for_each(l.y.begin(), l.y.end(), addY);
    }
    for (const auto& b : bands_) {
        std::for_each(b.x.begin(), b.x.end(), addX);
        std::for_each(b.lo.begin(), b.lo.end(), addY);
        std::for_each(b.hi.begin(), b.hi.end(), addY);
    }
    auto addSpans = [&addX](const Intervals& iv) {
        for (const auto& [a, b] : iv.spans)
            addX(a), addX(b);
    };
    std::for_each(intervals_.begin(), intervals_.end(), addSpans);
    for (const auto& row : rows_)
        std::for_each(row.layers.begin(), row.layers.end(), addSpans);
    if (fixedX_)
        r.x0 = xLo_, r.x1 = xHi_;
    if (!(r.x0 < r.x1))
        r.x0 = std::isfinite(r.x0) ? r.x0 - 1.0 : 0.0, r.x1 = r.x0 + 2.0;
    if (fixedY_)
        r.y0 = yLo_, r.y1 = yHi_;
    if (!(r.y0 < r.y1))
        r.y0 = std::isfinite(r.y0) ? r.y0 - 1.0 : 0.0, r.y1 = r.y0 + 2.0;
    return r;
}

double Plot::leftMargin(const Canvas& canvas) const {
    const double yLabelBand = yLabel_.empty() ? 8.0 : 30.0;
    double widest = 0.0;
    if (isTimeline()) {
        for (const auto& row : rows_)
            widest = std::max(widest, canvas.textWidth(row.label, kTickFont));
    } else {
        const Range range = dataRange();
        const auto ticks = niceTicks(range.y0, range.y1);
        for (double t : ticks)
            widest =
                std::max(widest, canvas.textWidth(tickText(t, ticks[1] - ticks[0]), kTickFont));
    }
    return std::max(70.0, yLabelBand + widest + 10.0);
}

void Plot::draw(Canvas& c, double top, double left) const {
    const Range range = dataRange();
    const auto xTicks = niceTicks(range.x0, range.x1);
    const auto yTicks = niceTicks(range.y0, range.y1);
    const double areaTop = top + titleBand(title_, subtitle_);
    // Axis limits snap to the outer ticks so the grid ends at the frame.
    const Frame f{left,
                  areaTop,
                  width_ - left - kRightMargin,
                  top + height_ - kBottomMargin - areaTop,
                  xTicks.front(),
                  xTicks.back(),
                  yTicks.front(),
                  yTicks.back()};

    drawXAxis(c, f, xTicks);
    if (isTimeline())
        drawTimeline(c, f);
    else {
        drawYAxis(c, f, yTicks);
        drawSeries(c, f);
    }
    c.strokeRect(f.left, f.top, f.width, f.height, kBlack, 1.0);

    TextStyle titleStyle = style(kTitleFont, Anchor::Middle);
    titleStyle.bold = true;
    c.text(title_, width_ / 2.0, top + 24, titleStyle);
    if (!subtitle_.empty())
        c.text(subtitle_, width_ / 2.0, top + (title_.empty() ? 24 : 42),
               style(kSubtitleFont, Anchor::Middle, kDarkGrey));
    c.text(xLabel_, f.left + f.width / 2, top + height_ - 12, style(kLabelFont, Anchor::Middle));
    if (!yLabel_.empty()) {
        TextStyle vertical = style(kLabelFont, Anchor::Middle);
        vertical.vertical = true;
        c.text(yLabel_, 20, f.top + f.height / 2, vertical);
    }
    drawLegend(c, f);
}

void Plot::drawSeries(Canvas& c, const Frame& f) const {
    c.beginClip(f.left, f.top, f.width, f.height);
    for (const auto& b : bands_) {
        std::vector<Pt> poly;
        const std::size_t n = std::min({b.x.size(), b.lo.size(), b.hi.size()});
        for (std::size_t i = 0; i < n; ++i)
            poly.push_back(f.at(b.x[i], b.hi[i]));
        for (std::size_t i = n; i-- > 0;)
            poly.push_back(f.at(b.x[i], b.lo[i]));
        c.fillPolygon(poly, b.color, b.alpha);
    }
    // Intervals: a faint full-height shade plus a solid strip along the bottom.
    const double stripY = f.bottom() - 4;
    for (const auto& iv : intervals_)
        for (const auto& [a, b] : iv.spans) {
            const double xa = f.xAt(a), w = std::max(f.xAt(b) - xa, 2.0);
            c.fillRect(xa, f.top, w, stripY - f.top, iv.color, 0.18);
            c.fillRect(xa, stripY - 3, w, 6, iv.color);
        }
    for (const auto& l : lines_) {
        std::vector<Pt> pts;
        for (std::size_t i = 0; i < std::min(l.x.size(), l.y.size()); ++i)
            pts.push_back(f.at(l.x[i], l.y[i]));
        c.polyline(pts, l.color, 2.0);
    }
    c.endClip();
}

void Plot::drawTimeline(Canvas& c, const Frame& f) const {
    const double rowHeight = f.height / rows_.size();
    const double barHeight = std::min(0.6 * rowHeight, 14.0);
    const double font = std::min(kTickFont, 0.85 * rowHeight);
    for (std::size_t i = 0; i < rows_.size(); ++i) {
        const double centre = f.top + (i + 0.5) * rowHeight;
        if (i % 2 == 1)
            c.fillRect(f.left, f.top + i * rowHeight, f.width, rowHeight, {244, 244, 246});
        c.text(rows_[i].label, f.left - 6, centre + 0.35 * font,
               style(font, Anchor::End, kDarkGrey));
    }
    c.beginClip(f.left, f.top, f.width, f.height);
    for (std::size_t i = 0; i < rows_.size(); ++i) {
        const double centre = f.top + (i + 0.5) * rowHeight;
        for (const auto& layer : rows_[i].layers)
            for (const auto& [a, b] : layer.spans) {
                const double xa = f.xAt(a);
                c.fillRect(xa, centre - barHeight / 2, std::max(f.xAt(b) - xa, 2.0), barHeight,
                           layer.color);
            }
    }
    c.endClip();
}

void Plot::drawLegend(Canvas& c, const Frame& f) const {
    struct Entry {
        std::string text;
        Rgb color;
        bool line;
    };
    std::vector<Entry> entries;
    for (const auto& l : lines_)
        if (!l.label.empty() && !isTimeline())
            entries.push_back({l.label, l.color, true});
    for (const auto& iv : intervals_)
        if (!iv.label.empty() && !isTimeline())
            entries.push_back({iv.label, iv.color, false});
    for (const auto& [text, color] : legendEntries_)
        entries.push_back({text, color, false});
    if (entries.empty())
        return;
    double textWidth = 0.0;
    for (const auto& e : entries)
        textWidth = std::max(textWidth, c.textWidth(e.text, kLegendFont));
    const double rowStep = 18.0, w = textWidth + 44.0, h = entries.size() * rowStep + 8.0;
    const bool right =
        legendCorner_ == LegendCorner::TopRight || legendCorner_ == LegendCorner::BottomRight;
    const bool bottom =
        legendCorner_ == LegendCorner::BottomLeft || legendCorner_ == LegendCorner::BottomRight;
    const double x = right ? f.right() - 10 - w : f.left + 10;
    const double y = bottom ? f.bottom() - 14 - h : f.top + 10;
    c.fillRect(x, y, w, h, {255, 255, 255}, 0.88);
    c.strokeRect(x, y, w, h, {190, 190, 190}, 0.8);
    for (std::size_t i = 0; i < entries.size(); ++i) {
        const double rowY = y + 4 + (i + 0.5) * rowStep;
        if (entries[i].line)
            c.polyline({{x + 8, rowY}, {x + 32, rowY}}, entries[i].color, 3.0);
        else
            c.fillRect(x + 14, rowY - 6, 12, 12, entries[i].color);
        c.text(entries[i].text, x + 38, rowY + 4.5, style(kLegendFont));
    }
}

void Plot::save(const std::string& path) const {
    detail::renderToFile(path, width_, height_, [this](Canvas& c) { draw(c, 0.0, leftMargin(c)); });
}

std::vector<std::string> Plot::saveAs(const std::string& stem,
                                      const std::vector<std::string>& extensions) const {
    return saveEach(*this, stem, extensions);
}

int Figure::width() const {
    int w = 200;
    for (const auto& p : panels_)
        w = std::max(w, p.width());
    return w;
}

int Figure::height() const {
    double h = titleHeight();
    for (const auto& p : panels_)
        h += p.height();
    return std::max(150, static_cast<int>(std::ceil(h)));
}

void Figure::save(const std::string& path) const {
    detail::renderToFile(path, width(), height(), [this](Canvas& c) {
        double left = 0.0;
        for (const auto& p : panels_)
            left = std::max(left, p.leftMargin(c));
        TextStyle titleStyle = style(kTitleFont + 1, Anchor::Middle);
        titleStyle.bold = true;
        c.text(title_, width() / 2.0, 24, titleStyle);
        double top = titleHeight();
        for (const auto& p : panels_) {
            p.draw(c, top, left);
            top += p.height();
        }
    });
}

std::vector<std::string> Figure::saveAs(const std::string& stem,
                                        const std::vector<std::string>& extensions) const {
    return saveEach(*this, stem, extensions);
}

Rgb seriesColor(std::size_t i) {
    static const Rgb palette[] = {{31, 119, 180}, {44, 160, 44},  {214, 39, 40},  {148, 103, 189},
                                  {140, 86, 75},  {23, 190, 207}, {188, 189, 34}, {127, 127, 127}};
    return palette[i % (sizeof palette / sizeof palette[0])];
}

double niceStep(double raw) {
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    for (double m : {1.0, 2.0, 2.5, 5.0})
        if (m * magnitude >= raw)
            return m * magnitude;
    return 10.0 * magnitude;
}

std::vector<double> niceTicks(double lo, double hi, int count) {
    if (!(hi > lo))
        hi = lo + 1.0;
    const double step = niceStep((hi - lo) / std::max(1, count - 1));
    const double first = std::floor(lo / step + 1e-9) * step;
    std::vector<double> ticks;
    for (int i = 0; first + i * step < hi + step * (1.0 - 1e-9); ++i)
        ticks.push_back(first + i * step);
    if (ticks.size() < 2)
        ticks.push_back(ticks.back() + step);
    return ticks;
}

}  // namespace daep::eval
