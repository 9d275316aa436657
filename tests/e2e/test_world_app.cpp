// daep-world end to end: import a benchmark world, render it, and fail clearly on a missing model.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "RunApp.h"
#include "daep/world/WorldSpec.h"

#ifdef DAEP_WORLD_BIN
namespace daep::test {
namespace {

namespace fs = std::filesystem;
const std::string kBench = std::string(DAEP_SHARED_DIR) + "/datasets/daep-benchmark";

AppResult runWorld(const std::string& args, const fs::path& scratch) {
    return runApp(DAEP_WORLD_BIN, args, scratch);
}

TEST(WorldApp, ImportsAndRendersTheMaze) {
    if (!fs::exists(kBench))
        GTEST_SKIP() << kBench << " not present";
    const auto dir = freshDir("world_maze");
    const auto yaml = dir / "maze.yaml";
    const auto r = runWorld("import " + kBench + "/worlds/maze_static.world --out " +
                                yaml.string() + " --model-path " + kBench + "/models --people " +
                                kBench + "/launch/maze_dynamic.launch --box-config " + kBench +
                                "/config/maze_exploration.yaml --starts " + kBench +
                                "/config/experiments.yaml --starts-key maze --skip-missing",
                            dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("1 meshes, 5 people, 5 starts"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("warning:"), std::string::npos);  // the skipped nist_maze_wall models
    const auto world = daep::world::loadWorldFile(yaml.string());
    EXPECT_EQ(world.name, "maze_static");

    const auto png = dir / "maze.png";
    const auto rr =
        runWorld("render " + yaml.string() + " --out " + png.string() + " --size 640", dir);
    ASSERT_EQ(rr.exitCode, 0) << rr.err;
    const cv::Mat img = cv::imread(png.string());
    ASSERT_FALSE(img.empty());
    EXPECT_EQ(img.cols, 640);
    EXPECT_EQ(img.rows, 640);
    // Something was drawn: the image is not a plain white page.
    cv::Mat grey;
    cv::cvtColor(img, grey, cv::COLOR_BGR2GRAY);
    EXPECT_GT(cv::countNonZero(grey < 128), 2000);
}

TEST(WorldApp, RendersABuiltinWorld) {
    const auto dir = freshDir("world_render");
    const auto png = dir / "exhibition.png";
    const auto r = runWorld("render exhibition --out " + png.string() + " --size 500", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const cv::Mat img = cv::imread(png.string());
    EXPECT_EQ(img.cols, 500);
    EXPECT_EQ(img.rows, 500);
}

TEST(WorldApp, ReachBoundsEveryStartOfTheTinyRoom) {
    // 40 x 25 x 10 cells (y centres -2.5 .. 2.3: the south row lies in the wall), the door
    // wider than the drone: all seen but the 2 x 2 cells inside the pillar in each of the 10
    // layers, 9960 of 10000 cells. (The partition's cells in the wall row count: rays reach
    // them past the partition's end.)
    const auto dir = freshDir("world_reach");
    const auto r = runWorld("reach " + std::string(DAEP_E2E_DATA) + "/tiny_room.yaml", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (int s = 0; s < 5; ++s)
        EXPECT_NE(r.out.find("start " + std::to_string(s) + " "), std::string::npos) << r.out;
    std::size_t lines = 0;
    for (std::size_t at = r.out.find("reachable 99.60 %  (observable 79.7 m^3");
         at != std::string::npos; at = r.out.find("reachable 99.60 %", at + 1))
        ++lines;
    EXPECT_EQ(lines, 5u) << r.out;

    const auto one = runWorld(
        "reach " + std::string(DAEP_E2E_DATA) + "/tiny_room.yaml --start 1 --robot-radius 0.8",
        dir);
    ASSERT_EQ(one.exitCode, 0) << one.err;
    EXPECT_EQ(one.out.find("start 0 "), std::string::npos) << one.out;
    EXPECT_NE(one.out.find("start 1 "), std::string::npos) << one.out;
}

TEST(WorldApp, ReachRejectsBadOptions) {
    const auto dir = freshDir("world_reach_bad");
    const auto range = runWorld("reach exhibition --start 5", dir);
    EXPECT_EQ(range.exitCode, 1);
    EXPECT_NE(range.err.find("--start: 5 is out of range 0..4"), std::string::npos) << range.err;
    const auto res = runWorld("reach exhibition --resolution 0", dir);
    EXPECT_EQ(res.exitCode, 1);
    EXPECT_NE(res.err.find("--resolution"), std::string::npos) << res.err;
    EXPECT_EQ(runWorld("reach exhibition --climb abc", dir).exitCode, 1);
}

TEST(WorldApp, MissingModelExitsWithTheUri) {
    const auto dir = freshDir("world_missing");
    std::ofstream(dir / "w.world")
        << "<sdf version='1.6'><world name='default'>\n"
           "<include><uri>model://no_such_model</uri></include></world></sdf>\n";
    const auto r = runWorld("import " + (dir / "w.world").string() + " --out " +
                                (dir / "w.yaml").string() + " --model-path " + dir.string(),
                            dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("model://no_such_model"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("w.world:2:"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "w.yaml"));
}

TEST(WorldApp, BadArgumentsExitWithUsage) {
    const auto dir = freshDir("world_args");
    const auto help = runWorld("--help", dir);
    EXPECT_EQ(help.exitCode, 0);
    EXPECT_NE(help.out.find("daep-world reach WORLD"), std::string::npos) << help.out;
    const auto r = runWorld("render exhibition", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("--out is required"), std::string::npos) << r.err;
    EXPECT_EQ(runWorld("frobnicate", dir).exitCode, 1);
}

}  // namespace
}  // namespace daep::test
#endif
