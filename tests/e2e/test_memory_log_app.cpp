// memory.csv: a short run samples the process's memory beside the map's size at the interval
// asked for, plus a final row; memory_every_s = 0 writes none.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "RunApp.h"

namespace {

using daep::test::freshDir;
using daep::test::kTinyIni;
using daep::test::readText;
using daep::test::runExplore;

std::vector<std::vector<double>> csvRows(const std::string& text, std::string& header) {
    std::istringstream in(text);
    std::getline(in, header);
    std::vector<std::vector<double>> rows;
    for (std::string line; std::getline(in, line);) {
        std::vector<double> row;
        std::istringstream cells(line);
        for (std::string cell; std::getline(cells, cell, ',');)
            row.push_back(std::stod(cell));
        rows.push_back(row);
    }
    return rows;
}

TEST(MemoryLogApp, SamplesAtTheIntervalWithTheMapSize) {
    const auto dir = freshDir("memory_log");
    const auto out = dir / "run";
    const auto r = runExplore(kTinyIni +
                                  " --set experiment.max_time_s=25 --set output.memory_every_s=10"
                                  " --set output.scene=false --quiet --out " +
                                  out.string(),
                              dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    std::string header;
    const auto rows = csvRows(readText(out / "memory.csv"), header);
    EXPECT_EQ(header, "t,rss_mb,peak_rss_mb,known_volume_m3,map_nodes");
    ASSERT_EQ(rows.size(), 4u);  // t = 0, 10, 20 and the end at 25
    const double times[] = {0, 10, 20, 25};
    for (std::size_t i = 0; i < rows.size(); ++i) {
        ASSERT_EQ(rows[i].size(), 5u);
        EXPECT_DOUBLE_EQ(rows[i][0], times[i]);
        EXPECT_GT(rows[i][1], 5.0);         // a real resident set, in MB
        EXPECT_GE(rows[i][2], rows[i][1]);  // the peak is at least the current
        EXPECT_GT(rows[i][3], 0.0);         // the take-off already mapped some
        EXPECT_GT(rows[i][4], 0.0);
        if (i > 0) {
            EXPECT_GE(rows[i][2], rows[i - 1][2]);  // peaks never fall
            EXPECT_GE(rows[i][3], rows[i - 1][3]);  // known volume only grows
        }
    }
    EXPECT_TRUE(std::filesystem::exists(out / "memory.png"));
}

TEST(MemoryLogApp, ZeroIntervalWritesNoFile) {
    const auto dir = freshDir("memory_log_off");
    const auto out = dir / "run";
    const auto r = runExplore(kTinyIni +
                                  " --set experiment.max_time_s=5 --set output.memory_every_s=0"
                                  " --set output.scene=false --quiet --out " +
                                  out.string(),
                              dir);
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out / "memory.csv"));
    EXPECT_TRUE(std::filesystem::exists(out / "summary.json"));
}

TEST(MemoryLogApp, NegativeIntervalIsAnInputError) {
    const auto dir = freshDir("memory_log_bad");
    const auto r = runExplore(
        kTinyIni + " --set output.memory_every_s=-1 --quiet --out " + (dir / "run").string(), dir);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.err.find("memory_every_s"), std::string::npos) << r.err;
}

}  // namespace
