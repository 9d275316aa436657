#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "daep/eval/Plot.h"

namespace fs = std::filesystem;
using namespace daep::eval;

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
