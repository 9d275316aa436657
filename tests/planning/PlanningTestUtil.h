#pragma once

#include <gtest/gtest.h>

#include <mrpt/config/CConfigFileMemory.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "daep/common/Types.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/planning/Planner.h"

namespace daep::planning::test {

inline std::unique_ptr<mapping::ExplorationMap> makeMap(const Aabb& box, double maxRange = 5.0) {
    mapping::MapParams params;
    params.resolution = 0.2;
    params.maxRange = maxRange;
    return std::make_unique<mapping::ExplorationMap>(params, box);
}

inline Aabb box(double x0, double y0, double z0, double x1, double y1, double z1) {
    Aabb b;
    b.min = {x0, y0, z0};
    b.max = {x1, y1, z1};
    return b;
}

/** Distance from `origin` (inside `room`) along unit `dir` to the room's boundary. */
inline double distanceToWall(const Aabb& room, const Eigen::Vector3d& origin,
                             const Eigen::Vector3d& dir) {
    double t = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (dir[a] > 0)
            t = std::min(t, (room.max[a] - origin[a]) / dir[a]);
        if (dir[a] < 0)
            t = std::min(t, (room.min[a] - origin[a]) / dir[a]);
    }
    return t;
}

/**
 * A synthetic scan from `origin` of the walls of an empty box-shaped `room`: one point per
 * (azimuth, elevation) step where the ray meets a wall. Elevations within +-maxElevationDeg.
 */
inline std::vector<Eigen::Vector3f> roomScan(const Aabb& room, const Eigen::Vector3d& origin,
                                             double stepDeg = 1.0, double maxElevationDeg = 90.0) {
    std::vector<Eigen::Vector3f> points;
    const double step = stepDeg * M_PI / 180.0;
    const double maxEl = maxElevationDeg * M_PI / 180.0;
    for (double el = -maxEl; el <= maxEl + 1e-9; el += step) {
        for (double az = 0; az < 2 * M_PI; az += step) {
            const Eigen::Vector3d dir(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                      std::sin(el));
            points.push_back((origin + distanceToWall(room, origin, dir) * dir).cast<float>());
        }
    }
    return points;
}

inline std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/** All default parameter files (defaults.ini and one per planner), concatenated. */
inline std::string defaultsText() {
    const std::string dir = std::string(DAEP_SOURCE_DIR) + "/share/daep/config/";
    std::string text = readFile(dir + "defaults.ini");
    std::vector<std::string> planners;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().extension() == ".ini" && e.path().filename() != "defaults.ini")
            planners.push_back(e.path().string());
    std::sort(planners.begin(), planners.end());
    for (const auto& p : planners)
        text += "\n" + readFile(p);
    return text;
}

/** The ini text with `key` of `[section]` removed (or its value replaced when value given). */
inline std::string editKey(const std::string& text, const std::string& section,
                           const std::string& key, const std::string* value = nullptr) {
    std::istringstream in(text);
    std::ostringstream out;
    std::string line, current;
    while (std::getline(in, line)) {
        if (!line.empty() && line[0] == '[')
            current = line.substr(1, line.find(']') - 1);
        const bool match = current == section && line.rfind(key + " ", 0) == 0;
        if (!match) {
            out << line << '\n';
        } else if (value != nullptr) {
            out << key << " = " << *value << '\n';
        }
    }
    return out.str();
}

inline std::unique_ptr<mrpt::config::CConfigFileMemory> configFromText(const std::string& text) {
    return std::make_unique<mrpt::config::CConfigFileMemory>(text);
}

/** A planning context at `position` over `map` (time and motion limits at their defaults). */
inline PlanningContext contextFor(const mapping::ExplorationMap& map,
                                  const Eigen::Vector3d& position, double yaw = 0.0) {
    PlanningContext c;
    c.time = 12.0;
    c.pose.position = position;
    c.pose.yaw = yaw;
    c.map = &map;
    c.explorationBox = map.explorationBox();
    return c;
}

/** Known free for x < knownUntil (no obstacles), unknown beyond; box 0..length x 0..4 x 0..2. */
inline std::unique_ptr<mapping::ExplorationMap> westKnown(double length, double knownUntil) {
    // The clearing rays start at knownUntil and must reach x = 0.
    auto map = makeMap(box(0, 0, 0, length, 4, 2), std::max(15.0, knownUntil + 4.0));
    for (double y = 0.1; y < 4.0; y += 0.2)
        for (double z = 0.1; z < 2.0; z += 0.2)
            map->insertPointCloud({knownUntil - 0.1, y, z},
                                  {Eigen::Vector3f(-100.f, float(y), float(z))});
    return map;
}

/** Where halfSeenRoom is seen from. */
inline const Eigen::Vector3d kHalfSeenRoomEye{2.0, 2.0, 1.0};

/**
 * An 8 x 4 m box `height` high, in a room whose walls stand 0.1 m outside it and whose
 * ceiling is at `ceiling`, seen from kHalfSeenRoomEye out to 2.5 m: its western half
 * (x < ~4.5).
 */
inline std::unique_ptr<mapping::ExplorationMap> halfSeenRoom(double height, double ceiling) {
    const Eigen::Vector3d& from = kHalfSeenRoomEye;
    auto map = makeMap(box(0, 0, 0, 8, 4, height), 2.5);
    map->insertPointCloud(from, roomScan(box(-0.1, -0.1, -0.1, 8.1, 4.1, ceiling), from, 0.5));
    return map;
}

/** An 8 x 4 x 2 m box whose western half (x < ~4.5) is seen from (2, 2, 1). */
struct HalfKnownRoomMap : ::testing::Test {
    void SetUp() override { map = halfSeenRoom(2.0, 2.1); }
    const Eigen::Vector3d root = kHalfSeenRoomEye;
    std::unique_ptr<mapping::ExplorationMap> map;
};

}  // namespace daep::planning::test
