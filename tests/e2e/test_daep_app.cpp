// End-to-end: DAEP flown by the real daep-explore binary through the tiny room's walker.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "RunApp.h"

namespace fs = std::filesystem;
using daep::test::freshDir;
using daep::test::jsonNumber;
using daep::test::kTinyIni;
using daep::test::readText;
using daep::test::runExplore;

namespace {

struct DaepRun {
    std::string source;
    int start;
};

void PrintTo(const DaepRun& r, std::ostream* os) {
    *os << r.source << " start " << r.start;
}

class DaepTinyRoom : public ::testing::TestWithParam<DaepRun> {};

/** summary.json of daep-explore on the tiny room's experiment with `sets` (--set ...). */
std::string summaryWith(const std::string& sets, const fs::path& dir) {
    const auto r = runExplore(
        kTinyIni + " --quiet --set output.scene=false " + sets + " --out " + dir.string(),
        dir.parent_path());
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return readText(dir / "summary.json");
}

std::string summaryOf(const DaepRun& run, const fs::path& dir) {
    return summaryWith(
        "--set experiment.planner=daep --set experiment.start=" + std::to_string(run.start) +
            " --set tracking.people_source=" + run.source,
        dir);
}

/** The nodes of a local tree a plan row says the deadline cut ("deadline: local: ..., N nodes"). */
int nodesOfACutLocalTree(const std::string& planRow) {
    if (planRow.find("deadline: local: ") == std::string::npos)
        return 0;
    const std::size_t end = planRow.rfind(" nodes");
    if (end == std::string::npos)
        return 0;
    const std::size_t start = planRow.rfind(' ', end - 1);  // after "deadline: ", so found
    return std::stoi(planRow.substr(start + 1, end - start - 1));
}

}  // namespace

TEST_P(DaepTinyRoom, ExploresBothRoomsWithoutTouchingTheWalker) {
    const DaepRun& run = GetParam();
    const auto dir = freshDir("daep_" + run.source + std::to_string(run.start));
    const std::string summary = summaryOf(run, dir / "run");
    // The walker crosses the door the drone must fly through to see the second room: each
    // room is half the volume.
    EXPECT_GT(jsonNumber(summary, "coverage_percent"), 75.0) << summary;
    EXPECT_EQ(jsonNumber(summary, "collisions"), 0.0) << summary;
    EXPECT_EQ(jsonNumber(summary, "static_collisions"), 0.0) << summary;
    EXPECT_NE(readText(dir / "run" / "config.ini").find("people_source = " + run.source),
              std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Sources, DaepTinyRoom,
                         // With sensed people DAEP can meet someone its camera never saw
                         // (README, "DAEP: the people it knows of"); from these starts it does
                         // not, and a regression would show.
                         ::testing::Values(DaepRun{"ground_truth", 3}, DaepRun{"ground_truth", 4},
                                           DaepRun{"sensed", 0}, DaepRun{"sensed", 4}),
                         [](const auto& p) {
                             return p.param.source + "_start" + std::to_string(p.param.start);
                         });

TEST(DaepTinyRoom, SensedRunsAreReproducibleFromTheSeed) {
    const auto dir = freshDir("daep_repro");
    const DaepRun run{"sensed", 4};
    const std::string a = daep::test::deterministicSummaryText(summaryOf(run, dir / "a"));
    const std::string b = daep::test::deterministicSummaryText(summaryOf(run, dir / "b"));
    EXPECT_EQ(a, b);
    EXPECT_EQ(readText(dir / "a" / "trajectory.csv"), readText(dir / "b" / "trajectory.csv"));
}

namespace {

/** A people.csv or people_truth.csv row's first four fields: t, who, x, y. */
struct PersonRow {
    std::string t, who;
    double x = 0.0, y = 0.0;
};

/** The rows of a people CSV after its header, which goes to `header`. */
std::vector<PersonRow> personRows(const fs::path& file, std::string& header) {
    std::istringstream text(readText(file));
    std::getline(text, header);
    std::vector<PersonRow> rows;
    for (std::string line; std::getline(text, line);) {
        std::istringstream fields(line);
        PersonRow r;
        std::string x, y;
        std::getline(fields, r.t, ',');
        std::getline(fields, r.who, ',');
        std::getline(fields, x, ',');
        std::getline(fields, y, ',');
        r.x = std::stod(x);
        r.y = std::stod(y);
        rows.push_back(r);
    }
    return rows;
}

}  // namespace

TEST(DaepTinyRoom, PeopleTruthSitsBesideTheTracksFrameByFrame) {
    // With sensed people the tracks in people.csv are what the camera saw; people_truth.csv
    // has where the walker really was at the same frames, so tracks can be judged.
    const auto dir = freshDir("daep_truth");
    summaryWith(
        "--set experiment.planner=daep --set experiment.start=4"
        " --set tracking.people_source=sensed --set experiment.max_time_s=30",
        dir / "daep");
    std::string header;
    std::map<std::string, std::array<double, 2>> walkerAt;  // the one walker, by frame time
    double lastFrame = 0.0;
    for (const PersonRow& r : personRows(dir / "daep" / "people_truth.csv", header)) {
        EXPECT_EQ(r.who, "0") << r.t;
        EXPECT_TRUE(walkerAt.emplace(r.t, std::array<double, 2>{r.x, r.y}).second)
            << "two rows at " << r.t;
        lastFrame = std::max(lastFrame, std::stod(r.t));
    }
    EXPECT_EQ(header, "t,person,x,y,vx,vy,heading");
    EXPECT_GT(lastFrame, 15.0);  // take-off and a few plans at least
    const auto frames = static_cast<std::size_t>(std::lround(lastFrame * 5.0)) + 1;
    EXPECT_EQ(walkerAt.size(), frames);  // every frame, at 5 Hz
    // Every track row is at a frame of the truth, and the tracks seen lie on the walker.
    const std::vector<PersonRow> tracks = personRows(dir / "daep" / "people.csv", header);
    int onTheWalker = 0;
    for (const PersonRow& r : tracks) {
        const auto at = walkerAt.find(r.t);
        ASSERT_NE(at, walkerAt.end()) << "no truth at " << r.t;
        if (std::hypot(r.x - at->second[0], r.y - at->second[1]) < 0.5)
            ++onTheWalker;
    }
    EXPECT_GT(tracks.size(), 0u);
    EXPECT_GT(onTheWalker, int(tracks.size()) / 2);
    // A planner that does not track people writes neither file.
    summaryWith("--set experiment.planner=aep --set experiment.max_time_s=5", dir / "aep");
    EXPECT_FALSE(fs::exists(dir / "aep" / "people_truth.csv"));
    EXPECT_FALSE(fs::exists(dir / "aep" / "people.csv"));
}

namespace {

/** summary.json of a run in the crossing hall, where a walker passes through start 0. */
std::string crossingRun(const std::string& planner, const fs::path& dir) {
    return summaryWith("--set experiment.world=crossing.yaml --set experiment.planner=" + planner +
                           " --set experiment.planning_fixed_s=10 --set planning.deadline_s=10"
                           " --set experiment.max_time_s=40",
                       dir);
}

}  // namespace

TEST(DaepLongPlans, AHoverThatBecomesUnsafeWhilePlanningIsEvadedBeforeThePlanEnds) {
    // Every plan takes 10 s of hovering; the walker reaches the drone during the first one.
    const auto dir = freshDir("daep_crossing");
    const std::string daep = crossingRun("daep", dir / "daep");
    EXPECT_EQ(jsonNumber(daep, "collisions"), 0.0) << daep;
    EXPECT_EQ(jsonNumber(daep, "static_collisions"), 0.0) << daep;
    EXPECT_GE(jsonNumber(daep, "hover_evasions"), 1.0) << daep;
    // AEP does not watch people: hovering through its plans, it is walked into.
    const std::string aep = crossingRun("aep", dir / "aep");
    EXPECT_GE(jsonNumber(aep, "collisions"), 1.0) << aep;
    EXPECT_EQ(jsonNumber(aep, "hover_evasions"), 0.0) << aep;
}

TEST(DaepDeadline, PlansCutByTheDeadlineKeepTheMissionGoingSafely) {
    // A deadline no plan can meet with measured planning time: every plan call is cut as its
    // tree begins to grow (when the clock's first look comes within the microsecond, one node
    // may grow first), so the drone mostly turns on the spot looking around, and a cut plan
    // never ends the mission (a cut global tree judges no frontier unreachable).
    const auto dir = freshDir("daep_deadline");
    const std::string summary = summaryWith(
        "--set experiment.planner=daep --set experiment.planning_time=measured"
        " --set planning.deadline_s=0.000001 --set experiment.max_time_s=20",
        dir / "run");
    EXPECT_EQ(jsonNumber(summary, "collisions"), 0.0) << summary;
    EXPECT_EQ(jsonNumber(summary, "static_collisions"), 0.0) << summary;
    EXPECT_NE(summary.find("\"end_reason\": \"time limit\""), std::string::npos) << summary;
    std::istringstream plans(readText(dir / "run" / "plans.csv"));
    std::string line;
    std::getline(plans, line);  // header
    int rows = 0, escapes = 0, cutTreeNodes = 0;
    while (std::getline(plans, line)) {
        ++rows;
        const bool escape = line.find("evasion: ") != std::string::npos;  // hovering unsafe
        escapes += escape;
        EXPECT_TRUE(escape || line.find("deadline: ") != std::string::npos) << line;
        cutTreeNodes += nodesOfACutLocalTree(line);
    }
    // It moves only to escape the walker (escapes are at most 1.6 m) or along the few nodes a
    // cut tree grew (each at most daep.ini's extension_range, 1 m, from its parent).
    EXPECT_LE(jsonNumber(summary, "path_length_m"),
              1.7 * (escapes + jsonNumber(summary, "hover_evasions")) + 1.0 * cutTreeNodes + 0.01)
        << summary;
    EXPECT_LE(cutTreeNodes, rows / 2) << "the deadline hardly cut the trees";
    EXPECT_GE(rows, 5);
}
