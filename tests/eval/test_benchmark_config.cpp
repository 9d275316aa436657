#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>

#include "daep/common/Error.h"
#include "daep/eval/BenchmarkConfig.h"
#include "daep/eval/BenchmarkResults.h"
#include "daep/eval/BenchmarkRunner.h"

namespace fs = std::filesystem;
using namespace daep::eval;

namespace {

class BenchmarkConfigTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("daep_benchcfg_" + std::to_string(::getpid()));
        fs::create_directories(dir_);
        std::ofstream(dir_ / "base.ini") << "[experiment]\nworld = cafe\n";
    }
    void TearDown() override { fs::remove_all(dir_); }

    std::string write(const std::string& text) {
        const auto path = dir_ / "bench.ini";
        std::ofstream(path) << text;
        return path.string();
    }

    /** The InputError message of loading `text`, or "" if it loads. */
    std::string errorOf(const std::string& text, const std::vector<std::string>& sets = {}) {
        try {
            loadBenchmarkConfig(write(text), sets);
        } catch (const daep::InputError& e) {
            return e.what();
        }
        return "";
    }

    fs::path dir_;
};

const char* kValid =
    "# comment\n"
    "[benchmark]\n"
    "planners = rhnbvp, aep   # two planners\n"
    "worlds = crosswalks,cafe\n"
    "modes = dynamic\n"
    "starts = 0-1,3\n"
    "repetitions = 2\n"
    "seed = 10\n"
    "experiment = base.ini\n"
    "\n"
    "[set]\n"
    "experiment.max_time_s = 30\n";

}  // namespace

TEST_F(BenchmarkConfigTest, ExpandsTheMatrixWithDeterministicSeeds) {
    const auto cfg = loadBenchmarkConfig(write(kValid));
    EXPECT_EQ(cfg.planners, (std::vector<std::string>{"rhnbvp", "aep"}));
    EXPECT_EQ(cfg.worlds, (std::vector<std::string>{"crosswalks", "cafe"}));
    EXPECT_EQ(cfg.starts, (std::vector<int>{0, 1, 3}));
    EXPECT_EQ(cfg.experiment, fs::weakly_canonical(dir_ / "base.ini").string());
    ASSERT_EQ(cfg.sets.size(), 1u);
    EXPECT_EQ(cfg.sets[0].first, "experiment.max_time_s");
    EXPECT_EQ(cfg.sets[0].second, "30");

    const auto runs = cfg.expand();
    ASSERT_EQ(runs.size(), 2u * 2u * 1u * 3u * 2u);
    EXPECT_EQ(runs.front().id(), "crosswalks_dynamic_rhnbvp_s0_r0");
    EXPECT_EQ(runs.front().seed, 10);
    EXPECT_EQ(runs[1].id(), "crosswalks_dynamic_rhnbvp_s0_r1");
    EXPECT_EQ(runs[1].seed, 11);
    EXPECT_EQ(runs.back().id(), "cafe_dynamic_aep_s3_r1");
    EXPECT_EQ(runs.back().seed, 11);
}

TEST_F(BenchmarkConfigTest, CommandLineOverridesReplaceBenchmarkKeysAndAddRunSettings) {
    const auto cfg =
        loadBenchmarkConfig(write(kValid), {"benchmark.planners=dep", "benchmark.starts=4",
                                            "experiment.max_time_s=60", "rhnbvp.zero_gain=0"});
    EXPECT_EQ(cfg.planners, (std::vector<std::string>{"dep"}));
    EXPECT_EQ(cfg.starts, (std::vector<int>{4}));
    ASSERT_EQ(cfg.sets.size(), 2u);
    EXPECT_EQ(cfg.sets[0].second, "60");
    EXPECT_EQ(cfg.sets[1].first, "rhnbvp.zero_gain");
}

TEST_F(BenchmarkConfigTest, RemembersWhereEachKeyWasGiven) {
    const std::string file = (dir_ / "bench.ini").string();
    const auto cfg = loadBenchmarkConfig(write(kValid), {"benchmark.starts=4", "camera.width=9"});
    EXPECT_EQ(cfg.where("planners"), file + ":3");
    EXPECT_EQ(cfg.where("starts"), "--set benchmark.starts");
    EXPECT_EQ(cfg.where("experiment.max_time_s"), file + ":12");
    EXPECT_EQ(cfg.where("camera.width"), "--set camera.width");
    const auto overrides = cfg.runOverrides(cfg.expand().front());
    EXPECT_EQ(overrides.front(), "experiment.max_time_s=30");
    EXPECT_EQ(overrides.back(), "experiment.seed=10");
}

TEST_F(BenchmarkConfigTest, ARunRunsAgainWhenItsInputsChanged) {
    const auto cfg =
        loadBenchmarkConfig(write(kValid), {"benchmark.planners=aep", "benchmark.worlds=cafe",
                                            "benchmark.starts=0", "benchmark.repetitions=1"});
    RunSpec before = cfg.expand().front();
    before.inputs = {"[experiment]\nmax_time_s = 30\n\n", {{"cafe.yaml", "aaa"}}, "d1"};
    RunnerOptions options;
    options.outDirectory = (dir_ / "out").string();
    options.exploreBinary = "/bin/true";
    const BenchmarkRunner previous(cfg, options, {before});
    const fs::path runDir = previous.runDirectory(before);
    writeRunSpec(runDir.string(), before);
    std::ofstream(runDir / "config.ini") << before.inputs.parameters;
    std::ofstream(runDir / "exit_code") << "0\n";
    std::ofstream(runDir / "summary.json") << "{\"coverage_percent\": 1}\n";
    EXPECT_EQ(previous.changeSinceLastRun(before), "");
    EXPECT_TRUE(previous.pendingRuns().empty());

    RunSpec now = before;
    now.inputs = {"[experiment]\nmax_time_s = 60\n\n", {{"cafe.yaml", "aaa"}}, "d2"};
    const BenchmarkRunner changedParameter(cfg, options, {now});
    EXPECT_EQ(changedParameter.changeSinceLastRun(now), "[experiment] max_time_s: 30 -> 60");
    EXPECT_EQ(changedParameter.pendingRuns().size(), 1u);

    now.inputs = {before.inputs.parameters, {{"cafe.yaml", "bbb"}}, "d3"};
    const BenchmarkRunner changedWorld(cfg, options, {now});
    EXPECT_EQ(changedWorld.changeSinceLastRun(now), "world file cafe.yaml changed");
    EXPECT_EQ(changedWorld.pendingRuns().size(), 1u);

    // A failed run is kept without --retry-failed, unless its inputs changed.
    std::ofstream(runDir / "exit_code") << "2\n";
    EXPECT_TRUE(previous.pendingRuns().empty());
    EXPECT_EQ(changedWorld.pendingRuns().size(), 1u);
}

TEST_F(BenchmarkConfigTest, ErrorsNameFileLineAndKey) {
    const std::string file = (dir_ / "bench.ini").string();
    std::string text = kValid;
    text.insert(text.find("seed"), "color = red\n");
    EXPECT_EQ(errorOf(text), file + ":8: unknown key [benchmark] color");

    EXPECT_EQ(errorOf(std::string(kValid) + "[runs]\n"), file +
                                                             ":13: unknown section [runs] "
                                                             "(expected [benchmark] or [set])");
    text = kValid;
    text.erase(text.find("repetitions"), std::string("repetitions = 2\n").size());
    EXPECT_EQ(errorOf(text), file + ": missing required key [benchmark] repetitions");

    text = kValid;
    text.replace(text.find("0-1,3"), 5, "3-1");
    EXPECT_EQ(errorOf(text), file + ":6: [benchmark] starts: bad range '3-1'");

    text = kValid;
    text.replace(text.find("dynamic"), 7, "windy");
    EXPECT_NE(errorOf(text).find(file + ":5: [benchmark] modes"), std::string::npos);

    EXPECT_NE(errorOf(kValid, {"benchmark.nope=1"}).find("--set benchmark.nope"),
              std::string::npos);
    EXPECT_NE(errorOf(std::string(kValid) + "experiment.planner = aep\n")
                  .find(file + ":13: experiment.planner is set per run"),
              std::string::npos);
    text = kValid;
    text.replace(text.find("base.ini"), 8, "missing.ini");
    EXPECT_NE(errorOf(text).find(file + ":9: [benchmark] experiment: no such file"),
              std::string::npos);
    text = kValid;
    text.insert(text.find("seed"), "seed = 3\n");
    EXPECT_NE(errorOf(text).find(file + ":9: duplicate key [benchmark] seed"), std::string::npos);
}

// Found by fuzz_benchmark_config: seed + repetition overflowed an int in expand(), and a huge
// matrix or start range exhausted memory (or took hours) before any run started.
TEST_F(BenchmarkConfigTest, RejectsMatricesBeyondAnIntOrAMillionRuns) {
    const std::string file = (dir_ / "bench.ini").string();
    std::string text = kValid;
    text.replace(text.find("seed = 10"), 9, "seed = 2147483647");
    EXPECT_EQ(errorOf(text), file + ":8: [benchmark] seed: seed + repetitions - 1 must fit an int");
    EXPECT_EQ(errorOf(kValid, {"benchmark.repetitions=100000"}),
              "--set benchmark.repetitions: [benchmark] repetitions: the matrix has 1200000 runs "
              "(at most 1000000)");
    EXPECT_EQ(errorOf(kValid, {"benchmark.starts=0-2147483647"}),
              "--set benchmark.starts: [benchmark] starts: more than 10000 values");
    const auto cfg = loadBenchmarkConfig(
        write(kValid), {"benchmark.starts=2147483647", "benchmark.seed=2147483646"});
    EXPECT_EQ(cfg.starts, (std::vector<int>{2147483647}));
    EXPECT_EQ(cfg.expand().back().seed, 2147483647);
}

TEST(BenchmarkIntList, ParsesRangesAndListsAndRejectsJunk) {
    EXPECT_EQ(parseIntList("0-4"), (std::vector<int>{0, 1, 2, 3, 4}));
    EXPECT_EQ(parseIntList("0, 2"), (std::vector<int>{0, 2}));
    EXPECT_EQ(parseIntList("2"), (std::vector<int>{2}));
    EXPECT_THROW(parseIntList(""), daep::InputError);
    EXPECT_THROW(parseIntList("a"), daep::InputError);
    EXPECT_THROW(parseIntList("1,1"), daep::InputError);
    EXPECT_THROW(parseIntList("-1"), daep::InputError);
    EXPECT_THROW(parseIntList("1-2x"), daep::InputError);
}

TEST(BenchmarkShellQuote, QuotesOnlyWhatNeedsIt) {
    EXPECT_EQ(shellQuote("/a/b-c.ini"), "/a/b-c.ini");
    EXPECT_EQ(shellQuote("experiment.max_time_s=30"), "experiment.max_time_s=30");
    EXPECT_EQ(shellQuote("a b"), "'a b'");
    EXPECT_EQ(shellQuote("it's"), "'it'\\''s'");
    EXPECT_EQ(shellQuote(""), "''");
    EXPECT_EQ(shellQuote("$HOME"), "'$HOME'");
}
