#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <set>

#include "daep/eval/Plot.h"

namespace fs = std::filesystem;
using namespace daep::eval;

namespace {

fs::path scratch(const std::string& name) {
    return fs::temp_directory_path() / ("daep_plot_" + std::to_string(::getpid()) + "_" + name);
}

std::string readFile(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
        ++n;
    return n;
}

Plot samplePlot() {
    Plot plot(640, 400);
    plot.setTitle("Coverage & <test>");
    plot.setSubtitle("bands: min–max");
    plot.setXLabel("time [s]");
    plot.setYLabel("coverage [%]");
    plot.setYRange(0, 100);
    plot.addBand({0, 10, 20}, {0, 10, 20}, {40, 60, 80}, {255, 0, 0}, 0.3);
    plot.addLine({0, 10, 20}, {20, 35, 50}, {0, 0, 255}, "mean");
    plot.addIntervals({{5, 7}}, {255, 140, 0}, "collision ongoing");
    return plot;
}

}  // namespace

TEST(Plot, WritesPngOfTheRequestedSizeWithLineAndBlendedBand) {
    const auto path =
        fs::temp_directory_path() / ("daep_plot_" + std::to_string(::getpid()) + ".png");
    Plot plot(640, 400);
    plot.setTitle("test");
    plot.setXLabel("time [s]");
    plot.setYLabel("coverage [%]");
    plot.setYRange(0, 100);
    plot.addBand({0, 10, 20}, {0, 10, 20}, {40, 60, 80}, {255, 0, 0}, 0.3);
    plot.addLine({0, 10, 20}, {20, 35, 50}, {0, 0, 255}, "mean");
    plot.save(path.string());

    const cv::Mat img = cv::imread(path.string());
    ASSERT_FALSE(img.empty());
    EXPECT_EQ(img.cols, 640);
    EXPECT_EQ(img.rows, 400);
    cv::Mat blue, band;
    cv::inRange(img, cv::Scalar(200, 0, 0), cv::Scalar(255, 40, 40), blue);
    EXPECT_GT(cv::countNonZero(blue), 200);  // the line
    // The band is red blended with white at 30 %: (B, G, R) about (178, 178, 255).
    cv::inRange(img, cv::Scalar(160, 160, 240), cv::Scalar(195, 195, 255), band);
    EXPECT_GT(cv::countNonZero(band), 2000);
    fs::remove(path);
}

TEST(Plot, NiceTicksCoverTheRangeWithRoundSteps) {
    EXPECT_EQ(niceTicks(0, 100), (std::vector<double>{0, 20, 40, 60, 80, 100}));
    const auto t = niceTicks(0, 1187);
    EXPECT_DOUBLE_EQ(t.front(), 0.0);
    EXPECT_GE(t.back(), 1187.0);
    EXPECT_DOUBLE_EQ(t[1] - t[0], 250.0);  // 1187 / 5 = 237 rounds up to 250
    EXPECT_DOUBLE_EQ(t.back(), 1250.0);
    EXPECT_THROW(Plot(10, 10), std::invalid_argument);
}

TEST(Plot, SvgIsWellFormedWithItsSizeAndTheLabelsAsText) {
    const auto path = scratch("a.svg");
    samplePlot().save(path.string());
    const std::string svg = readFile(path);
    EXPECT_EQ(svg.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg ", 0), 0u);
    EXPECT_NE(svg.find("width=\"640\" height=\"400\" viewBox=\"0 0 640 400\""), std::string::npos);
    EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
    EXPECT_EQ(count(svg, "<g "), count(svg, "</g>"));
    EXPECT_EQ(count(svg, "<text "), count(svg, "</text>"));
    for (const char* label : {">Coverage &amp; &lt;test&gt;</text>", ">time [s]</text>",
                              ">coverage [%]</text>", ">mean</text>", ">collision ongoing</text>",
                              ">bands: min\u2013max</text>", ">100</text>"})
        EXPECT_NE(svg.find(label), std::string::npos) << label;
    EXPECT_NE(svg.find("font-family=\"DejaVu Sans"), std::string::npos);
    EXPECT_NE(svg.find("stroke=\"#0000ff\""), std::string::npos);                     // the line
    EXPECT_NE(svg.find("fill=\"#ff0000\" fill-opacity=\"0.3\""), std::string::npos);  // band
    fs::remove(path);
}

TEST(Plot, PdfHasThePageSizeAndEmbedsTheDejaVuFont) {
    const auto path = scratch("a.pdf");
    samplePlot().save(path.string());
    const std::string pdf = readFile(path);
    EXPECT_EQ(pdf.rfind("%PDF-1.", 0), 0u);
    EXPECT_NE(pdf.find("%%EOF", pdf.size() - 8), std::string::npos);
    EXPECT_NE(pdf.find("/MediaBox [ 0 0 640 400 ]"), std::string::npos);
    // Text is set in a real font, embedded: fontconfig found DejaVu (fonts-dejavu-core).
    EXPECT_NE(pdf.find("DejaVuSans"), std::string::npos);
    fs::remove(path);
}

TEST(Plot, SaveAsWritesEachFormatAndRejectsOthers) {
    const auto stem = scratch("multi");
    const auto written = samplePlot().saveAs(stem.string());
    ASSERT_EQ(written.size(), 3u);
    for (const auto& p : written)
        EXPECT_GT(fs::file_size(p), 1000u) << p;
    EXPECT_EQ(readFile(stem.string() + ".png").substr(1, 3), "PNG");
    EXPECT_THROW(samplePlot().save(stem.string() + ".jpg"), std::invalid_argument);
    EXPECT_THROW(samplePlot().save("/proc/daep_no_such_dir/x.png"), std::runtime_error);
    for (const auto& p : written)
        fs::remove(p);
}

TEST(Plot, TimelineRowsAreLabelledAndDrawnAsBars) {
    Plot plot(600, 220);
    plot.setTitle("Collision episodes");
    plot.setXRange(0, 100);
    plot.addTimelineRow("DAEP s0 r0: 1", {{20, 40}}, {0, 160, 0});
    plot.addTimelineRow("AEP s0 r0: 0", {}, {0, 0, 200});
    plot.addTimelineSpans({{60, 70}}, {30, 30, 30});
    plot.addLegendEntry("static geometry", {30, 30, 30});
    EXPECT_THROW(Plot(600, 200).addTimelineSpans({{1, 2}}, {}), std::logic_error);
    const auto svg = scratch("timeline.svg"), png = scratch("timeline.png");
    plot.save(svg.string());
    plot.save(png.string());
    const std::string text = readFile(svg);
    for (const char* label : {">DAEP s0 r0: 1</text>", ">AEP s0 r0: 0</text>",
                              ">static geometry</text>", ">Collision episodes</text>"})
        EXPECT_NE(text.find(label), std::string::npos) << label;
    const cv::Mat img = cv::imread(png.string());
    ASSERT_EQ(img.cols, 600);
    cv::Mat green, dark;
    cv::inRange(img, cv::Scalar(0, 150, 0), cv::Scalar(10, 170, 10), green);
    cv::inRange(img, cv::Scalar(25, 25, 25), cv::Scalar(35, 35, 35), dark);
    const cv::Rect lower(0, 110, 600, 110);
    EXPECT_GT(cv::countNonZero(green), 500);        // 20 s of 100 s in a ~500 px wide area
    EXPECT_GT(cv::countNonZero(dark(lower)), 200);  // the static span on the second row
    fs::remove(svg);
    fs::remove(png);
}

TEST(Figure, StacksPanelsUnderItsTitleWithAlignedPlotAreas) {
    Figure figure("maze (dynamic)");
    figure.addPanel(samplePlot());
    Plot timeline(640, 180);
    timeline.addTimelineRow("a rather long row label: 12", {{2, 3}}, {0, 0, 0});
    figure.addPanel(timeline);
    EXPECT_EQ(figure.width(), 640);
    EXPECT_EQ(figure.height(), 34 + 400 + 180);
    const auto stem = scratch("figure");
    const auto written = figure.saveAs(stem.string(), {"svg", "png"});
    const std::string svg = readFile(written[0]);
    EXPECT_NE(svg.find(">maze (dynamic)</text>"), std::string::npos);
    EXPECT_NE(svg.find(">a rather long row label: 12</text>"), std::string::npos);
    // One left edge for both plot areas: the frames are <rect x=... fill="none" stroke="#000000">.
    std::set<std::string> frameX;
    for (auto at = svg.find("fill=\"none\" stroke=\"#000000\""); at != std::string::npos;
         at = svg.find("fill=\"none\" stroke=\"#000000\"", at + 1)) {
        const auto rect = svg.rfind("<rect x=\"", at);
        frameX.insert(svg.substr(rect + 9, svg.find('"', rect + 9) - rect - 9));
    }
    EXPECT_EQ(frameX.size(), 1u);
    const cv::Mat img = cv::imread(written[1]);
    EXPECT_EQ(img.cols, 640);
    EXPECT_EQ(img.rows, 614);
    for (const auto& p : written)
        fs::remove(p);
}
