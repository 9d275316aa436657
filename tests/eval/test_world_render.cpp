// The top-down world figure (daep-world render): what it must show, and its errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

#include "daep/eval/Plot.h"
#include "daep/eval/WorldRender.h"

namespace {

namespace fs = std::filesystem;
using daep::world::WorldSpec;

/** A 10 x 6 m room: one 2 x 1 m block, two starts, one person walking a square. */
WorldSpec smallRoom() {
    WorldSpec w;
    w.name = "room";
    w.explorationBox.min = Eigen::Vector3d(0, 0, 0);
    w.explorationBox.max = Eigen::Vector3d(10, 6, 2.5);
    daep::world::BoxShape block;
    block.name = "block";
    block.pose.translation() = Eigen::Vector3d(5, 3, 1);
    block.size = Eigen::Vector3d(2, 1, 2);
    w.boxes.push_back(block);
    w.starts = {Eigen::Vector3d(1, 1, 0), Eigen::Vector3d(9, 5, 0)};
    w.people.push_back({"walker", {{2, 2}, {8, 2}, {8, 4}, {2, 4}}});
    return w;
}

/** Pixels within `tolerance` of a BGR colour. */
int pixelsOf(const cv::Mat& img, const cv::Vec3b& bgr, int tolerance = 12) {
    int n = 0;
    for (int y = 0; y < img.rows; ++y)
        for (int x = 0; x < img.cols; ++x) {
            const cv::Vec3b p = img.at<cv::Vec3b>(y, x);
            if (std::abs(p[0] - bgr[0]) <= tolerance && std::abs(p[1] - bgr[1]) <= tolerance &&
                std::abs(p[2] - bgr[2]) <= tolerance)
                ++n;
        }
    return n;
}

fs::path pngPath(const std::string& name) {
    return fs::temp_directory_path() /
           ("daep_test_render_" + std::to_string(::getpid()) + "_" + name + ".png");
}

TEST(WorldRender, DrawsTheBoxTheGeometryTheStartsAndTheRoutes) {
    const fs::path png = pngPath("room");
    daep::eval::renderWorldPng(smallRoom(), png.string(), 400);
    const cv::Mat img = cv::imread(png.string(), cv::IMREAD_COLOR);
    fs::remove(png);
    ASSERT_FALSE(img.empty());
    EXPECT_EQ(img.cols, 400);
    EXPECT_EQ(img.rows, 400);
    // The exploration box's outline (BGR 200, 90, 0) runs around the 10 x 6 m room.
    EXPECT_GT(pixelsOf(img, cv::Vec3b(200, 90, 0)), 500);
    // Two start rings (red, BGR 0, 0, 220).
    EXPECT_GT(pixelsOf(img, cv::Vec3b(0, 0, 220)), 60);
    // The only person's route, in the first hue of the route palette (HSV 0, 220, 200).
    cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(0, 220, 200)), bgr;
    cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
    EXPECT_GT(pixelsOf(img, bgr.at<cv::Vec3b>(0, 0)), 300);
    // Geometry, grid and labels on a white page.
    const int white = pixelsOf(img, cv::Vec3b(255, 255, 255), 0);
    EXPECT_GT(white, 400 * 400 / 4);
    EXPECT_LT(white, 400 * 400 - 5000);
}

TEST(WorldRender, TooSmallOrUnwritableIsAnError) {
    EXPECT_THROW(daep::eval::renderWorldPng(smallRoom(), pngPath("small").string(), 100),
                 std::runtime_error);
    EXPECT_THROW(daep::eval::renderWorldPng(smallRoom(), "/nonexistent-dir/room.png", 400),
                 std::runtime_error);
}

TEST(Plot, NiceStepIsOneTwoTwoAndAHalfOrFiveTimesAPowerOfTen) {
    EXPECT_DOUBLE_EQ(daep::eval::niceStep(0.7), 1.0);
    EXPECT_DOUBLE_EQ(daep::eval::niceStep(1.0), 1.0);
    EXPECT_DOUBLE_EQ(daep::eval::niceStep(1.2), 2.0);
    EXPECT_DOUBLE_EQ(daep::eval::niceStep(2.2), 2.5);
    EXPECT_DOUBLE_EQ(daep::eval::niceStep(3.0), 5.0);
    EXPECT_DOUBLE_EQ(daep::eval::niceStep(7.0), 10.0);
    EXPECT_DOUBLE_EQ(daep::eval::niceStep(0.03), 0.05);
}

}  // namespace
