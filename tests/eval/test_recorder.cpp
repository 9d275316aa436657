#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "daep/eval/RunRecorder.h"
#include "daep/eval/Statistics.h"

namespace fs = std::filesystem;
using namespace daep::eval;

namespace {
std::string readText(const fs::path& p) {
    std::ifstream f(p);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}
fs::path tempDir(const std::string& name) {
    return fs::temp_directory_path() / ("daep_eval_" + std::to_string(::getpid()) + "_" + name);
}
}  // namespace

TEST(Statistics, PercentileInterpolatesLinearly) {
    EXPECT_DOUBLE_EQ(median({3, 1, 2}), 2.0);
    EXPECT_DOUBLE_EQ(median({1, 2, 3, 4}), 2.5);
    EXPECT_DOUBLE_EQ(percentile({0, 10}, 95), 9.5);
    EXPECT_DOUBLE_EQ(percentile({5}, 95), 5.0);
    EXPECT_DOUBLE_EQ(percentile({}, 50), 0.0);
    EXPECT_DOUBLE_EQ(percentile({1, 2, 3}, 100), 3.0);
    EXPECT_DOUBLE_EQ(mean({1, 2, 3, 6}), 3.0);
}

TEST(Json, StringsAreEscaped) {
    EXPECT_EQ(jsonString("a\"b\\c\nd"), "\"a\\\"b\\\\c\\nd\"");
}

TEST(RunRecorder, WritesCsvRowsAndSummaryWithAllKeys) {
    const auto dir = tempDir("rec");
    fs::remove_all(dir);
    {
        RunRecorder rec((dir / "nested").string());
        rec.addSample({0.0, 1.5, 0.0, 0.0, 0});
        rec.addSample({1.0, 2.25, 0.5, 0.05, 1});
        daep::FlatPose p;
        p.position = {1, 2, 3};
        p.yaw = 0.5;
        rec.addPose(0.1, p);
        rec.addPlan(0.0, 0.05, 0.001, "path", 12.5, 1);
        rec.addCollision(2, 10.0, 11.5);
        CollisionKnowledge lost;
        lost.tracked = 0;
        lost.untrackedFor = 12.34;
        lost.unseenWatch = "open";
        rec.addCollision(1, 20.0, 20.5, lost);
        CollisionKnowledge found;
        found.tracked = 1;
        found.trackedFor = 0.2;
        found.unseenWatch = "cleared";
        rec.addCollision(3, 30.0, 31.0, found);
        RunSummary s;
        s.coveragePercent = 42.125;
        s.collisions = 3;
        s.finished = true;
        s.endReason = EndReason::plannerFinished("no frontiers left");
        s.labels = {{"world", "cafe"}};
        rec.flush();
        rec.writeSummary(s);
        rec.writeCollisions();
        rec.writeTiming(2.0, 100.0, {{"render", 0.5}, {"map", 1.25}});
    }
    const auto ts = readText(dir / "nested" / "timeseries.csv");
    EXPECT_EQ(ts,
              "t,coverage_percent,path_length_m,planning_time_s,collisions\n"
              "0.000,1.5000,0.0000,0.0000,0\n1.000,2.2500,0.5000,0.0500,1\n");
    EXPECT_EQ(readText(dir / "nested" / "trajectory.csv"),
              "sim_time,x,y,z,yaw\n0.100,1.0000,2.0000,3.0000,0.5000\n");
    const auto summary = readText(dir / "nested" / "summary.json");
    for (const char* key :
         {"\"world\": \"cafe\"", "\"coverage_percent\": 42.1250", "\"collisions\": 3",
          "\"finished\": true", "\"plan_ms_median\"", "\"plan_ms_p95\"", "\"wall_time_s\"",
          "\"static_collisions\"", "\"iterations\"", "\"exploration_time_s\"", "\"path_length_m\"",
          "\"planning_time_s\"", "\"end_reason\": \"planner finished: no frontiers left\""})
        EXPECT_NE(summary.find(key), std::string::npos) << key;
    EXPECT_EQ(summary.find("reachable_percent"), std::string::npos);  // unset: not written
    EXPECT_EQ(readText(dir / "nested" / "collisions.csv"),
              "person,start_s,end_s,tracked,unseen_watch,tracked_for_s,untracked_for_s\n"
              "2,10.000,11.500,-1,-,-,-\n1,20.000,20.500,0,open,-,12.3\n"
              "3,30.000,31.000,1,cleared,0.2,-\n");
    const std::string timing = readText(dir / "nested" / "timing.json");
    EXPECT_NE(timing.find("\"speedup_vs_real_time\": 50.00,"), std::string::npos) << timing;
    EXPECT_NE(timing.find("\"wall_time_by_stage_s\": {\"render\": 0.500, \"map\": 1.250}"),
              std::string::npos)
        << timing;
    fs::remove_all(dir);
}

TEST(RunRecorder, WritesTheReachableBoundNextToTheCoverage) {
    const auto dir = tempDir("rec_reach");
    {
        RunRecorder rec(dir.string());
        RunSummary s;
        s.coveragePercent = 42.125;
        s.reachablePercent = 97.5;
        rec.writeSummary(s);
    }
    EXPECT_NE(readText(dir / "summary.json")
                  .find("\"coverage_percent\": 42.1250,\n  \"reachable_percent\": 97.5000,\n"),
              std::string::npos)
        << readText(dir / "summary.json");
    fs::remove_all(dir);
}

TEST(RunRecorder, SummaryEndsWithTheProvenanceBlock) {
    const auto dir = tempDir("rec_provenance");
    {
        RunRecorder rec(dir.string());
        RunSummary s;
        s.wallTime = 1.5;
        s.provenance = {"node7", "2026-12-02T02:16:33Z", "daep-explore 'a b.ini' --quiet"};
        rec.writeSummary(s);
    }
    const std::string summary = readText(dir / "summary.json");
    const daep::BuildInfo& b = daep::buildInfo();
    const std::string expected =
        "  \"wall_time_s\": 1.500,\n  \"provenance\": {\n"
        "    \"version\": \"" +
        b.version +
        "\",\n"
        "    \"git_commit\": \"" +
        b.gitCommit +
        "\",\n"
        "    \"git_dirty\": " +
        (b.gitDirty ? "true" : "false") +
        ",\n"
        "    \"build_type\": \"" +
        b.buildType + "\",\n";
    EXPECT_NE(summary.find(expected), std::string::npos) << summary;
    for (const char* line :
         {"    \"host\": \"node7\",\n", "    \"date_utc\": \"2026-12-02T02:16:33Z\",\n",
          "    \"command_line\": \"daep-explore 'a b.ini' --quiet\"\n  }\n}\n",
          "    \"libraries\": {\"MRPT\": \""})
        EXPECT_NE(summary.find(line), std::string::npos) << line << summary;
    fs::remove_all(dir);
}

TEST(RunRecorder, UnwritableDirectoryIsAClearError) {
    try {
        RunRecorder rec("/proc/daep_cannot_write_here");
        FAIL() << "expected an exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("/proc/daep_cannot_write_here"), std::string::npos);
    }
}
