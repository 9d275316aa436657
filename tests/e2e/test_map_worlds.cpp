// End to end: worlds whose geometry is a scanned map (tests/e2e/data/maps): explored by
// daep-explore, drawn and scanned by daep-world.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "RunApp.h"
#include "daep/world/WorldSpec.h"

#if defined(DAEP_WORLD_BIN) && defined(DAEP_EXPLORE_BIN)
namespace daep::test {
namespace {

namespace fs = std::filesystem;
const std::string kMaps = std::string(DAEP_E2E_DATA) + "/maps";

/** The tiny room's mission, 45 s, on a world made of a map instead of boxes. */
AppResult exploreMapWorld(const std::string& world, const fs::path& dir) {
    return runExplore(kTinyIni + " --set experiment.world=maps/" + world +
                          " --set experiment.max_time_s=45 --quiet --out " + (dir / "run").string(),
                      dir);
}

TEST(MapWorlds, ExploresTheRoomScannedAtAFinerResolution) {
    const auto dir = freshDir("map_bt");
    const auto r = exploreMapWorld("tiny_room_bt.yaml", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string summary = readText(dir / "run" / "summary.json");
    EXPECT_GT(jsonNumber(summary, "coverage_percent"), 40.0) << summary;
    EXPECT_EQ(jsonNumber(summary, "static_collisions"), 0) << summary;
    EXPECT_GT(jsonNumber(summary, "reachable_percent"), 90.0) << summary;
    EXPECT_LE(jsonNumber(summary, "coverage_percent"), jsonNumber(summary, "reachable_percent"));
    EXPECT_GT(jsonNumber(summary, "path_length_m"), 1.0) << summary;
}

TEST(MapWorlds, ExploresTheRoomScannedAtACoarserResolution) {
    const auto dir = freshDir("map_ot");
    const auto r = exploreMapWorld("tiny_room_ot.yaml", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string summary = readText(dir / "run" / "summary.json");
    EXPECT_GT(jsonNumber(summary, "coverage_percent"), 30.0) << summary;
    EXPECT_EQ(jsonNumber(summary, "static_collisions"), 0) << summary;
}

TEST(MapWorlds, RendersAMapWorld) {
    const auto dir = freshDir("map_render");
    const auto png = dir / "room.png";
    const auto r =
        runApp(DAEP_WORLD_BIN,
               "render " + kMaps + "/tiny_room_bt.yaml --out " + png.string() + " --size 400", dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const cv::Mat img = cv::imread(png.string());
    ASSERT_EQ(img.cols, 400);
    // The walls are drawn: a dark band where the west wall stands, white inside the room.
    cv::Mat grey;
    cv::cvtColor(img, grey, cv::COLOR_BGR2GRAY);
    const cv::Mat room = grey(cv::Rect(60, 150, 280, 200));
    EXPECT_GT(cv::countNonZero(room < 170), 500) << "no map geometry drawn";
}

TEST(MapWorlds, ScanWritesAMapThatLoads) {
    const auto dir = freshDir("map_scan");
    for (const char* name : {"room.bt", "room.ot", "room.ply"}) {
        const auto out = dir / name;
        const auto r = runApp(DAEP_WORLD_BIN,
                              "scan " + std::string(DAEP_E2E_DATA) + "/tiny_room.yaml --out " +
                                  out.string() + " --step-deg 2 --resolution 0.2",
                              dir);
        ASSERT_EQ(r.exitCode, 0) << r.err;
        EXPECT_NE(r.out.find("5 stations, 81000 rays"), std::string::npos) << r.out;
        EXPECT_GT(fs::file_size(out), 1000u) << name;
    }
    std::ofstream(dir / "w.yaml") << "exploration_box: {min: [-4, -2.5, 0], max: [4, 2.5, 2]}\n"
                                     "starts: [[-2.5, -1.5, 0.2]]\n"
                                     "octomap: room.bt\n"
                                     "point_cloud: {file: room.ply, voxel_size: 0.2}\n";
    const auto world = daep::world::loadWorldFile((dir / "w.yaml").string());
    ASSERT_EQ(world.voxelMaps.size(), 2u);
    EXPECT_EQ(world.voxelMaps[0].cells, world.voxelMaps[1].cells);

    const auto bad =
        runApp(DAEP_WORLD_BIN, "scan exhibition --out " + (dir / "x.stl").string(), dir);
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.err.find("x.stl: the output must end in .bt, .ot or .ply"), std::string::npos)
        << bad.err;
    const auto station = runApp(
        DAEP_WORLD_BIN, "scan exhibition --station 1,2 --out " + (dir / "x.bt").string(), dir);
    EXPECT_EQ(station.exitCode, 1);
    EXPECT_NE(station.err.find("--station: expected X,Y,Z"), std::string::npos) << station.err;
}

TEST(MapWorlds, BadMapExitsOneWithTheFile) {
    const auto dir = freshDir("map_bad");
    std::ofstream(dir / "w.yaml") << "exploration_box: {min: [-4, -2.5, 0], max: [4, 2.5, 2]}\n"
                                     "starts: [[-2.5, -1.5, 0.2]]\n"
                                     "octomap: w.yaml\n";
    const auto r = runExplore(kTinyIni + " --set experiment.world=" + (dir / "w.yaml").string() +
                                  " --quiet --out " + (dir / "run").string(),
                              dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("w.yaml:3: octomap: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("w.yaml: not an OctoMap file"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace daep::test
#endif
