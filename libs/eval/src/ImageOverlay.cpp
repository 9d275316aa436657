#include "daep/eval/ImageOverlay.h"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "Canvas.h"

namespace daep::eval {
namespace {

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

constexpr double kFont = 13.0;
constexpr double kPad = 8.0;
constexpr double kRow = 19.0;

void setColor(cairo_t* cr, Rgb c, double alpha = 1.0) {
    cairo_set_source_rgba(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0, alpha);
}

void setFont(cairo_t* cr, double size, bool bold = false) {
    cairo_select_font_face(cr, detail::kFontFamily, CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

double textWidth(cairo_t* cr, const std::string& s) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.c_str(), &e);
    return e.x_advance;
}

void showText(cairo_t* cr, const std::string& s, double x, double y, Rgb color = {0, 0, 0}) {
    setColor(cr, color);
    cairo_move_to(cr, x, y);
    cairo_show_text(cr, s.c_str());
}

void panel(cairo_t* cr, double x, double y, double w, double h) {
    cairo_rectangle(cr, x, y, w, h);
    setColor(cr, {255, 255, 255}, 0.88);
    cairo_fill_preserve(cr);
    setColor(cr, {150, 150, 150});
    cairo_set_line_width(cr, 1.0);
    cairo_stroke(cr);
}

void swatch(cairo_t* cr, const LegendSwatch& s, double x, double y) {
    setColor(cr, s.color);
    if (s.shape == LegendSwatch::Shape::Box) {
        cairo_rectangle(cr, x + 4, y - 6, 14, 12);
        cairo_fill_preserve(cr);
        setColor(cr, {90, 90, 90});  // white or pale swatches stay visible on the white panel
        cairo_set_line_width(cr, 0.8);
        cairo_stroke(cr);
        return;
    }
    cairo_set_line_width(cr, s.shape == LegendSwatch::Shape::Line ? 3.5 : 1.2);
    cairo_move_to(cr, x, y);
    cairo_line_to(cr, x + 22, y);
    cairo_stroke(cr);
}

void colorBar(cairo_t* cr, const ColorBar& bar, double x, double y, double w) {
    showText(cr, bar.label, x, y + 4);
    const double barY = y + 10, barW = w - 2 * kPad;
    auto gradient = cairo_pattern_create_linear(x, 0, x + barW, 0);
    for (std::size_t i = 0; i < bar.stops.size(); ++i) {
        const Rgb c = bar.stops[i];
        cairo_pattern_add_color_stop_rgb(gradient,
                                         double(i) / std::max<std::size_t>(1, bar.stops.size() - 1),
                                         c.r / 255.0, c.g / 255.0, c.b / 255.0);
    }
    cairo_rectangle(cr, x, barY, barW, 12);
    cairo_set_source(cr, gradient);
    cairo_fill(cr);
    cairo_pattern_destroy(gradient);
    setFont(cr, kFont - 2);
    showText(cr, bar.lowText, x, barY + 26, {60, 60, 60});
    showText(cr, bar.highText, x + barW - textWidth(cr, bar.highText), barY + 26, {60, 60, 60});
    setFont(cr, kFont);
}

void drawLegend(cairo_t* cr, const Overlay& o) {
    setFont(cr, kFont);
    double w = o.colorBar.stops.empty() ? 0.0 : 200.0;
    for (const auto& s : o.legend)
        w = std::max(w, 30 + textWidth(cr, s.label));
    setFont(cr, kFont + 1, true);
    w = std::max(w, textWidth(cr, o.title)) + 2 * kPad;
    setFont(cr, kFont);
    const double barH = o.colorBar.stops.empty() ? 0.0 : 44.0;
    const double titleH = o.title.empty() ? 0.0 : kRow + 2;
    const double h = titleH + kRow * o.legend.size() + barH + kPad;
    const double x = 10, y = 10;
    panel(cr, x, y, w, h);
    double row = y + kPad + 6;
    if (!o.title.empty()) {
        setFont(cr, kFont + 1, true);
        showText(cr, o.title, x + kPad, row + 5);
        setFont(cr, kFont);
        row += titleH;
    }
    for (const auto& s : o.legend) {
        swatch(cr, s, x + kPad, row);
        showText(cr, s.label, x + kPad + 30, row + 4.5);
        row += kRow;
    }
    if (!o.colorBar.stops.empty())
        colorBar(cr, o.colorBar, x + kPad, row, w);
}

void drawScaleBar(cairo_t* cr, double metresPerPixel, double width, double height) {
    const double metres = scaleBarLength(0.2 * width * metresPerPixel);
    const double len = metres / metresPerPixel;
    char text[32];
    std::snprintf(text, sizeof text, metres >= 1.0 ? "%.0f m" : "%.1f m", metres);
    setFont(cr, kFont);
    const double w = len + 2 * kPad + 8 + textWidth(cr, text), h = 30;
    const double x = 10, y = height - 10 - h;
    panel(cr, x, y, w, h);
    const double barX = x + kPad, barY = y + h / 2 - 4;
    for (int i = 0; i < 4; ++i) {  // alternating quarters, like a map's scale bar
        cairo_rectangle(cr, barX + i * len / 4, barY, len / 4, 8);
        setColor(cr, i % 2 ? Rgb{255, 255, 255} : Rgb{0, 0, 0});
        cairo_fill(cr);
    }
    cairo_rectangle(cr, barX, barY, len, 8);
    setColor(cr, {0, 0, 0});
    cairo_set_line_width(cr, 1.0);
    cairo_stroke(cr);
    showText(cr, text, barX + len + 8, barY + 8);
}

}  // namespace

double scaleBarLength(double target) {
    if (!(target > 0.0))
        return 1.0;
    const double p = std::pow(10.0, std::floor(std::log10(target)));
    double best = p;
    for (double m : {1.0, 2.0, 5.0, 10.0})
        if (m * p <= target * 1.3)
            best = m * p;
    return best;
}

void writeAnnotatedPng(const unsigned char* bgr, int width, int height, std::size_t stride,
                       const Overlay& overlay, const std::string& path) {
    SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height),
                       &cairo_surface_destroy);
    if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
        throw std::runtime_error("cannot write " + path + ": no image surface");
    cairo_surface_flush(surface.get());
    unsigned char* data = cairo_image_surface_get_data(surface.get());
    const int outStride = cairo_image_surface_get_stride(surface.get());
    for (int y = 0; y < height; ++y) {
        const unsigned char* in = bgr + y * stride;
        auto* out = reinterpret_cast<std::uint32_t*>(data + y * outStride);
        for (int x = 0; x < width; ++x, in += 3)
            out[x] = std::uint32_t(in[2]) << 16 | std::uint32_t(in[1]) << 8 | in[0];
    }
    cairo_surface_mark_dirty(surface.get());
    ContextPtr cr(cairo_create(surface.get()), &cairo_destroy);
    // Laid out for about 1280 x 960; smaller or larger images scale the overlay with them.
    const double scale = std::clamp(std::min(width / 1280.0, height / 960.0), 0.5, 2.0);
    cairo_scale(cr.get(), scale, scale);
    if (!overlay.legend.empty() || !overlay.title.empty() || !overlay.colorBar.stops.empty())
        drawLegend(cr.get(), overlay);
    if (overlay.metresPerPixel > 0.0)
        drawScaleBar(cr.get(), overlay.metresPerPixel * scale, width / scale, height / scale);
    cairo_surface_flush(surface.get());
    const cairo_status_t status = cairo_surface_write_to_png(surface.get(), path.c_str());
    if (status != CAIRO_STATUS_SUCCESS)
        throw std::runtime_error("cannot write " + path + ": " + cairo_status_to_string(status));
}

}  // namespace daep::eval
