#include "daep/eval/WorldRender.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

#include "daep/eval/Plot.h"

namespace daep::eval {
namespace {

using world::WorldSpec;
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr int kTitleBand = 40;
constexpr int kLegendBand = 56;
constexpr int kMargin = 16;
const cv::Scalar kBlack(0, 0, 0);
const cv::Scalar kBoxColour(200, 90, 0);
const cv::Scalar kStartColour(0, 0, 220);

/** World xy -> pixel, y up. */
class Projection {
public:
    Projection(double xMin, double yMax, double scale, cv::Point2d origin)
        : xMin_(xMin), yMax_(yMax), scale_(scale), origin_(origin) {}

    cv::Point2d toPx(double x, double y) const {
        return {origin_.x + (x - xMin_) * scale_, origin_.y + (yMax_ - y) * scale_};
    }
    cv::Point toPixel(double x, double y) const {
        const cv::Point2d p = toPx(x, y);
        return {static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y))};
    }
    double scale() const { return scale_; }

private:
    double xMin_, yMax_, scale_;
    cv::Point2d origin_;
};

/** Shade of a footprint by its top height: tall is dark, low is light. */
cv::Scalar heightShade(double top, double zLow, double zHigh) {
    const double t = std::clamp((top - zLow) / std::max(zHigh - zLow, 1e-6), 0.0, 1.0);
    const double v = 200.0 - 150.0 * t;
    return cv::Scalar(v, v * 0.95, v * 0.9);
}

struct Footprint {
    std::vector<cv::Point> hull;
    double top = 0.0;
};

std::vector<cv::Point> hullOf(const std::vector<Eigen::Vector3d>& pts, const Projection& proj) {
    std::vector<cv::Point> px, hull;
    for (const auto& p : pts)
        px.push_back(proj.toPixel(p.x(), p.y()));
    cv::convexHull(px, hull);
    return hull;
}

/** Corners (box) or rim points (cylinder) of a solid in world coordinates. */
std::vector<Eigen::Vector3d> solidPoints(const Eigen::Isometry3d& pose, const Eigen::Vector3d& half,
                                         bool round) {
    std::vector<Eigen::Vector3d> pts;
    const int n = round ? 48 : 4;
    for (int i = 0; i < n; ++i) {
        const double a = 2.0 * M_PI * i / n;
        const double x = round ? half.x() * std::cos(a) : (i == 0 || i == 3 ? -1 : 1) * half.x();
        const double y = round ? half.y() * std::sin(a) : (i < 2 ? -1 : 1) * half.y();
        for (double sz : {-1.0, 1.0})
            pts.push_back(pose * Eigen::Vector3d(x, y, sz * half.z()));
    }
    return pts;
}

double topOf(const std::vector<Eigen::Vector3d>& pts) {
    double top = -std::numeric_limits<double>::infinity();
    for (const auto& p : pts)
        top = std::max(top, p.z());
    return top;
}

std::vector<Footprint> footprints(const WorldSpec& w, const Projection& proj) {
    std::vector<Footprint> out;
    auto add = [&](const std::vector<Eigen::Vector3d>& pts) {
        out.push_back({hullOf(pts, proj), topOf(pts)});
    };
    for (const auto& b : w.boxes)
        if (b.name != "ground")
            add(solidPoints(b.pose, 0.5 * b.size, false));
    for (const auto& c : w.cylinders)
        add(solidPoints(c.pose, Eigen::Vector3d(c.radius, c.radius, 0.5 * c.length), true));
    for (const auto& m : w.meshes)
        for (const auto& t : m.triangles) {
            std::vector<Eigen::Vector3d> pts;
            for (int k = 0; k < 3; ++k)
                pts.push_back(m.vertices[t[k]].cast<double>());
            add(pts);
        }
    for (const auto& map : w.voxelMaps)
        for (const auto& b : map.boxes)
            out.push_back({{proj.toPixel(b.min.x(), b.min.y()), proj.toPixel(b.max.x(), b.min.y()),
                            proj.toPixel(b.max.x(), b.max.y()), proj.toPixel(b.min.x(), b.max.y())},
                           b.max.z()});
    std::sort(out.begin(), out.end(),
              [](const Footprint& a, const Footprint& b) { return a.top < b.top; });
    return out;
}

void drawGeometry(cv::Mat& img, const WorldSpec& w, const Projection& proj) {
    const auto prints = footprints(w, proj);
    if (prints.empty())
        return;
    const double zLow = std::min(0.0, prints.front().top);
    const double zHigh = std::max(prints.back().top, zLow + 0.5);
    for (const auto& f : prints) {
        const cv::Scalar c = heightShade(f.top, zLow, zHigh);
        if (f.hull.size() >= 3)
            cv::fillConvexPoly(img, f.hull, c, cv::LINE_AA);
        if (f.hull.size() >= 2)  // thin or vertical faces still show as a line
            cv::polylines(img, f.hull, true, c, 1, cv::LINE_AA);
    }
}

std::string metres(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g m", v);
    return buf;
}

void drawGrid(cv::Mat& img, const Projection& proj, const Eigen::Vector2d& lo,
              const Eigen::Vector2d& hi, double step) {
    const cv::Scalar grid(232, 232, 232), axis(200, 200, 200);
    for (double x = std::ceil(lo.x() / step) * step; x <= hi.x(); x += step)
        cv::line(img, proj.toPixel(x, lo.y()), proj.toPixel(x, hi.y()),
                 std::abs(x) < 1e-9 ? axis : grid, 1);
    for (double y = std::ceil(lo.y() / step) * step; y <= hi.y(); y += step)
        cv::line(img, proj.toPixel(lo.x(), y), proj.toPixel(hi.x(), y),
                 std::abs(y) < 1e-9 ? axis : grid, 1);
}

cv::Scalar personColour(size_t i, size_t n) {
    cv::Mat hsv(1, 1, CV_8UC3,
                cv::Scalar(static_cast<double>(i * 170 / std::max<size_t>(n, 1)), 220, 200));
    cv::Mat bgr;
    cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
    const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
    return cv::Scalar(c[0], c[1], c[2]);
}

void drawRoute(cv::Mat& img, const world::PersonRoute& r, const Projection& proj,
               const cv::Scalar& c) {
    const size_t n = r.waypoints.size();
    for (size_t i = 0; i < n; ++i) {
        const cv::Point2d a = proj.toPx(r.waypoints[i].x(), r.waypoints[i].y());
        const cv::Point2d b = proj.toPx(r.waypoints[(i + 1) % n].x(), r.waypoints[(i + 1) % n].y());
        const double len = cv::norm(b - a);
        if (len < 1.0)
            continue;
        cv::line(img, a, b, c, 2, cv::LINE_AA);
        const cv::Point2d mid = 0.5 * (a + b), dir = (b - a) / len;
        const double head = std::min(10.0, 0.4 * len);
        cv::arrowedLine(img, mid - dir * head, mid + dir * head, c, 2, cv::LINE_AA, 0, 0.8);
    }
    const cv::Point2d first = proj.toPx(r.waypoints[0].x(), r.waypoints[0].y());
    cv::circle(img, first, 5, c, cv::FILLED, cv::LINE_AA);
    cv::circle(img, first, 5, kBlack, 1, cv::LINE_AA);
}

void drawStarts(cv::Mat& img, const WorldSpec& w, const Projection& proj) {
    for (size_t i = 0; i < w.starts.size(); ++i) {
        const cv::Point p = proj.toPixel(w.starts[i].x(), w.starts[i].y());
        cv::circle(img, p, 10, cv::Scalar(255, 255, 255), cv::FILLED, cv::LINE_AA);
        cv::circle(img, p, 10, kStartColour, 2, cv::LINE_AA);
        const std::string label = std::to_string(i);  // 0-4, as experiment.start
        int base = 0;
        const cv::Size ts = cv::getTextSize(label, kFont, 0.45, 1, &base);
        cv::putText(img, label, p + cv::Point(-ts.width / 2, ts.height / 2), kFont, 0.45,
                    kStartColour, 1, cv::LINE_AA);
    }
}

void drawScaleBar(cv::Mat& img, const Projection& proj, double step) {
    const int y = img.rows - kLegendBand + 18, x0 = kMargin;
    const int len = static_cast<int>(std::lround(step * proj.scale()));
    cv::rectangle(img, {x0, y - 3}, {x0 + len, y + 3}, kBlack, cv::FILLED);
    cv::putText(img, metres(step), {x0 + len + 6, y + 5}, kFont, 0.45, kBlack, 1, cv::LINE_AA);
}

struct LegendEntry {
    cv::Scalar colour;
    std::string text;
    int kind;  ///< 0 filled square, 1 outlined square, 2 circle, 3 arrow
};

constexpr int kLegendSymbol = 24, kLegendGap = 18;

/** The room an entry takes in the row: symbol, text and the gap to the next entry. */
int entryWidth(const LegendEntry& e, double font) {
    int base = 0;
    return kLegendSymbol + cv::getTextSize(e.text, kFont, font, 1, &base).width + kLegendGap;
}

int legendWidth(const std::vector<LegendEntry>& entries, double font) {
    int width = 0;
    for (const auto& e : entries)
        width += entryWidth(e, font);
    return width - kLegendGap;
}

void legendItem(cv::Mat& img, int& x, int y, const LegendEntry& e, double font) {
    if (e.kind == 0)
        cv::rectangle(img, {x, y - 6}, {x + 16, y + 6}, e.colour, cv::FILLED);
    else if (e.kind == 1)
        cv::rectangle(img, {x, y - 6}, {x + 16, y + 6}, e.colour, 2);
    else if (e.kind == 2)
        cv::circle(img, {x + 8, y}, 7, e.colour, 2, cv::LINE_AA);
    else
        cv::arrowedLine(img, {x, y}, {x + 18, y}, e.colour, 2, cv::LINE_AA, 0, 0.4);
    cv::putText(img, e.text, {x + kLegendSymbol, y + 5}, kFont, font, kBlack, 1, cv::LINE_AA);
    x += entryWidth(e, font);
}

/** One row under the map; a smaller font where the image is too narrow for it. */
void drawLegend(cv::Mat& img, const WorldSpec& w) {
    std::vector<LegendEntry> entries{{heightShade(1.0, 0.0, 1.0), "geometry (darker = taller)", 0},
                                     {kBoxColour, "exploration box", 1},
                                     {kStartColour, "starts", 2}};
    if (!w.people.empty())
        entries.push_back(
            {personColour(0, w.people.size()), "people routes (dot = first waypoint)", 3});
    const int available = img.cols - 2 * kMargin;
    double font = 0.42;
    for (int width = legendWidth(entries, font); width > available && font > 0.25;
         width = legendWidth(entries, font))
        font -= 0.02;
    int x = kMargin;
    for (const auto& e : entries)
        legendItem(img, x, img.rows - 16, e, font);
}

void drawTitle(cv::Mat& img, const WorldSpec& w) {
    size_t triangles = 0, boxes = 0, voxelBoxes = 0;
    for (const auto& map : w.voxelMaps)
        voxelBoxes += map.boxes.size();
    for (const auto& m : w.meshes)
        triangles += m.triangles.size();
    for (const auto& b : w.boxes)
        boxes += b.name == "ground" ? 0 : 1;
    char buf[256];
    const auto s = w.explorationBox.size();
    std::snprintf(buf, sizeof buf,
                  "%s - box %.1f x %.1f x %.1f m, %zu boxes, %zu cylinders, %zu meshes (%zu "
                  "triangles), %zu people",
                  w.name.c_str(), s.x(), s.y(), s.z(), boxes, w.cylinders.size(), w.meshes.size(),
                  triangles, w.people.size());
    std::string title = buf;
    if (voxelBoxes > 0)
        title += ", " + std::to_string(voxelBoxes) + " voxel-map boxes";
    double font = 0.55;
    int base = 0;
    while (font > 0.3 &&
           cv::getTextSize(title, kFont, font, 1, &base).width > img.cols - 2 * kMargin)
        font -= 0.05;
    cv::putText(img, title, {kMargin, 26}, kFont, font, kBlack, 1, cv::LINE_AA);
}

/** xy extent of the box, starts, routes and geometry (without the ground slab). */
void extentOf(const WorldSpec& w, Eigen::Vector2d& lo, Eigen::Vector2d& hi) {
    lo = w.explorationBox.min.head<2>();
    hi = w.explorationBox.max.head<2>();
    auto grow = [&](double x, double y) {
        lo = lo.cwiseMin(Eigen::Vector2d(x, y));
        hi = hi.cwiseMax(Eigen::Vector2d(x, y));
    };
    for (const auto& s : w.starts)
        grow(s.x(), s.y());
    for (const auto& p : w.people)
        for (const auto& q : p.waypoints)
            grow(q.x(), q.y());
    for (const auto& b : w.boxes)
        if (b.name != "ground")
            for (const auto& p : solidPoints(b.pose, 0.5 * b.size, false))
                grow(p.x(), p.y());
    for (const auto& c : w.cylinders)
        for (const auto& p : solidPoints(c.pose, Eigen::Vector3d(c.radius, c.radius, 0), true))
            grow(p.x(), p.y());
    for (const auto& m : w.meshes)
        for (const auto& v : m.vertices)
            grow(v.x(), v.y());
    for (const auto& map : w.voxelMaps)
        for (const auto& b : map.boxes) {
            grow(b.min.x(), b.min.y());
            grow(b.max.x(), b.max.y());
        }
    const Eigen::Vector2d pad = Eigen::Vector2d::Constant(0.03 * (hi - lo).maxCoeff() + 0.5);
    lo -= pad;
    hi += pad;
}

}  // namespace

void renderWorldPng(const WorldSpec& w, const std::string& pngPath, int size) {
    if (size < 200)
        throw std::runtime_error("image size must be at least 200 px");
    Eigen::Vector2d lo, hi;
    extentOf(w, lo, hi);
    const double availW = size - 2.0 * kMargin, availH = size - kTitleBand - kLegendBand;
    const double scale = std::min(availW / (hi.x() - lo.x()), availH / (hi.y() - lo.y()));
    const cv::Point2d origin(kMargin + 0.5 * (availW - scale * (hi.x() - lo.x())),
                             kTitleBand + 0.5 * (availH - scale * (hi.y() - lo.y())));
    const Projection proj(lo.x(), hi.y(), scale, origin);

    cv::Mat img(size, size, CV_8UC3, cv::Scalar(255, 255, 255));
    const double step = niceStep((hi - lo).maxCoeff() / 10.0);  // about ten grid lines
    drawGrid(img, proj, lo, hi, step);
    drawGeometry(img, w, proj);
    const auto& b = w.explorationBox;
    cv::rectangle(img, proj.toPixel(b.min.x(), b.max.y()), proj.toPixel(b.max.x(), b.min.y()),
                  kBoxColour, 2, cv::LINE_AA);
    for (size_t i = 0; i < w.people.size(); ++i)
        drawRoute(img, w.people[i], proj, personColour(i, w.people.size()));
    drawStarts(img, w, proj);
    drawTitle(img, w);
    drawScaleBar(img, proj, step);
    drawLegend(img, w);
    if (!cv::imwrite(pngPath, img))
        throw std::runtime_error(pngPath + ": cannot write PNG");
}

}  // namespace daep::eval
