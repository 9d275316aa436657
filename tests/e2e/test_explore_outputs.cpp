// End-to-end: daep-explore's output folder holds one run only, its summary says which build
// made it, and a bad --set value is blamed on the --set.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "RunApp.h"

namespace fs = std::filesystem;
using namespace daep::test;

TEST(ExploreOutputs, AReusedFolderKeepsNoFileOfAnEarlierRun) {
    const auto dir = freshDir("explore_reuse");
    const auto out = dir / "run";
    fs::create_directories(out);
    // What an earlier run with other outputs left behind, and a file that is not a run's.
    for (const char* stale : {"run.rawlog", "people.csv", "scene_top.png", "summary.json"})
        std::ofstream(out / stale) << "earlier run\n";
    std::ofstream(out / "notes.txt") << "mine\n";
    const auto r = runExplore(kTinyIni +
                                  " --quiet --set experiment.max_time_s=3 "
                                  "--set output.scene=false --out " +
                                  out.string(),
                              dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* stale : {"run.rawlog", "people.csv", "scene_top.png"})
        EXPECT_FALSE(fs::exists(out / stale)) << stale;
    EXPECT_NE(readText(out / "summary.json").find("\"coverage_percent\""), std::string::npos);
    EXPECT_EQ(readText(out / "notes.txt"), "mine\n");
    fs::remove_all(dir);
}

TEST(ExploreOutputs, SummaryEndsWithTheRunsProvenance) {
    const auto dir = freshDir("explore_provenance");
    const auto r = runExplore(
        kTinyIni + " --quiet --set experiment.max_time_s=3 --set output.scene=false --out " +
            (dir / "run").string(),
        dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string summary = readText(dir / "run" / "summary.json");
    const auto provenance = summary.find(",\n  \"provenance\": {\n    \"version\": \"");
    ASSERT_NE(provenance, std::string::npos) << summary;
    EXPECT_GT(provenance, summary.find("\"wall_time_s\""));
    EXPECT_NE(summary.find("\"command_line\": \"" + std::string(DAEP_EXPLORE_BIN) + " " + kTinyIni +
                           " --quiet --set experiment.max_time_s=3"),
              std::string::npos)
        << summary;
    EXPECT_EQ(summary.substr(summary.size() - 8), "\"\n  }\n}\n");
    // The determinism tests' view of it keeps every metric and drops the whole block.
    const std::string kept = deterministicSummaryText(summary);
    EXPECT_EQ(kept.find("provenance"), std::string::npos) << kept;
    EXPECT_EQ(kept.find("command_line"), std::string::npos) << kept;
    EXPECT_NE(kept.find("\"exploration_start_s\""), std::string::npos) << kept;
    EXPECT_EQ(kept.substr(kept.size() - 2), "}\n");
    fs::remove_all(dir);
}

TEST(ExploreOutputs, BadSetValueNamesTheSetNotTheConfigFile) {
    const auto dir = freshDir("explore_bad_set");
    const struct {
        std::string set, message;
    } cases[] = {
        {"camera.width=abc", "--set camera.width: [camera] width: 'abc' is not an integer"},
        {"experiment.max_time_s=-1", "--set experiment.max_time_s: [experiment] max_time_s: must"},
        {"map.max_range=0", "--set map.max_range: [map] max_range: 0 must be > 0"},
    };
    for (const auto& c : cases) {
        const auto r = runExplore(
            kTinyIni + " --quiet --set " + c.set + " --out " + (dir / "run").string(), dir);
        EXPECT_EQ(r.exitCode, 1) << c.set;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.set << ": " << r.err;
    }
    // A bad value in the file names the file and line.
    fs::copy_file(std::string(DAEP_E2E_DATA) + "/tiny_room.yaml", dir / "tiny_room.yaml");
    std::ofstream(dir / "bad.ini") << readText(kTinyIni) << "\n[map]\nmax_range = 0\n";
    const auto r =
        runExplore((dir / "bad.ini").string() + " --quiet --out " + (dir / "run").string(), dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("bad.ini:"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(": [map] max_range: 0 must be > 0"), std::string::npos) << r.err;
    fs::remove_all(dir);
}

TEST(ExploreOutputs, RenderSceneDrawsTheSamePngsARunWouldHave) {
    const auto dir = freshDir("explore_render_scene");
    const std::string common = kTinyIni +
                               " --quiet --set experiment.max_time_s=5 --set output.png_width=320 "
                               "--set output.png_height=240 ";
    const auto rendered = runExplore(common + "--out " + (dir / "rendered").string(), dir);
    ASSERT_EQ(rendered.exitCode, 0) << rendered.err;
    if (!fs::exists(dir / "rendered" / "scene_top.png"))
        GTEST_SKIP() << "no EGL/OpenGL here: the run skipped its PNGs (" << rendered.err << ")";
    const auto later = dir / "later";
    ASSERT_EQ(
        runExplore(common + "--set output.render_png=false --out " + later.string(), dir).exitCode,
        0);
    ASSERT_TRUE(fs::exists(later / "scene.3Dscene"));
    ASSERT_FALSE(fs::exists(later / "scene_top.png"));
    const auto r = runExplore("--render-scene " + later.string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* png : {"scene_perspective.png", "scene_top.png"}) {
        ASSERT_TRUE(fs::exists(later / png)) << png;
        EXPECT_EQ(readText(later / png), readText(dir / "rendered" / png)) << png;
    }
    fs::remove_all(dir);
}

TEST(ExploreOutputs, RenderSceneNamesTheSceneItCannotRead) {
    const auto dir = freshDir("explore_render_bad_scene");
    const auto run = dir / "run";
    ASSERT_EQ(runExplore(kTinyIni +
                             " --quiet --set experiment.max_time_s=3 "
                             "--set output.render_png=false --out " +
                             run.string(),
                         dir)
                  .exitCode,
              0);
    const std::string scene = readText(run / "scene.3Dscene");
    struct Case {
        std::string content, message;
    };
    for (const Case& c :
         {Case{"", "does not exist"}, Case{"not a scene\n", "cannot read the scene"},
          Case{scene.substr(0, scene.size() / 2), "cannot read the scene"}}) {
        fs::remove(run / "scene.3Dscene");
        if (!c.content.empty())
            std::ofstream(run / "scene.3Dscene", std::ios::binary) << c.content;
        const auto r = runExplore("--render-scene " + run.string(), dir);
        EXPECT_EQ(r.exitCode, 1) << c.message;
        EXPECT_NE(r.err.find((run / "scene.3Dscene").string()), std::string::npos) << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
        EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "one line: " << r.err;
        EXPECT_FALSE(fs::exists(run / "scene_top.png"));
    }
    const auto r = runExplore("--render-scene " + run.string() + " " + kTinyIni, dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("--render-scene takes the run's folder alone"), std::string::npos)
        << r.err;
    fs::remove_all(dir);
}
