// End-to-end: the real daep-benchmark on the smoke config (4 short missions).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <utility>
#include <vector>

#include "RunApp.h"

namespace fs = std::filesystem;
using namespace daep::test;

namespace {

std::vector<std::string> lines(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);)
        out.push_back(line);
    return out;
}

std::string smokeConfig() {
    return std::string(DAEP_SOURCE_DIR) + "/config-ini/benchmark_smoke.ini";
}

/** Width and height from a PNG's IHDR chunk; {0, 0} if the file is not a PNG. */
std::pair<int, int> pngSize(const fs::path& file) {
    const std::string data = readText(file);
    if (data.size() < 24 || data.compare(1, 3, "PNG") != 0 || data.compare(12, 4, "IHDR") != 0)
        return {0, 0};
    auto be32 = [&data](std::size_t at) {
        int v = 0;
        for (std::size_t i = at; i < at + 4; ++i)
            v = v * 256 + static_cast<unsigned char>(data[i]);
        return v;
    };
    return {be32(16), be32(20)};
}

fs::file_time_type summaryTime(const fs::path& out, const std::string& run) {
    return fs::last_write_time(out / "runs" / run / "summary.json");
}

}  // namespace

TEST(BenchmarkApp, SmokeBenchmarkRunsAggregatesAndResumes) {
    const auto scratch = freshDir("benchmark");
    const auto out = scratch / "out";
    auto r = runApp(DAEP_BENCHMARK_BIN, smokeConfig() + " --jobs 2 --out " + out.string(), scratch);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("4 runs ok, 0 failed"), std::string::npos) << r.out;

    const auto csv = lines(readText(out / "results.csv"));
    ASSERT_EQ(csv.size(), 5u) << readText(out / "results.csv");
    EXPECT_EQ(csv[0].rfind("world,mode,planner,start,repetition,seed,status,exit_code,log,"
                           "coverage_percent,reachable_percent,exploration_time_s,path_length_m",
                           0),
              0u);
    for (const char* run :
         {"crosswalks,dynamic,aep,0,0,1,ok,0,", "crosswalks,dynamic,daep,0,0,1,ok,0,",
          "crosswalks,dynamic,dep,0,0,1,ok,0,", "crosswalks,dynamic,rhnbvp,0,0,1,ok,0,"}) {
        bool found = false;
        for (const auto& line : csv)
            found = found || line.rfind(run, 0) == 0;
        EXPECT_TRUE(found) << run;
    }
    const auto summary = readText(out / "runs/crosswalks_dynamic_aep_s0_r0/summary.json");
    EXPECT_NEAR(jsonNumber(summary, "exploration_time_s"), 30.0, 1e-6);  // [set] reached the run
    EXPECT_EQ(summary.find("\"planner\": \"aep\"") != std::string::npos, true) << summary;

    const std::string table = readText(out / "table.md");
    EXPECT_NE(table.find("| RH-NBVP | AEP | DEP | DAEP |"), std::string::npos) << table;
    for (const char* row :
         {"| **C %** |", "| **T s** |", "| **PL m** |", "| **PT s** |", "| **NOC** |"})
        EXPECT_NE(table.find(row), std::string::npos) << row;

    EXPECT_EQ(pngSize(out / "plots/coverage_crosswalks_dynamic.png"), std::make_pair(900, 520));
    for (const char* png :
         {"collisions_aep_crosswalks_dynamic.png", "collisions_rhnbvp_crosswalks_dynamic.png",
          "collisions_daep_crosswalks_dynamic.png"})
        EXPECT_EQ(pngSize(out / "plots" / png), std::make_pair(900, 360)) << png;
    // Every plot also as SVG and PDF.
    for (const char* stem : {"coverage_crosswalks_dynamic", "collisions_daep_crosswalks_dynamic"}) {
        EXPECT_EQ(readText(out / "plots" / (std::string(stem) + ".svg")).rfind("<?xml", 0), 0u);
        EXPECT_EQ(readText(out / "plots" / (std::string(stem) + ".pdf")).rfind("%PDF-", 0), 0u);
    }
    // The paper's Fig. 4 layout: coverage with bands over a collision timeline (4 runs, 4 rows).
    EXPECT_EQ(pngSize(out / "plots/fig4_crosswalks_dynamic.png"),
              std::make_pair(900, 34 + 440 + 110 + 4 * 16));
    EXPECT_EQ(readText(out / "plots/fig4_crosswalks_dynamic.pdf").rfind("%PDF-", 0), 0u);
    const std::string fig4 = readText(out / "plots/fig4_crosswalks_dynamic.svg");
    for (const char* text : {">crosswalks (dynamic)</text>", ">Coverage over time</text>",
                             ">Collision episodes</text>", ">DAEP (1 run)</text>",
                             ">RH-NBVP (1 run)</text>", ">time [s]</text>"})
        EXPECT_NE(fig4.find(text), std::string::npos) << text;
    for (const char* planner : {"RH-NBVP", "AEP", "DEP", "DAEP"}) {
        const std::string row = std::string(">") + planner + " s0 r0: ";
        EXPECT_NE(fig4.find(row), std::string::npos) << row;
    }

    // Second invocation: everything is done, nothing runs again.
    const auto before = summaryTime(out, "crosswalks_dynamic_rhnbvp_s0_r0");
    r = runApp(DAEP_BENCHMARK_BIN, smokeConfig() + " --jobs 2 --out " + out.string(), scratch);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("4 of 4 runs already done or failed"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("0 runs ok, 0 failed, 4 skipped"), std::string::npos) << r.out;
    EXPECT_EQ(summaryTime(out, "crosswalks_dynamic_rhnbvp_s0_r0"), before);

    // A crashed run (recorded exit code) is kept as failed, and re-run with --retry-failed.
    const auto crashed = out / "runs/crosswalks_dynamic_daep_s0_r0";
    std::ofstream(crashed / "exit_code") << "139\n";
    r = runApp(DAEP_BENCHMARK_BIN, "--aggregate " + out.string(), scratch);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(readText(out / "results.csv").find("crosswalks,dynamic,daep,0,0,1,failed,139,"),
              std::string::npos);
    r = runApp(DAEP_BENCHMARK_BIN, smokeConfig() + " --retry-failed --jobs 2 --out " + out.string(),
               scratch);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("1 runs ok, 0 failed, 3 skipped"), std::string::npos) << r.out;

    // --emit-jobs lists one shell command per pending run: none now, all in a fresh directory.
    const auto jobs = scratch / "jobs.txt";
    r = runApp(DAEP_BENCHMARK_BIN,
               smokeConfig() + " --out " + out.string() + " --emit-jobs " + jobs.string(), scratch);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_TRUE(lines(readText(jobs)).empty());
    const auto fresh = scratch / "fresh";
    r = runApp(DAEP_BENCHMARK_BIN,
               smokeConfig() + " --out " + fresh.string() + " --emit-jobs " + jobs.string(),
               scratch);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto commands = lines(readText(jobs));
    ASSERT_EQ(commands.size(), 4u);
    EXPECT_NE(commands[0].find(std::string(DAEP_EXPLORE_BIN) + " "), std::string::npos);
    EXPECT_NE(commands[0].find("--set experiment.max_time_s=30"), std::string::npos);
    EXPECT_NE(commands[0].find("--set experiment.planner=rhnbvp"), std::string::npos);
    EXPECT_NE(
        commands[0].find("--out " + (fresh / "runs/crosswalks_dynamic_rhnbvp_s0_r0").string()),
        std::string::npos)
        << commands[0];
    EXPECT_NE(commands[0].find("echo $? > "), std::string::npos);

    // One emitted command run by a shell, then aggregated, gives an ok row.
    ASSERT_EQ(std::system(commands[3].c_str()), 0);
    r = runApp(DAEP_BENCHMARK_BIN, "--aggregate " + fresh.string(), scratch);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string freshCsv = readText(fresh / "results.csv");
    EXPECT_NE(freshCsv.find("crosswalks,dynamic,daep,0,0,1,ok,0,"), std::string::npos) << freshCsv;
    EXPECT_NE(freshCsv.find("crosswalks,dynamic,aep,0,0,1,pending,"), std::string::npos)
        << freshCsv;
    fs::remove_all(scratch);
}

TEST(BenchmarkApp, BadConfigIsExitOneNamingFileAndLine) {
    const auto scratch = freshDir("benchmark_bad");
    std::ofstream(scratch / "bad.ini") << "[benchmark]\nplanners = aep\nfoo = 1\n";
    const auto r = runApp(DAEP_BENCHMARK_BIN, (scratch / "bad.ini").string(), scratch);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("bad.ini:3: unknown key [benchmark] foo"), std::string::npos) << r.err;
    fs::remove_all(scratch);
}

TEST(BenchmarkApp, LoadKeepsThreadsBusyBesideTheRunsAndIsRecorded) {
    const auto scratch = freshDir("benchmark_load");
    const auto out = scratch / "out";
    auto r = runApp(DAEP_BENCHMARK_BIN,
                    smokeConfig() + " --set benchmark.planners=daep --set experiment.max_time_s=5" +
                        " --jobs 1 --load 1 --out " + out.string(),
                    scratch);
    ASSERT_EQ(r.exitCode, 0) << r.out << r.err;
    EXPECT_NE(r.out.find("1 at a time beside 1 busy thread, into"), std::string::npos) << r.out;
    const std::string spec = readText(out / "runs" / "crosswalks_dynamic_daep_s0_r0" / "run.json");
    EXPECT_NE(spec.find("\"cpu_load_threads\": 1"), std::string::npos) << spec;
    EXPECT_NE(readText(out / "table.md").find("1 run with 1 busy thread."), std::string::npos)
        << readText(out / "table.md");

    r = runApp(DAEP_BENCHMARK_BIN, smokeConfig() + " --load -1 --out " + out.string(), scratch);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("--load: '-1' is not an integer from 0 to 1024"), std::string::npos)
        << r.err;
    fs::remove_all(scratch);
}
