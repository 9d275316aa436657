#include "daep/eval/Plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace daep::eval {

namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kGrid(225, 225, 225);

cv::Scalar bgr(Rgb c) {
    return cv::Scalar(c.b, c.g, c.r);
}

std::string tickText(double v, double step) {
    char buf[32];
    const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step)));
    std::snprintf(buf, sizeof buf, "%.*f", decimals, std::abs(v) < 1e-12 ? 0.0 : v);
    return buf;
}

/** Maps data coordinates into the plot area. */
struct Frame {
    cv::Rect area;
    double x0, x1, y0, y1;

    cv::Point at(double x, double y) const {
        const double fx = (x - x0) / (x1 - x0);
        const double fy = (y - y0) / (y1 - y0);
        return {area.x + static_cast<int>(std::lround(fx * area.width)),
                area.y + area.height - static_cast<int>(std::lround(fy * area.height))};
    }
};

void putCentered(cv::Mat& img, const std::string& text, cv::Point center, double scale,
                 int thickness = 1) {
    int baseline = 0;
    const auto size = cv::getTextSize(text, kFont, scale, thickness, &baseline);
    cv::putText(img, text, {center.x - size.width / 2, center.y + size.height / 2}, kFont, scale,
                kBlack, thickness, cv::LINE_AA);
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
    for (const auto& iv : intervals_)
        for (const auto& [a, b] : iv.spans)
            addX(a), addX(b);
    if (!(r.x0 < r.x1))
        r.x0 = std::isfinite(r.x0) ? r.x0 - 1.0 : 0.0, r.x1 = r.x0 + 2.0;
    if (fixedY_)
        r.y0 = yLo_, r.y1 = yHi_;
    if (!(r.y0 < r.y1))
        r.y0 = std::isfinite(r.y0) ? r.y0 - 1.0 : 0.0, r.y1 = r.y0 + 2.0;
    return r;
}

void Plot::save(const std::string& path) const {
    cv::Mat img(height_, width_, CV_8UC3, cv::Scalar(255, 255, 255));
    const Range range = dataRange();
    const auto xTicks = niceTicks(range.x0, range.x1);
    const auto yTicks = niceTicks(range.y0, range.y1);
    // Axis limits snap to the outer ticks so the grid ends at the frame.
    Frame f{cv::Rect(70, 40, width_ - 70 - 20, height_ - 40 - 55), xTicks.front(), xTicks.back(),
            yTicks.front(), yTicks.back()};

    for (double t : xTicks) {
        cv::line(img, f.at(t, f.y0), f.at(t, f.y1), kGrid, 1);
        putCentered(img, tickText(t, xTicks[1] - xTicks[0]), f.at(t, f.y0) + cv::Point(0, 14),
                    0.42);
    }
    for (double t : yTicks) {
        cv::line(img, f.at(f.x0, t), f.at(f.x1, t), kGrid, 1);
        const std::string text = tickText(t, yTicks[1] - yTicks[0]);
        int baseline = 0;
        const auto size = cv::getTextSize(text, kFont, 0.42, 1, &baseline);
        cv::putText(img, text, f.at(f.x0, t) + cv::Point(-size.width - 6, size.height / 2), kFont,
                    0.42, kBlack, 1, cv::LINE_AA);
    }

    for (const auto& b : bands_) {
        std::vector<cv::Point> poly;
        for (std::size_t i = 0; i < b.x.size(); ++i)
            poly.push_back(f.at(b.x[i], b.hi[i]));
        for (std::size_t i = b.x.size(); i-- > 0;)
            poly.push_back(f.at(b.x[i], b.lo[i]));
        if (poly.size() < 3)
            continue;
        cv::Mat overlay = img.clone();
        cv::fillPoly(overlay, std::vector<std::vector<cv::Point>>{poly}, bgr(b.color), cv::LINE_AA);
        cv::addWeighted(overlay, b.alpha, img, 1.0 - b.alpha, 0.0, img);
    }
    // Intervals: a faint full-height shade plus a solid strip along the bottom.
    const int stripY = f.area.y + f.area.height - 4;
    for (const auto& iv : intervals_) {
        cv::Mat overlay = img.clone();
        for (const auto& [a, b] : iv.spans)
            cv::rectangle(overlay, {f.at(a, f.y0).x, f.area.y}, {f.at(b, f.y0).x, stripY},
                          bgr(iv.color), cv::FILLED);
        cv::addWeighted(overlay, 0.18, img, 0.82, 0.0, img);
        for (const auto& [a, b] : iv.spans) {
            const int xa = f.at(a, f.y0).x;
            cv::rectangle(img, {xa, stripY - 3}, {std::max(f.at(b, f.y0).x, xa + 2), stripY + 3},
                          bgr(iv.color), cv::FILLED);
        }
    }
    for (const auto& l : lines_) {
        std::vector<cv::Point> pts;
        for (std::size_t i = 0; i < std::min(l.x.size(), l.y.size()); ++i)
            pts.push_back(f.at(l.x[i], l.y[i]));
        cv::polylines(img, pts, false, bgr(l.color), 2, cv::LINE_AA);
    }
    cv::rectangle(img, f.area, kBlack, 1);

    putCentered(img, title_, {width_ / 2, 20}, 0.6, 1);
    putCentered(img, xLabel_, {f.area.x + f.area.width / 2, height_ - 18}, 0.5);
    if (!yLabel_.empty()) {
        int baseline = 0;
        const auto size = cv::getTextSize(yLabel_, kFont, 0.5, 1, &baseline);
        cv::Mat label(size.height + baseline + 4, size.width + 4, CV_8UC3, cv::Scalar::all(255));
        cv::putText(label, yLabel_, {2, size.height + 1}, kFont, 0.5, kBlack, 1, cv::LINE_AA);
        cv::rotate(label, label, cv::ROTATE_90_COUNTERCLOCKWISE);
        const int x = 4, y = f.area.y + (f.area.height - label.rows) / 2;
        if (y >= 0 && label.rows <= height_)
            label.copyTo(img(cv::Rect(x, std::max(0, y), label.cols, label.rows)));
    }

    // Legend: top-left inside the plot area.
    cv::Point row(f.area.x + 10, f.area.y + 16);
    auto legend = [&](const std::string& text, Rgb color) {
        cv::line(img, row + cv::Point(0, -4), row + cv::Point(22, -4), bgr(color), 4);
        cv::putText(img, text, row + cv::Point(28, 0), kFont, 0.45, kBlack, 1, cv::LINE_AA);
        row.y += 18;
    };
    for (const auto& l : lines_)
        if (!l.label.empty())
            legend(l.label, l.color);
    for (const auto& iv : intervals_)
        if (!iv.label.empty())
            legend(iv.label, iv.color);

    const auto parent = std::filesystem::path(path).parent_path();
    if (!parent.empty())
        std::filesystem::create_directories(parent);
    if (!cv::imwrite(path, img))
        throw std::runtime_error("cannot write plot " + path);
}

Rgb seriesColor(std::size_t i) {
    static const Rgb palette[] = {{31, 119, 180}, {44, 160, 44},  {214, 39, 40},  {148, 103, 189},
                                  {140, 86, 75},  {23, 190, 207}, {188, 189, 34}, {127, 127, 127}};
    return palette[i % (sizeof palette / sizeof palette[0])];
}

std::vector<double> niceTicks(double lo, double hi, int count) {
    if (!(hi > lo))
        hi = lo + 1.0;
    const double raw = (hi - lo) / std::max(1, count - 1);
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    double step = magnitude;
    for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
        if (m * magnitude >= raw) {
            step = m * magnitude;
            break;
        }
    const double first = std::floor(lo / step + 1e-9) * step;
    std::vector<double> ticks;
    for (int i = 0; first + i * step < hi + step * (1.0 - 1e-9); ++i)
        ticks.push_back(first + i * step);
    if (ticks.size() < 2)
        ticks.push_back(ticks.back() + step);
    return ticks;
}

}  // namespace daep::eval
