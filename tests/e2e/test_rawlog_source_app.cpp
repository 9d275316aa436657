// daep-explore with [experiment] source = rawlog, run as a real process.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "RunApp.h"

namespace {

using daep::test::freshDir;
using daep::test::jsonNumber;
using daep::test::kTinyIni;
using daep::test::readText;
using daep::test::runExplore;

const std::string kDataset = std::string(DAEP_SOURCE_DIR) + "/datasets/tiny_room_dynamic.rawlog";

int lineCount(const std::filesystem::path& p) {
    std::ifstream f(p);
    int n = 0;
    for (std::string l; std::getline(f, l);)
        ++n;
    return n;
}

TEST(RawlogSourceApp, ReplaysTheShippedDatasetWithAPlanner) {
    const auto dir = freshDir("rawlog_source");
    const auto out = dir / "run";
    const auto r = runExplore(
        kTinyIni + " --set experiment.source=rawlog" + " --set experiment.rawlog_file=" + kDataset +
            " --set rawlog.world=tiny_room.yaml" +
            " --set rawlog.plan_every_s=2 --set output.scene=false" + " --out " + out.string(),
        dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("source = rawlog"), std::string::npos);
    EXPECT_NE(r.out.find("== Result"), std::string::npos);
    EXPECT_NE(r.out.find("end of rawlog"), std::string::npos);

    const std::string summary = readText(out / "summary.json");
    EXPECT_NEAR(jsonNumber(summary, "exploration_time_s"), 20.2, 1e-9);
    EXPECT_EQ(jsonNumber(summary, "iterations"), 11.0);  // t = 0, 2, ..., 20
    EXPECT_GT(jsonNumber(summary, "coverage_percent"), 30.0);
    EXPECT_EQ(jsonNumber(summary, "box_volume_m3"), 80.0);            // tiny_room's box
    EXPECT_EQ(summary.find("reachable_percent"), std::string::npos);  // no start to bound from
    EXPECT_NE(summary.find("\"end_reason\": \"end of rawlog\""), std::string::npos);
    EXPECT_EQ(lineCount(out / "plans.csv"), 12);
    EXPECT_EQ(lineCount(out / "trajectory.csv"), 103);
    EXPECT_TRUE(std::filesystem::exists(out / "map.bt"));
    EXPECT_NE(readText(out / "config.ini").find("rawlog_file = " + kDataset), std::string::npos);
}

// The README's replay command, from another folder: the config names the dataset and its
// world relative to the share directory, and that world must still load (it is the test room's).
TEST(RawlogSourceApp, ShippedReplayConfigRunsAsWritten) {
    const std::string source(DAEP_SOURCE_DIR);
    EXPECT_EQ(readText(source + "/datasets/tiny_room.yaml"),
              readText(source + "/tests/e2e/data/tiny_room.yaml"))
        << "datasets/tiny_room.yaml is the test room's copy: keep the two equal";
    const auto dir = freshDir("rawlog_replay_config");
    const auto out = dir / "run";
    const auto r = runExplore(
        source + "/config-ini/tiny_room_replay.ini --quiet --set output.scene=false --out " +
            out.string(),
        dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string summary = readText(out / "summary.json");
    EXPECT_NE(summary.find("\"end_reason\": \"end of rawlog\""), std::string::npos) << summary;
    EXPECT_GT(jsonNumber(summary, "coverage_percent"), 30.0);
    EXPECT_EQ(lineCount(out / "trajectory.csv"), 103);
}

TEST(RawlogSourceApp, MissingRawlogIsExitOneNamingTheFile) {
    const auto dir = freshDir("rawlog_missing");
    const std::string missing = (dir / "nowhere.rawlog").string();
    const auto r = runExplore(kTinyIni + " --set experiment.source=rawlog" +
                                  " --set experiment.rawlog_file=" + missing + " --out " +
                                  (dir / "run").string(),
                              dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find(missing), std::string::npos) << r.err;

    const auto noFile = runExplore(
        kTinyIni + " --set experiment.source=rawlog --out " + (dir / "run2").string(), dir);
    EXPECT_EQ(noFile.exitCode, 1);
    EXPECT_NE(noFile.err.find("rawlog_file"), std::string::npos) << noFile.err;
}

}  // namespace
