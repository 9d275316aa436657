// End-to-end: the real daep-explore binary on a small world and on the built-in worlds.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "RunApp.h"

namespace fs = std::filesystem;
using daep::test::freshDir;
using daep::test::jsonNumber;
using daep::test::kTinyIni;
using daep::test::readText;
using daep::test::runExplore;

namespace {

std::string deterministicSummary(const fs::path& dir) {
    return daep::test::deterministicSummaryText(readText(dir / "summary.json"));
}

std::vector<std::vector<double>> readCsv(const fs::path& p) {
    std::istringstream in(readText(p));
    std::string line;
    std::getline(in, line);  // header
    std::vector<std::vector<double>> rows;
    while (std::getline(in, line)) {
        std::vector<double> row;
        std::istringstream cells(line);
        std::string cell;
        while (std::getline(cells, cell, ','))
            row.push_back(std::strtod(cell.c_str(), nullptr));
        rows.push_back(row);
    }
    return rows;
}

}  // namespace

TEST(ExploreApp, TinyRoomMissionWritesAllOutputsWithPlausibleMetrics) {
    const auto dir = freshDir("tiny");
    const auto r = runExplore(kTinyIni + " --out " + (dir / "run").string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    for (const char* f : {"summary.json", "timeseries.csv", "trajectory.csv", "plans.csv",
                          "collisions.csv", "timing.json", "config.ini", "map.bt"})
        EXPECT_TRUE(fs::exists(dir / "run" / f)) << f;
    EXPECT_GT(fs::file_size(dir / "run" / "map.bt"), 1000u);

    const std::string summary = readText(dir / "run" / "summary.json");
    for (const char* key : {"coverage_percent", "exploration_time_s", "path_length_m",
                            "planning_time_s", "plan_ms_median", "plan_ms_p95", "collisions",
                            "static_collisions", "iterations", "wall_time_s"})
        EXPECT_FALSE(std::isnan(jsonNumber(summary, key))) << key;
    EXPECT_NE(summary.find("\"finished\":"), std::string::npos);

    // timing.json: the wall time per stage adds up to no more than the run's wall time.
    const std::string timing = readText(dir / "run" / "timing.json");
    const double wall = jsonNumber(timing, "wall_time_s");
    double stages = 0.0;
    for (const char* stage :
         {"render", "people", "map", "world", "checks", "planning", "recording", "other"}) {
        const double s = jsonNumber(timing, stage);
        EXPECT_GE(s, 0.0) << stage;
        stages += s;
    }
    EXPECT_GT(jsonNumber(timing, "map"), 0.0);
    EXPECT_GT(jsonNumber(timing, "render"), 0.0);
    EXPECT_NEAR(stages, wall, 0.01 + 1e-3 * 8);  // each printed to 1 ms

    // A 60 m^3 room explored for up to 120 s: most of it must be known, nothing hit.
    EXPECT_GT(jsonNumber(summary, "coverage_percent"), 60.0);
    EXPECT_LE(jsonNumber(summary, "coverage_percent"), 100.0);
    // The bound: all but the pillar's 40 hidden cells (see test_world_app.cpp).
    EXPECT_NEAR(jsonNumber(summary, "reachable_percent"), 99.6, 1e-9);
    EXPECT_LE(jsonNumber(summary, "coverage_percent"), jsonNumber(summary, "reachable_percent"));
    EXPECT_EQ(jsonNumber(summary, "static_collisions"), 0);
    EXPECT_GT(jsonNumber(summary, "iterations"), 3);
    EXPECT_GT(jsonNumber(summary, "path_length_m"), 1.0);
    EXPECT_LE(jsonNumber(summary, "exploration_time_s"), 120.0 + 1e-6);
    // fixed planning time: 0.05 s charged per call
    EXPECT_NEAR(jsonNumber(summary, "planning_time_s"), 0.05 * jsonNumber(summary, "iterations"),
                1e-3);
    EXPECT_NEAR(jsonNumber(summary, "plan_ms_median"), 50.0, 1e-6);

    // The time series is ordered, coverage and path length never decrease.
    const auto rows = readCsv(dir / "run" / "timeseries.csv");
    ASSERT_GT(rows.size(), 10u);
    for (std::size_t i = 1; i < rows.size(); ++i) {
        EXPECT_GT(rows[i][0], rows[i - 1][0]);
        EXPECT_GE(rows[i][1] + 1e-9, rows[i - 1][1]);
        EXPECT_GE(rows[i][2] + 1e-9, rows[i - 1][2]);
    }
    EXPECT_NEAR(rows.back()[1], jsonNumber(summary, "coverage_percent"), 5.0);

    // The trajectory stays inside the rooms (walls at x = +-4, y = +-2.5; the drone is 0.4 m
    // wide).
    for (const auto& p : readCsv(dir / "run" / "trajectory.csv")) {
        EXPECT_GT(p[1], -3.8);
        EXPECT_LT(p[1], 3.8);
        EXPECT_GT(p[2], -2.3);
        EXPECT_LT(p[2], 2.3);
    }
}

TEST(ExploreApp, SameSeedAndFixedPlanningTimeIsBitForBitReproducible) {
    const auto dir = freshDir("repro");
    for (const char* run : {"a", "b"}) {
        const auto r = runExplore(
            kTinyIni + " --quiet --set experiment.max_time_s=40 --out " + (dir / run).string(),
            dir);
        ASSERT_EQ(r.exitCode, 0) << r.err;
    }
    EXPECT_EQ(deterministicSummary(dir / "a"), deterministicSummary(dir / "b"));
    EXPECT_EQ(readText(dir / "a" / "timeseries.csv"), readText(dir / "b" / "timeseries.csv"));
    EXPECT_EQ(readText(dir / "a" / "trajectory.csv"), readText(dir / "b" / "trajectory.csv"));

    const auto r = runExplore(kTinyIni +
                                  " --quiet --set experiment.max_time_s=40 "
                                  "--set experiment.seed=8 --out " +
                                  (dir / "c").string(),
                              dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(readText(dir / "a" / "trajectory.csv"), readText(dir / "c" / "trajectory.csv"));
}

TEST(ExploreApp, BuiltInWorldRunsFromItsReadyConfig) {
    const auto dir = freshDir("builtin");
    const std::string ini = std::string(DAEP_SOURCE_DIR) + "/config-ini/crosswalks_dynamic.ini";
    const auto r = runExplore(ini +
                                  " --quiet --set experiment.max_time_s=30"
                                  " --set experiment.planning_time=fixed --out " +
                                  (dir / "run").string(),
                              dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string summary = readText(dir / "run" / "summary.json");
    EXPECT_NE(summary.find("\"world\": \"crosswalks\""), std::string::npos);
    EXPECT_GT(jsonNumber(summary, "coverage_percent"), 5.0);
    EXPECT_EQ(jsonNumber(summary, "static_collisions"), 0);
}

struct BadInputCase {
    std::string name;
    std::string args;
    std::vector<std::string> messageParts;
};

void PrintTo(const BadInputCase& c, std::ostream* os) {
    *os << c.name;
}

class ExploreAppBadInput : public ::testing::TestWithParam<BadInputCase> {};

TEST_P(ExploreAppBadInput, ExitsNonZeroWithAClearMessage) {
    const auto& c = GetParam();
    const auto dir = freshDir("bad_" + c.name);
    const auto r = runExplore(c.args + " --out " + (dir / "run").string(), dir);
    EXPECT_EQ(r.exitCode, 1) << r.out << r.err;
    for (const auto& part : c.messageParts)
        EXPECT_NE(r.err.find(part), std::string::npos) << "missing '" << part << "' in: " << r.err;
}

namespace {

/** Writes an experiment file next to the test data (so its world path resolves). */
std::string writeIni(const std::string& name, const std::string& text) {
    const auto path = freshDir("ini_" + name) / (name + ".ini");
    std::ofstream(path) << text;
    return path.string();
}

std::string tinyIniWith(const std::string& experimentExtra, const std::string& world) {
    return "[experiment]\nworld = " + world +
           "\nmode = dynamic\nplanner = rhnbvp\nstart = 0\nseed = 1\nmax_time_s = 10\n"
           "planning_time = fixed\n" +
           experimentExtra;
}

const std::string kTinyWorld = std::string(DAEP_E2E_DATA) + "/tiny_room.yaml";

std::vector<BadInputCase> badInputCases() {
    std::vector<BadInputCase> cases;
    cases.push_back({"unknown_world",
                     kTinyIni + " --set experiment.world=atlantis",
                     {"atlantis", "exhibition", "cafe"}});
    cases.push_back(
        {"unknown_planner", kTinyIni + " --set experiment.planner=magic", {"magic", "rhnbvp"}});
    cases.push_back({"typo_key", kTinyIni + " --set camera.widht=10", {"widht", "width"}});
    cases.push_back(
        {"bad_mode", kTinyIni + " --set experiment.mode=chaos", {"mode", "static", "dynamic"}});
    cases.push_back({"bad_number", kTinyIni + " --set camera.rate_hz=fast", {"[camera] rate_hz"}});
    cases.push_back({"bad_people_source",
                     kTinyIni + " --set tracking.people_source=psychic",
                     {"[tracking] people_source", "psychic", "ground_truth", "sensed"}});
    cases.push_back(
        {"start_out_of_range", kTinyIni + " --set experiment.start=9", {"start", "0..4"}});
    cases.push_back({"missing_file", "/nonexistent/exp.ini", {"/nonexistent/exp.ini"}});
    cases.push_back(
        {"fixed_plans_beyond_deadline",
         kTinyIni + " --set experiment.planning_fixed_s=2 --set planning.deadline_s=1.5",
         {"[planning] deadline_s", "planning_fixed_s", "every plan would miss it"}});
    cases.push_back({"no_deadline",
                     kTinyIni + " --set planning.deadline_s=0",
                     {"[planning] deadline_s", "must be > 0"}});
    {
        const std::string ini =
            writeIni("missing_key",
                     "[experiment]\nworld = cafe\nmode = static\nplanner = rhnbvp\n"
                     "start = 0\nmax_time_s = 10\nplanning_time = fixed\n");
        cases.push_back({"missing_key", ini, {"missing_key.ini", "[experiment] seed", "missing"}});
    }
    {
        const std::string ini =
            writeIni("unknown_key_line", tinyIniWith("", kTinyWorld) + "\n[drone]\nsped = 2\n");
        cases.push_back({"unknown_key_line", ini, {"unknown_key_line.ini:11", "sped"}});
    }
    {
        const auto dir = freshDir("bad_world_file");
        std::ofstream(dir / "broken.yaml")
            << "name: broken\nexploration_box: {min: [0, 0, 0], max: [1, 1, 1]}\n"
               "starts: [[0.5, 0.5, 0.1]]\nboxes:\n  - {center: [0, 0], size: [1, 1, 1]}\n";
        const std::string ini =
            writeIni("bad_world_file", tinyIniWith("", (dir / "broken.yaml").string()));
        cases.push_back({"bad_world_file", ini, {"broken.yaml", "center"}});
    }
    {
        const auto dir = freshDir("start_inside");
        std::ofstream(dir / "blocked.yaml")
            << "name: blocked\nexploration_box: {min: [-3, -3, 0], max: [3, 3, 2]}\n"
               "starts: [[0, 0, 0.2]]\nboxes:\n"
               "  - {name: block, center: [0, 0, 0.5], size: [1, 1, 1]}\n";
        const std::string ini =
            writeIni("start_inside", tinyIniWith("", (dir / "blocked.yaml").string()));
        cases.push_back({"start_inside", ini, {"blocked.yaml", "starts[0]", "inside", "'block'"}});
    }
    return cases;
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(Errors, ExploreAppBadInput, ::testing::ValuesIn(badInputCases()),
                         [](const auto& testInfo) { return testInfo.param.name; });
