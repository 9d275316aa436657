#include <gtest/gtest.h>

#include <unistd.h>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "daep/eval/RunRecorder.h"

namespace fs = std::filesystem;

namespace {

/** The non-comment lines of a TUM file, each split into its numbers. */
std::vector<std::vector<double>> readTumRows(const fs::path& file) {
    std::ifstream in(file);
    std::vector<std::vector<double>> rows;
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || line[0] == '#')
            continue;
        std::istringstream fields(line);
        std::vector<double> row;
        for (double v; fields >> v;)
            row.push_back(v);
        EXPECT_TRUE(fields.eof()) << "not a number in: " << line;
        rows.push_back(row);
    }
    return rows;
}

daep::FlatPose pose(double x, double y, double z, double yaw) {
    daep::FlatPose p;
    p.position = {x, y, z};
    p.yaw = yaw;
    return p;
}

}  // namespace

TEST(RunRecorder, WritesEveryPoseAlsoAsATumTrajectory) {
    const auto dir = fs::temp_directory_path() / ("daep_eval_tum_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    const std::vector<std::pair<double, daep::FlatPose>> poses = {{0.0, pose(1, 2, 0.1, 0.0)},
                                                                  {0.2, pose(1.5, -2.25, 1.1, 0.5)},
                                                                  {12.4, pose(0, 0, 1, -3.0)}};
    {
        daep::eval::RunRecorder rec(dir.string());
        for (const auto& [t, p] : poses)
            rec.addPose(t, p);
    }
    std::ifstream file(dir / "trajectory_tum.txt");
    std::string header;
    std::getline(file, header);
    EXPECT_EQ(header, "# timestamp tx ty tz qx qy qz qw");

    const auto rows = readTumRows(dir / "trajectory_tum.txt");
    ASSERT_EQ(rows.size(), poses.size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const auto& r = rows[i];
        const auto& [t, p] = poses[i];
        ASSERT_EQ(r.size(), 8u) << "line " << i;
        EXPECT_NEAR(r[0], t, 1e-9);  // seconds
        EXPECT_NEAR(r[1], p.position.x(), 1e-4);
        EXPECT_NEAR(r[2], p.position.y(), 1e-4);
        EXPECT_NEAR(r[3], p.position.z(), 1e-4);
        EXPECT_EQ(r[4], 0.0);  // a yaw-only pose: rotation about z
        EXPECT_EQ(r[5], 0.0);
        EXPECT_NEAR(r[6] * r[6] + r[7] * r[7], 1.0, 1e-5);
        EXPECT_NEAR(2 * std::atan2(r[6], r[7]), p.yaw, 1e-5);
    }
    fs::remove_all(dir);
}
