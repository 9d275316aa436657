// End-to-end: what every app shares on its command line (--version, --debug, one-line errors),
// and the installed apps run from another directory.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "RunApp.h"
#include "daep/common/BuildInfo.h"

namespace fs = std::filesystem;
using daep::test::freshDir;
using daep::test::jsonNumber;
using daep::test::kTinyIni;
using daep::test::readText;
using daep::test::runApp;
using daep::test::runExplore;

namespace {

struct AppBinary {
    std::string name, path;
};

const std::vector<AppBinary>& allApps() {
    static const std::vector<AppBinary> apps = {{"daep-explore", DAEP_EXPLORE_BIN},
                                                {"daep-replay", DAEP_REPLAY_BIN},
                                                {"daep-predict-eval", DAEP_PREDICT_EVAL_BIN},
                                                {"daep-benchmark", DAEP_BENCHMARK_BIN},
                                                {"daep-world", DAEP_WORLD_BIN},
                                                {"daep-detect-eval", DAEP_DETECT_EVAL_BIN}};
    return apps;
}

std::size_t lineCount(const std::string& text) {
    return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

/** An experiment that replays `rawlog` (source = rawlog) in the tiny room. */
std::string replayArgs(const std::string& rawlog, const fs::path& out) {
    return kTinyIni + " --set experiment.source=rawlog --set experiment.rawlog_file=" + rawlog +
           " --set rawlog.world=tiny_room.yaml --set output.scene=false --quiet --out " +
           out.string();
}

}  // namespace

TEST(AppCommandLine, EveryAppPrintsItsVersionWithTheCommit) {
    const auto dir = freshDir("version");
    const std::string commit = daep::shortCommit();
    for (const auto& app : allApps()) {
        const auto r = runApp(app.path, "--version", dir);
        EXPECT_EQ(r.exitCode, 0) << app.name << ": " << r.err;
        EXPECT_EQ(r.out.rfind(app.name + " ", 0), 0u) << r.out;
        EXPECT_NE(r.out.find("commit " + commit), std::string::npos) << app.name << ": " << r.out;
        EXPECT_NE(r.out.find("MRPT"), std::string::npos) << r.out;
        EXPECT_EQ(r.err, "") << app.name;
    }
}

TEST(AppCommandLine, EveryAppRejectsAnUnknownOptionOnOneLine) {
    const auto dir = freshDir("unknown_option");
    for (const auto& app : allApps()) {
        const std::string args = app.name == "daep-world" ? "render x --bogus" : "x --bogus";
        const auto r = runApp(app.path, args, dir);
        EXPECT_EQ(r.exitCode, 1) << app.name;
        EXPECT_NE(r.err.find("unknown option --bogus"), std::string::npos) << r.err;
        EXPECT_EQ(lineCount(r.err), 1u) << app.name << ": " << r.err;
    }
}

TEST(AppCommandLine, UnreadableRawlogIsOneLineAndTheBacktraceOnlyWithDebug) {
    const auto dir = freshDir("rawlog_passwd");
    const auto r = runExplore(replayArgs("/etc/passwd", dir / "run"), dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("/etc/passwd"), std::string::npos) << r.err;
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.find("Call stack"), std::string::npos) << r.err;

    // An observation of a serialization version MRPT does not know: MRPT's own exception.
    const auto badVersion = dir / "bad_version.rawlog";
    const std::string className = "CObservationOdometry";
    std::ofstream(badVersion, std::ios::binary)
        << static_cast<char>(0x80 | className.size()) << className << static_cast<char>(99)
        << std::string(64, '\0');
    const auto plain = runExplore(replayArgs(badVersion.string(), dir / "run2"), dir);
    EXPECT_EQ(plain.exitCode, 1);
    EXPECT_NE(plain.err.find("version"), std::string::npos) << plain.err;
    EXPECT_EQ(lineCount(plain.err), 1u) << plain.err;
    const auto debug = runExplore(replayArgs(badVersion.string(), dir / "run3") + " --debug", dir);
    EXPECT_EQ(debug.exitCode, 1);
    EXPECT_NE(debug.err.find(badVersion.string()), std::string::npos) << debug.err;
    EXPECT_NE(debug.err.find("Call stack"), std::string::npos) << debug.err;
    EXPECT_GT(lineCount(debug.err), 3u);
}

TEST(AppCommandLine, TruncatedRawlogEndsWithAOneLineReasonInTheSummary) {
    const auto dir = freshDir("rawlog_truncated");
    const std::string full =
        readText(std::string(DAEP_SOURCE_DIR) + "/datasets/tiny_room_dynamic.rawlog");
    const auto cut = dir / "cut.rawlog";
    std::ofstream(cut, std::ios::binary) << full.substr(0, full.size() / 2);
    const auto r = runExplore(replayArgs(cut.string(), dir / "run"), dir);
    EXPECT_NE(r.exitCode, 0);
    EXPECT_EQ(lineCount(r.err), 1u) << r.err;
    EXPECT_NE(r.err.find("cut.rawlog"), std::string::npos) << r.err;
    const std::string summary = readText(dir / "run" / "summary.json");
    const auto reason = summary.find("\"end_reason\": \"error: ");
    ASSERT_NE(reason, std::string::npos) << summary;
    const std::string line = summary.substr(reason, summary.find('\n', reason) - reason);
    EXPECT_EQ(line.find("\\n"), std::string::npos) << line;  // no escaped multi-line text
    EXPECT_EQ(line.find("Call stack"), std::string::npos) << line;
}

TEST(PredictEvalApp, NothingScoredSaysSoAndFails) {
    const auto dir = freshDir("predict_nothing");
    const auto tracks = dir / "short.txt";
    // One person in three frames: far fewer than a window's 8 observed + 12 predicted.
    std::ofstream(tracks) << "0 1 1.0 2.0\n10 1 1.4 2.0\n20 1 1.8 2.0\n";
    const auto r = runApp(DAEP_PREDICT_EVAL_BIN, tracks.string(), dir);
    EXPECT_EQ(r.exitCode, 2);
    EXPECT_NE(r.out.find("ADE=n/a FDE=n/a coverage95=n/a"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("0.000"), std::string::npos) << r.out;
    EXPECT_NE(r.err.find("nothing scored"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("short.txt"), std::string::npos) << r.err;
}

TEST(InstalledApps, RunFromAnotherDirectoryWithTheirSharedFiles) {
    const auto dir = freshDir("install");
    const auto prefix = dir / "prefix";
    const std::string install = std::string(DAEP_CMAKE_COMMAND) + " --install " + DAEP_BINARY_DIR +
                                " --prefix " + prefix.string() + " > " +
                                (dir / "install.log").string() + " 2>&1";
    ASSERT_EQ(std::system(install.c_str()), 0) << readText(dir / "install.log");
    for (const char* file : {"bin/daep-explore", "bin/daep-world", "bin/daep-benchmark",
                             "share/daep/config/defaults.ini", "share/daep/worlds/cafe.yaml",
                             "share/daep/config-ini/exhibition_dynamic.ini",
                             "share/daep/datasets/tiny_room_dynamic.rawlog"})
        EXPECT_TRUE(fs::exists(prefix / file)) << file;

    // From an empty directory, with no DAEP_SHARE_DIR: the apps find PREFIX/share/daep.
    const auto work = dir / "elsewhere";
    fs::create_directories(work);
    const std::string inWork = "cd " + work.string() + " && env -u DAEP_SHARE_DIR ";
    const auto run = runApp(inWork + (prefix / "bin" / "daep-explore").string(),
                            "config-ini/exhibition_dynamic.ini --quiet --set output.scene=false"
                            " --set experiment.max_time_s=10 --set experiment.planning_time=fixed"
                            " --out run",
                            dir);
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_NE(run.out.find("planner daep, world exhibition, mode dynamic"), std::string::npos)
        << run.out;
    const std::string summary = readText(work / "run" / "summary.json");
    EXPECT_NE(summary.find("\"world\": \"exhibition\""), std::string::npos) << summary;
    EXPECT_GT(jsonNumber(summary, "coverage_percent"), 1.0);
    EXPECT_TRUE(fs::exists(work / "run" / "trajectory_tum.txt"));

    const auto render = runApp(inWork + (prefix / "bin" / "daep-world").string(),
                               "render cafe --out cafe.png --size 200", dir);
    ASSERT_EQ(render.exitCode, 0) << render.err;
    EXPECT_TRUE(fs::exists(work / "cafe.png"));
    fs::remove_all(dir);
}
