#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "daep/common/Error.h"
#include "daep/eval/BenchmarkResults.h"
#include "daep/eval/Plot.h"

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
    const auto dir =
        fs::temp_directory_path() / ("daep_benchres_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

/** A hand-written run directory: run.json, exit_code, summary.json and a short timeseries. */
void writeRun(const fs::path& root, const RunSpec& spec, int exitCode, double coverage, double time,
              int collisions) {
    const auto dir = root / "runs" / spec.id();
    writeRunSpec(dir.string(), spec);
    std::ofstream(dir / kExitCodeFile) << exitCode << "\n";
    if (exitCode != 0)
        return;
    std::ofstream(dir / "summary.json")
        << "{\n  \"mode\": \"" << spec.mode << "\",\n  \"planner\": \"" << spec.planner
        << "\",\n  \"world\": \"" << spec.world << "\",\n  \"coverage_percent\": " << coverage
        << ",\n  \"exploration_time_s\": " << time << ",\n  \"path_length_m\": " << time / 10
        << ",\n  \"planning_time_s\": 1.5,\n  \"collisions\": " << collisions
        << ",\n  \"finished\": true,\n  \"end_reason\": \"planner finished\"\n}\n";
    std::ofstream ts(dir / "timeseries.csv");
    ts << "t,coverage_percent,path_length_m,planning_time_s,collisions\n";
    for (int t = 0; t <= 10; ++t)
        ts << t << ".000," << coverage * t / 10 << ",0,0,0\n";
    std::ofstream(dir / "collisions.csv") << "person,start_s,end_s\n0,2.0,3.5\n1,7.0,7.4\n";
}

}  // namespace

TEST(BenchmarkResults, ParsesFlatJson) {
    const auto kv = parseFlatJson("{ \"a\": \"x \\\"y\\\"\", \"b\": 1.50,\"c\":true }");
    ASSERT_EQ(kv.size(), 3u);
    EXPECT_EQ(kv[0].second, "x \"y\"");
    EXPECT_EQ(kv[1].second, "1.50");
    EXPECT_EQ(kv[2].first, "c");
    EXPECT_EQ(kv[2].second, "true");
    EXPECT_THROW(parseFlatJson("{\"a\" 1}"), std::runtime_error);
    EXPECT_THROW(parseFlatJson("{\"a\": 1"), std::runtime_error);
    EXPECT_THROW(parseFlatJson("[1, 2]"), std::runtime_error);
}

TEST(BenchmarkResults, FlattensNestedObjectsWithDottedKeys) {
    const auto kv = parseFlatJson(
        "{\"c\": 12.3400, \"provenance\": {\"git_dirty\": false, \"libraries\": {\"MRPT\": "
        "\"2.5.8\"}, \"n\": -3}, \"list\": [1, \"x\"], \"z\": null}");
    const std::vector<std::pair<std::string, std::string>> expected = {
        {"c", "12.3400"},
        {"provenance.git_dirty", "false"},
        {"provenance.libraries.MRPT", "2.5.8"},
        {"provenance.n", "-3"},
        {"list[0]", "1"},
        {"list[1]", "x"},
        {"z", "null"}};
    EXPECT_EQ(kv, expected);
}

TEST(BenchmarkResults, ProvenanceGoesToItsColumnsAndTheTableHeader) {
    const auto root = tempDir("provenance");
    const RunSpec a{"wa", "dynamic", "aep", 0, 0, 1, {}}, b{"wa", "dynamic", "dep", 0, 0, 1, {}};
    writeRun(root, a, 0, 80, 100, 0);
    writeRun(root, b, 0, 70, 100, 0);
    auto addProvenance = [&root](const RunSpec& spec, const std::string& commit) {
        const auto file = root / "runs" / spec.id() / "summary.json";
        std::string text = readText(file);
        text.replace(text.rfind("\n}"), 3,
                     ",\n  \"provenance\": {\n    \"version\": \"1.2.3\",\n    \"git_commit\": \"" +
                         commit +
                         "\",\n    \"git_dirty\": true,\n    \"build_type\": \"Release\",\n"
                         "    \"compiler\": \"GNU 12\",\n    \"sanitizers\": \"\",\n"
                         "    \"libraries\": {\"MRPT\": \"2.5.8\"},\n    \"host\": \"node1\",\n"
                         "    \"date_utc\": \"2026-01-02T03:04:05Z\",\n"
                         "    \"command_line\": \"daep-explore x.ini\"\n  }\n}");
        std::ofstream(file) << text;
    };
    addProvenance(a, "1111111aaaa");
    addProvenance(b, "1111111aaaa");
    EXPECT_EQ(aggregateBenchmark(root.string()), 2u);
    const std::string csv = readText(root / "results.csv");
    EXPECT_NE(csv.find(",version,git_commit,git_dirty,build_type,host,date_utc,cpu_load_threads,"
                       "params_digest\n"),
              std::string::npos)
        << csv;
    EXPECT_NE(csv.find(",1.2.3,1111111aaaa,true,Release,node1,2026-01-02T03:04:05Z,0,\n"),
              std::string::npos)
        << csv;
    std::string table = readText(root / "table.md");
    EXPECT_NE(table.find("Made by daep 1.2.3 1111111-dirty (Release, GNU 12; MRPT 2.5.8) (2 runs)"),
              std::string::npos)
        << table;
    EXPECT_NE(table.find("On node1 (2), 2026-01-02T03:04:05Z to 2026-01-02T03:04:05Z."),
              std::string::npos)
        << table;
    EXPECT_EQ(table.find("Mixed builds"), std::string::npos);
    EXPECT_EQ(table.find("Under load"), std::string::npos);
    // The metrics do not take the provenance for theirs.
    EXPECT_EQ(readRuns(root.string())[0].metrics.size(), 7u);

    writeRun(root, b, 0, 70, 100, 0);
    addProvenance(b, "2222222bbbb");
    aggregateBenchmark(root.string());
    table = readText(root / "table.md");
    EXPECT_NE(table.find("**Mixed builds**: these runs were made by 2 different builds"),
              std::string::npos)
        << table;
    EXPECT_NE(table.find("- daep 1.2.3 2222222-dirty"), std::string::npos) << table;
    fs::remove_all(root);
}

TEST(BenchmarkResults, RunsUnderLoadAreCountedInTheTableAndColumn) {
    const auto root = tempDir("load");
    const RunSpec a{"wa", "dynamic", "aep", 0, 0, 1, {}}, b{"wa", "dynamic", "aep", 1, 0, 1, {}};
    writeRun(root, a, 0, 80, 100, 0);
    writeRun(root, b, 0, 70, 100, 0);
    writeRunSpec((root / "runs" / b.id()).string(), b, 2);
    EXPECT_EQ(readRun((root / "runs" / b.id()).string()).loadThreads, 2);
    aggregateBenchmark(root.string());
    const std::string table = readText(root / "table.md");
    EXPECT_NE(table.find("**Under load** (`daep-benchmark --load N`: N threads kept busy beside "
                         "the runs): 1 run with 0 busy threads, 1 run with 2 busy threads."),
              std::string::npos)
        << table;
    const std::string csv = readText(root / "results.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3);
    EXPECT_NE(csv.find(",0,\n"), std::string::npos) << csv;  // no digest in these runs
    EXPECT_NE(csv.find(",2,\n"), std::string::npos) << csv;
    fs::remove_all(root);
}

TEST(BenchmarkResults, AggregatingAMissingOrEmptyFolderIsAnInputError) {
    const auto root = tempDir("missing");
    try {
        aggregateBenchmark((root / "nope").string());
        FAIL() << "expected an InputError";
    } catch (const daep::InputError& e) {
        EXPECT_EQ(std::string(e.what()), (root / "nope").string() + ": no such folder");
    }
    EXPECT_THROW(aggregateBenchmark(root.string()), daep::InputError);
    fs::remove_all(root);
}

TEST(BenchmarkResults, TableIsMeanAndStdOverWorldsOfPerWorldMeans) {
    const auto root = tempDir("table");
    // AEP: world A runs C = 80, 90 (mean 85); world B: 60 -> over worlds mean 72.5, std 17.68.
    writeRun(root, {"wa", "dynamic", "aep", 0, 0, 1, {}}, 0, 80, 100, 2);
    writeRun(root, {"wa", "dynamic", "aep", 1, 0, 1, {}}, 0, 90, 200, 4);
    writeRun(root, {"wb", "dynamic", "aep", 0, 0, 1, {}}, 0, 60, 300, 0);
    // DEP: A 70, B 70 -> 70 ± 0, fewer collisions, shorter time in B; one failed run ignored.
    writeRun(root, {"wa", "dynamic", "dep", 0, 0, 1, {}}, 0, 70, 50, 1);
    writeRun(root, {"wb", "dynamic", "dep", 0, 0, 1, {}}, 0, 70, 50, 0);
    writeRun(root, {"wb", "dynamic", "dep", 1, 0, 1, {}}, 139, 0, 0, 0);

    const auto runs = readRuns(root.string());
    ASSERT_EQ(runs.size(), 6u);
    const auto tables = buildTables(runs, {"dep", "aep"});
    ASSERT_EQ(tables.size(), 1u);
    const ResultTable& t = tables[0];
    EXPECT_EQ(t.planners, (std::vector<std::string>{"dep", "aep"}));
    ASSERT_EQ(t.rows.size(), 5u);
    EXPECT_NEAR(t.cells[0][1].mean, 72.5, 1e-9);
    EXPECT_NEAR(t.cells[0][1].stddev, 17.677669529, 1e-6);
    EXPECT_EQ(t.cells[0][1].worlds, 2);
    EXPECT_NEAR(t.cells[0][0].mean, 70.0, 1e-9);
    EXPECT_NEAR(t.cells[0][0].stddev, 0.0, 1e-9);
    EXPECT_EQ(t.best[0], 1);                       // highest coverage: AEP
    EXPECT_NEAR(t.cells[1][1].mean, 225.0, 1e-9);  // T: (150 + 300) / 2
    EXPECT_EQ(t.best[1], 0);                       // lowest time: DEP
    EXPECT_NEAR(t.cells[4][1].mean, 1.5, 1e-9);    // NOC: (3 + 0) / 2
    EXPECT_NEAR(t.cells[4][0].mean, 0.5, 1e-9);
    EXPECT_EQ(t.best[4], 0);

    const std::string md = t.markdown();
    EXPECT_NE(md.find("| DEP | AEP |"), std::string::npos) << md;
    EXPECT_NE(md.find("| **C %** | 70.00 ± 0.00 | **72.50** ± 17.68 |"), std::string::npos) << md;
    EXPECT_NE(md.find("| **T s** | **50.00** ± 0.00 | 225.00 ± 106.07 |"), std::string::npos) << md;
    // PT is 1.5 for everyone: a tie is bold in both columns.
    EXPECT_NE(md.find("| **PT s** | **1.50** ± 0.00 | **1.50** ± 0.00 |"), std::string::npos) << md;

    // Per world: the means over each planner's ok runs (no reachable_percent here: "-").
    const std::string perWorld = perWorldMarkdown(runs, "dynamic", {"dep", "aep"});
    EXPECT_NE(perWorld.find("| wa | AEP | 2 | 85.00 | - | 150.00 | 3.00 | 0.00 |"),
              std::string::npos)
        << perWorld;
    EXPECT_NE(perWorld.find("| wb | DEP | 1 | 70.00 | - | 50.00 | 0.00 | 0.00 |"),
              std::string::npos)
        << perWorld;
    EXPECT_LT(perWorld.find("| wa | DEP"), perWorld.find("| wb | AEP"));  // world by world
    fs::remove_all(root);
}

TEST(BenchmarkResults, AggregateWritesResultsTableAndPlots) {
    const auto root = tempDir("aggregate");
    writeRun(root, {"wa", "dynamic", "aep", 0, 0, 1, {}}, 0, 80, 100, 2);
    writeRun(root, {"wa", "dynamic", "aep", 0, 1, 2, {}}, 0, 90, 100, 2);
    writeRun(root, {"wa", "dynamic", "dep", 0, 0, 1, {}}, 2, 0, 0, 0);
    EXPECT_EQ(aggregateBenchmark(root.string()), 3u);

    const std::string csv = readText(root / "results.csv");
    EXPECT_EQ(csv.rfind("world,mode,planner,start,repetition,seed,status,exit_code,log,"
                        "coverage_percent,",
                        0),
              0u);
    EXPECT_NE(csv.find("wa,dynamic,aep,0,1,2,ok,0,"), std::string::npos) << csv;
    EXPECT_NE(csv.find("wa,dynamic,dep,0,0,1,failed,2,"), std::string::npos) << csv;
    EXPECT_NE(csv.find(",planner finished,"), std::string::npos) << csv;
    EXPECT_NE(readText(root / "table.md").find("1 failed"), std::string::npos);

    const auto coverage = cv::imread((root / "plots" / "coverage_wa_dynamic.png").string());
    ASSERT_FALSE(coverage.empty());
    EXPECT_EQ(coverage.cols, 900);
    EXPECT_EQ(coverage.rows, 520);
    const auto timeline = cv::imread((root / "plots" / "collisions_aep_wa_dynamic.png").string());
    ASSERT_FALSE(timeline.empty());
    EXPECT_FALSE(fs::exists(root / "plots" / "collisions_dep_wa_dynamic.png"));
    // The orange collision segments are drawn (B,G,R = 0,140,255).
    cv::Mat orange;
    cv::inRange(timeline, cv::Scalar(0, 130, 245), cv::Scalar(10, 150, 255), orange);
    EXPECT_GT(cv::countNonZero(orange), 100);
    fs::remove_all(root);
}

namespace {

/** x and width of every <rect> filled with `fill` in an SVG. */
std::vector<std::pair<double, double>> rectsFilled(const std::string& svg,
                                                   const std::string& fill) {
    std::vector<std::pair<double, double>> out;
    const std::string mark = "fill=\"" + fill + "\"/>";
    for (auto at = svg.find(mark); at != std::string::npos; at = svg.find(mark, at + 1)) {
        const auto rect = svg.rfind("<rect ", at);
        auto value = [&](const std::string& key) {
            const auto k = svg.find(key + "=\"", rect);
            return std::stod(svg.substr(k + key.size() + 2));
        };
        out.emplace_back(value("x"), value("width"));
    }
    return out;
}

}  // namespace

TEST(BenchmarkResults, Fig4PutsCollisionEpisodesOnTheExplorationClock) {
    const auto root = tempDir("fig4");
    const RunSpec spec{"wa", "dynamic", "aep", 0, 0, 1, {}};
    writeRun(root, spec, 0, 80, 10, 2);
    const auto dir = root / "runs" / spec.id();
    std::ofstream(dir / "summary.json") << "{\"coverage_percent\": 80, \"exploration_time_s\": 10, "
                                           "\"exploration_start_s\": 5.0, \"collisions\": 2}\n";
    // Spawn clock: 6-7 s and 14 s until the end (-1) are 1-2 s and 9-10 s of exploration.
    std::ofstream(dir / "collisions.csv") << "person,start_s,end_s,tracked\n0,6.0,7.0,-1\n"
                                             "-1,14.0,-1.000,-1\n";
    const auto written = writePlots(readRuns(root.string()), (root / "plots").string());
    EXPECT_EQ(written.size(), 9u);  // coverage, fig4, collisions: png, svg, pdf each
    const std::string svg = readText(root / "plots" / "fig4_wa_dynamic.svg");
    EXPECT_NE(svg.find(">AEP s0 r0: 2</text>"), std::string::npos);
    EXPECT_NE(svg.find(">static geometry</text>"), std::string::npos);
    const auto person = rectsFilled(svg, "#1f77b4");  // the planner's colour
    const auto statics = rectsFilled(svg, "#1e1e1e");
    ASSERT_EQ(person.size(), 1u);
    ASSERT_EQ(statics.size(), 2u);                // the bar and the legend swatch
    const double secondWidth = person[0].second;  // 1 s
    EXPECT_NEAR(statics[0].second, secondWidth, 0.05);
    EXPECT_NEAR(statics[0].first - person[0].first, 8 * secondWidth, 0.05);
    fs::remove_all(root);
}
