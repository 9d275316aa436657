// End-to-end: daep-replay and daep-predict-eval as a user runs them.
#include <gtest/gtest.h>

#include <regex>

#include "RunApp.h"

namespace fs = std::filesystem;
using daep::test::freshDir;
using daep::test::jsonNumber;
using daep::test::readText;
using daep::test::runApp;
using daep::test::runExplore;

TEST(ReplayApp, ReplayingARunWithItsOwnSettingsGivesItsCoverage) {
    const auto dir = freshDir("replay");
    const std::string& ini = daep::test::kTinyIni;
    const auto run = runExplore(
        ini + " --quiet --set experiment.max_time_s=30 --out " + (dir / "run").string(), dir);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    const double coverage = jsonNumber(readText(dir / "run" / "summary.json"), "coverage_percent");

    const auto same =
        runApp(DAEP_REPLAY_BIN, ini + " " + (dir / "run" / "trajectory.csv").string(), dir);
    ASSERT_EQ(same.exitCode, 0) << same.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(same.out, m, std::regex("coverage ([0-9.]+) %"))) << same.out;
    EXPECT_NEAR(std::stod(m[1]), coverage, 0.5);

    const auto finer = runApp(DAEP_REPLAY_BIN,
                              ini + " " + (dir / "run" / "trajectory.csv").string() +
                                  " --set camera.width=320 --set camera.height=240",
                              dir);
    ASSERT_EQ(finer.exitCode, 0) << finer.err;
    ASSERT_TRUE(std::regex_search(finer.out, m, std::regex("coverage ([0-9.]+) %")));
    EXPECT_NEAR(std::stod(m[1]), coverage, 2.0);

    const auto bad = runApp(DAEP_REPLAY_BIN, ini + " " + ini, dir);
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.err.find("sim_time,x,y,z,yaw"), std::string::npos) << bad.err;
}

TEST(PredictEvalApp, HotelTracksEndWithTheSummaryLine) {
    const std::string tracks = std::string(DAEP_SHARED_DIR) + "/datasets/eth_ucy/biwi_hotel.txt";
    if (!fs::exists(tracks))
        GTEST_SKIP() << tracks << " not available";
    const auto dir = freshDir("predict");
    const auto r = runApp(DAEP_PREDICT_EVAL_BIN, tracks, dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        r.out, m, std::regex("\\nADE=([0-9.]+) FDE=([0-9.]+) coverage95=([0-9.]+)\\n$")))
        << r.out;
    EXPECT_NEAR(std::stod(m[1]), 0.28, 0.02);
    EXPECT_NEAR(std::stod(m[2]), 0.53, 0.03);
    EXPECT_NEAR(std::stod(m[3]), 0.95, 0.03);

    const auto bad = runApp(DAEP_PREDICT_EVAL_BIN, "/nonexistent/tracks.txt", dir);
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.err.find("/nonexistent/tracks.txt"), std::string::npos);
}
