#include "Canvas.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace daep::eval::detail {
namespace {

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

void selectFont(cairo_t* cr, double size, bool bold) {
    cairo_select_font_face(cr, kFontFamily, CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

double measure(cairo_t* cr, const std::string& s, double size, bool bold) {
    selectFont(cr, size, bold);
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.c_str(), &e);
    return e.x_advance;
}

double anchorShift(Anchor a, double width) {
    return a == Anchor::Start ? 0.0 : a == Anchor::Middle ? -0.5 * width : -width;
}

/** PNG and PDF: cairo draws and its font machinery (fontconfig, FreeType) sets the text. */
class CairoCanvas final : public Canvas {
public:
    explicit CairoCanvas(cairo_t* cr) : cr_(cr) {}

    void polyline(const std::vector<Pt>& pts, Rgb color, double width) override {
        if (pts.size() < 2)
            return;
        path(pts);
        setColor(color, 1.0);
        cairo_set_line_width(cr_, width);
        cairo_set_line_join(cr_, CAIRO_LINE_JOIN_ROUND);
        cairo_stroke(cr_);
    }
    void fillPolygon(const std::vector<Pt>& pts, Rgb color, double alpha) override {
        if (pts.size() < 3)
            return;
        path(pts);
        cairo_close_path(cr_);
        setColor(color, alpha);
        cairo_fill(cr_);
    }
    void fillRect(double x, double y, double w, double h, Rgb color, double alpha) override {
        cairo_rectangle(cr_, x, y, w, h);
        setColor(color, alpha);
        cairo_fill(cr_);
    }
    void strokeRect(double x, double y, double w, double h, Rgb color, double width) override {
        cairo_rectangle(cr_, x, y, w, h);
        setColor(color, 1.0);
        cairo_set_line_width(cr_, width);
        cairo_stroke(cr_);
    }
    void text(const std::string& s, double x, double y, const TextStyle& style) override {
        const double shift = anchorShift(style.anchor, textWidth(s, style.size, style.bold));
        cairo_save(cr_);
        cairo_translate(cr_, x, y);
        if (style.vertical)
            cairo_rotate(cr_, -M_PI / 2);
        selectFont(cr_, style.size, style.bold);
        setColor(style.color, 1.0);
        cairo_move_to(cr_, shift, 0.0);
        cairo_show_text(cr_, s.c_str());
        cairo_restore(cr_);
    }
    void beginClip(double x, double y, double w, double h) override {
        cairo_save(cr_);
        cairo_rectangle(cr_, x, y, w, h);
        cairo_clip(cr_);
    }
    void endClip() override { cairo_restore(cr_); }
    double textWidth(const std::string& s, double size, bool bold) const override {
        return measure(cr_, s, size, bold);
    }

private:
    void path(const std::vector<Pt>& pts) {
        cairo_new_path(cr_);
        cairo_move_to(cr_, pts[0].x, pts[0].y);
        for (std::size_t i = 1; i < pts.size(); ++i)
            cairo_line_to(cr_, pts[i].x, pts[i].y);
    }
    void setColor(Rgb c, double alpha) {
        cairo_set_source_rgba(cr_, c.r / 255.0, c.g / 255.0, c.b / 255.0, alpha);
    }

    cairo_t* cr_;
};

std::string hex(Rgb c) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", c.r, c.g, c.b);
    return buf;
}

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    std::string s = buf;
    s.erase(s.find_last_not_of('0') + 1);
    if (s.back() == '.')
        s.pop_back();
    return s == "-0" ? "0" : s;
}

std::string xmlEscaped(const std::string& s) {
    std::string out;
    for (char c : s)
        out += c == '&'   ? "&amp;"
               : c == '<' ? "&lt;"
               : c == '>' ? "&gt;"
               : c == '"' ? "&quot;"
                          : std::string(1, c);
    return out;
}

/**
 * SVG with the text as <text> elements (searchable, editable); cairo only measures the text so
 * that the layout matches the PNG and PDF.
 */
class SvgCanvas final : public Canvas {
public:
    SvgCanvas(std::ostream& out, int width, int height)
        : out_(out),
          measureSurface_(cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1),
                          &cairo_surface_destroy),
          measure_(cairo_create(measureSurface_.get()), &cairo_destroy) {
        out_ << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
             << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << width << "\" height=\""
             << height << "\" viewBox=\"0 0 " << width << ' ' << height << "\" font-family=\""
             << kFontFamily << ", sans-serif\">\n";
    }
    void finish() { out_ << "</svg>\n"; }

    void polyline(const std::vector<Pt>& pts, Rgb color, double width) override {
        if (pts.size() < 2)
            return;
        out_ << "<polyline points=\"" << points(pts) << "\" fill=\"none\" stroke=\"" << hex(color)
             << "\" stroke-width=\"" << num(width) << "\" stroke-linejoin=\"round\"/>\n";
    }
    void fillPolygon(const std::vector<Pt>& pts, Rgb color, double alpha) override {
        if (pts.size() < 3)
            return;
        out_ << "<polygon points=\"" << points(pts) << "\" fill=\"" << hex(color)
             << "\" fill-opacity=\"" << num(alpha) << "\"/>\n";
    }
    void fillRect(double x, double y, double w, double h, Rgb color, double alpha) override {
        out_ << "<rect" << box(x, y, w, h) << " fill=\"" << hex(color) << '"';
        if (alpha < 1.0)
            out_ << " fill-opacity=\"" << num(alpha) << '"';
        out_ << "/>\n";
    }
    void strokeRect(double x, double y, double w, double h, Rgb color, double width) override {
        out_ << "<rect" << box(x, y, w, h) << " fill=\"none\" stroke=\"" << hex(color)
             << "\" stroke-width=\"" << num(width) << "\"/>\n";
    }
    void text(const std::string& s, double x, double y, const TextStyle& style) override {
        static const char* anchors[] = {"start", "middle", "end"};
        out_ << "<text x=\"" << num(x) << "\" y=\"" << num(y) << "\" font-size=\""
             << num(style.size) << "\" text-anchor=\"" << anchors[static_cast<int>(style.anchor)]
             << "\" fill=\"" << hex(style.color) << '"';
        if (style.bold)
            out_ << " font-weight=\"bold\"";
        if (style.vertical)
            out_ << " transform=\"rotate(-90 " << num(x) << ' ' << num(y) << ")\"";
        out_ << '>' << xmlEscaped(s) << "</text>\n";
    }
    void beginClip(double x, double y, double w, double h) override {
        const int id = ++clips_;
        out_ << "<clipPath id=\"clip" << id << "\"><rect" << box(x, y, w, h)
             << "/></clipPath>\n<g clip-path=\"url(#clip" << id << ")\">\n";
    }
    void endClip() override { out_ << "</g>\n"; }
    double textWidth(const std::string& s, double size, bool bold) const override {
        return measure(measure_.get(), s, size, bold);
    }

private:
    static std::string points(const std::vector<Pt>& pts) {
        std::string s;
        for (const auto& p : pts)
            s += (s.empty() ? "" : " ") + num(p.x) + ',' + num(p.y);
        return s;
    }
    static std::string box(double x, double y, double w, double h) {
        return " x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(w) + "\" height=\"" +
               num(h) + '"';
    }

    std::ostream& out_;
    SurfacePtr measureSurface_;
    ContextPtr measure_;
    int clips_ = 0;
};

void checkCairo(cairo_status_t status, const std::string& path) {
    if (status != CAIRO_STATUS_SUCCESS)
        throw std::runtime_error("cannot write plot " + path + ": " +
                                 cairo_status_to_string(status));
}

void drawOnSurface(cairo_surface_t* surface, int width, int height, const std::string& path,
                   const std::function<void(Canvas&)>& draw) {
    checkCairo(cairo_surface_status(surface), path);
    ContextPtr cr(cairo_create(surface), &cairo_destroy);
    cairo_set_source_rgb(cr.get(), 1.0, 1.0, 1.0);
    cairo_rectangle(cr.get(), 0, 0, width, height);
    cairo_fill(cr.get());
    CairoCanvas canvas(cr.get());
    draw(canvas);
    checkCairo(cairo_status(cr.get()), path);
}

void writePng(const std::string& path, int width, int height,
              const std::function<void(Canvas&)>& draw) {
    SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height),
                       &cairo_surface_destroy);
    drawOnSurface(surface.get(), width, height, path, draw);
    checkCairo(cairo_surface_write_to_png(surface.get(), path.c_str()), path);
}

void writePdf(const std::string& path, int width, int height,
              const std::function<void(Canvas&)>& draw) {
    SurfacePtr surface(cairo_pdf_surface_create(path.c_str(), width, height),
                       &cairo_surface_destroy);
    drawOnSurface(surface.get(), width, height, path, draw);
    cairo_surface_finish(surface.get());
    checkCairo(cairo_surface_status(surface.get()), path);
}

void writeSvg(const std::string& path, int width, int height,
              const std::function<void(Canvas&)>& draw) {
    std::ostringstream text;
    SvgCanvas canvas(text, width, height);
    canvas.fillRect(0, 0, width, height, {255, 255, 255}, 1.0);
    draw(canvas);
    canvas.finish();
    std::ofstream out(path, std::ios::binary);
    out << text.str();
    if (!out)
        throw std::runtime_error("cannot write plot " + path);
}

}  // namespace

void renderToFile(const std::string& path, int width, int height,
                  const std::function<void(Canvas&)>& draw) {
    const std::filesystem::path file(path);
    const std::string ext = file.extension().string();
    if (ext != ".png" && ext != ".svg" && ext != ".pdf")
        throw std::invalid_argument("plot " + path + ": unknown format (use .png, .svg or .pdf)");
    if (!file.parent_path().empty())
        std::filesystem::create_directories(file.parent_path());
    if (ext == ".png")
        writePng(path, width, height, draw);
    else if (ext == ".pdf")
        writePdf(path, width, height, draw);
    else
        writeSvg(path, width, height, draw);
}

}  // namespace daep::eval::detail
