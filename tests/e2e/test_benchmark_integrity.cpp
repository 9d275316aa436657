// End-to-end: daep-benchmark's resume rule follows the runs' inputs, the matrix is checked
// before anything is launched, and every output says which build made it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "RunApp.h"

namespace fs = std::filesystem;
using namespace daep::test;

namespace {

/** A one-run benchmark of the tiny room, with its experiment and world copied beside it. */
fs::path writeTinyBenchmark(const fs::path& dir, const std::string& planners = "rhnbvp") {
    fs::copy_file(kTinyIni, dir / "tiny_room.ini", fs::copy_options::overwrite_existing);
    fs::copy_file(std::string(DAEP_E2E_DATA) + "/tiny_room.yaml", dir / "tiny_room.yaml",
                  fs::copy_options::overwrite_existing);
    const auto ini = dir / "bench.ini";
    std::ofstream(ini) << "[benchmark]\n"
                       << "planners = " << planners << "\n"
                       << "worlds = tiny_room.yaml\n"
                       << "modes = dynamic\n"
                       << "starts = 0\n"
                       << "repetitions = 1\n"
                       << "seed = 1\n"
                       << "experiment = tiny_room.ini\n"
                       << "\n[set]\n"
                       << "experiment.max_time_s = 4\n"
                       << "output.scene = false\n";
    return ini;
}

const char* kRun = "runs/tiny-room.yaml_dynamic_rhnbvp_s0_r0";

AppResult benchmark(const fs::path& ini, const fs::path& out, const std::string& extra,
                    const fs::path& scratch) {
    return runApp(DAEP_BENCHMARK_BIN, ini.string() + " --jobs 1 --out " + out.string() + extra,
                  scratch);
}

}  // namespace

TEST(BenchmarkIntegrity, ResumeReRunsExactlyTheRunsWhoseInputsChanged) {
    const auto dir = freshDir("bench_resume");
    const auto ini = writeTinyBenchmark(dir);
    const auto out = dir / "out";
    auto r = benchmark(ini, out, "", dir);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NEAR(jsonNumber(readText(out / kRun / "summary.json"), "exploration_time_s"), 4.0, 1e-6);

    // Nothing changed: skipped.
    r = benchmark(ini, out, "", dir);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("0 runs ok, 0 failed, 1 skipped"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("re-run"), std::string::npos) << r.out;

    // A changed parameter: the run runs again, and the output says why.
    r = benchmark(ini, out, " --set experiment.max_time_s=6", dir);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("re-run  tiny-room.yaml_dynamic_rhnbvp_s0_r0: [experiment] max_time_s: 4 "
                         "-> 6"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("1 runs ok, 0 failed, 0 skipped"), std::string::npos) << r.out;
    EXPECT_NEAR(jsonNumber(readText(out / kRun / "summary.json"), "exploration_time_s"), 6.0, 1e-6);
    EXPECT_NE(readText(out / "results.csv").find(",6.000,"), std::string::npos);

    // The world file's content changed (its name and the parameters did not).
    std::ofstream(dir / "tiny_room.yaml", std::ios::app) << "# edited\n";
    r = benchmark(ini, out, " --set experiment.max_time_s=6", dir);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("re-run  tiny-room.yaml_dynamic_rhnbvp_s0_r0: world file tiny_room.yaml "
                         "changed"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("1 runs ok, 0 failed, 0 skipped"), std::string::npos) << r.out;

    // A changed base experiment (a key outside [set]) counts too.
    std::ofstream(dir / "tiny_room.ini", std::ios::app) << "\n[map]\nmax_range = 4.5\n";
    r = benchmark(ini, out, " --set experiment.max_time_s=6", dir);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("[map] max_range: 5.0 -> 4.5"), std::string::npos) << r.out;

    // The run directory records the digest it ran with.
    const std::string runJson = readText(out / kRun / "run.json");
    EXPECT_NE(runJson.find("\"params_digest\": \""), std::string::npos) << runJson;
    EXPECT_NE(runJson.find("\"tiny_room.yaml\": \""), std::string::npos) << runJson;
    fs::remove_all(dir);
}

TEST(BenchmarkIntegrity, BadMatrixIsRejectedBeforeAnythingIsLaunched) {
    const auto dir = freshDir("bench_check");
    const auto ini = writeTinyBenchmark(dir);
    const auto out = dir / "out";
    const struct {
        std::string args, message;
    } cases[] = {
        {" --set benchmark.planners=aep,foo",
         "--set benchmark.planners: [benchmark] planners: unknown planner 'foo'"},
        {" --set benchmark.worlds=atlantis",
         "--set benchmark.worlds: [benchmark] worlds: world 'atlantis'"},
        {" --set benchmark.starts=0-9",
         "--set benchmark.starts: [benchmark] starts: start 5 is out of range 0..4"},
        {" --set experiment.max_tme_s=3",
         "--set experiment.max_tme_s: unknown key 'experiment.max_tme_s'"},
        {" --set experiment.max_time_s=abc",
         "--set experiment.max_time_s: [experiment] max_time_s: 'abc' is not a number"},
    };
    for (const auto& c : cases) {
        const auto r = benchmark(ini, out, c.args, dir);
        EXPECT_EQ(r.exitCode, 1) << c.args << "\n" << r.out << r.err;
        EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // one line
        EXPECT_FALSE(fs::exists(out)) << c.args << ": something was launched";
    }
    // The same errors from the file name its line.
    std::ofstream(ini, std::ios::app) << "experiment.max_tme_s = 3\n";
    const auto r = benchmark(ini, out, "", dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("bench.ini:13: unknown key 'experiment.max_tme_s'"), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(out));
    fs::remove_all(dir);
}

TEST(BenchmarkIntegrity, EveryOutputSaysWhichBuildMadeIt) {
    const auto dir = freshDir("bench_provenance");
    const auto ini = writeTinyBenchmark(dir);
    const auto out = dir / "out";
    const auto r = benchmark(ini, out, "", dir);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;

    const std::string summary = readText(out / kRun / "summary.json");
    for (const char* field :
         {"\"provenance\": {", "\"version\": \"", "\"git_commit\": \"",
          "\"git_dirty\": ", "\"build_type\": \"", "\"compiler\": \"",
          "\"libraries\": {\"MRPT\": \"", "\"OctoMap\": \"", "\"Embree\": \"", "\"OpenCV\": \"",
          "\"host\": \"", "\"date_utc\": \"20", "\"command_line\": \""})
        EXPECT_NE(summary.find(field), std::string::npos) << field << "\n" << summary;
    EXPECT_NE(summary.find("--set experiment.planner=rhnbvp"), std::string::npos) << summary;

    const std::string csv = readText(out / "results.csv");
    const std::string header = csv.substr(0, csv.find('\n'));
    EXPECT_NE(header.find(",version,git_commit,git_dirty,build_type,host,date_utc,cpu_load_threads,"
                          "params_digest"),
              std::string::npos)
        << header;

    const std::string table = readText(out / "table.md");
    EXPECT_NE(table.find("Made by daep "), std::string::npos) << table;
    EXPECT_NE(table.find("MRPT "), std::string::npos) << table;
    EXPECT_EQ(table.find("Mixed builds"), std::string::npos) << table;

    // A run made by another build is kept, reported per run and flagged in table.md.
    std::string edited = summary;
    const auto at = edited.find("\"git_commit\": \"") + 15;
    edited.replace(at, 7, "0000000");
    std::ofstream(out / kRun / "summary.json") << edited;
    const auto again = benchmark(ini, out, "", dir);
    ASSERT_EQ(again.exitCode, 0) << again.out << again.err;
    EXPECT_NE(again.out.find("kept    tiny-room.yaml_dynamic_rhnbvp_s0_r0: parameters unchanged, "
                             "made by build"),
              std::string::npos)
        << again.out;
    EXPECT_NE(readText(out / "table.md").find("Made by daep "), std::string::npos);
    fs::remove_all(dir);
}

TEST(BenchmarkIntegrity, MixedBuildsAreFlaggedInTheTable) {
    const auto dir = freshDir("bench_mixed");
    const auto ini = writeTinyBenchmark(dir, "rhnbvp, dep");
    const auto out = dir / "out";
    auto r = benchmark(ini, out, "", dir);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    const auto file = out / kRun / "summary.json";
    std::string summary = readText(file);
    const auto at = summary.find("\"git_commit\": \"") + 15;
    summary.replace(at, 7, "0000000");
    std::ofstream(file) << summary;
    r = runApp(DAEP_BENCHMARK_BIN, "--aggregate " + out.string(), dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string table = readText(out / "table.md");
    EXPECT_NE(table.find("**Mixed builds**: these runs were made by 2 different builds"),
              std::string::npos)
        << table;
    EXPECT_NE(table.find("0000000"), std::string::npos) << table;
    fs::remove_all(dir);
}

TEST(BenchmarkIntegrity, AggregatingAMissingFolderSaysSo) {
    const auto dir = freshDir("bench_aggregate_missing");
    auto r = runApp(DAEP_BENCHMARK_BIN, "--aggregate " + (dir / "nothing").string(), dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find((dir / "nothing").string() + ": no such folder"), std::string::npos)
        << r.err;
    fs::create_directories(dir / "empty");
    r = runApp(DAEP_BENCHMARK_BIN, "--aggregate " + (dir / "empty").string(), dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("no runs in this folder"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "empty" / "results.csv"));
    fs::remove_all(dir);
}
