// daep-world: imports Gazebo worlds into the world format, draws worlds as PNG, bounds the
// coverage a run can reach, and scans worlds into OctoMaps and point clouds.
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "daep/common/AppMain.h"
#include "daep/common/CommandLine.h"
#include "daep/common/Error.h"
#include "daep/eval/WorldRender.h"
#include "daep/world/GazeboImport.h"
#include "daep/world/ReachableVolume.h"
#include "daep/world/VoxelMaps.h"
#include "daep/world/WorldSpec.h"

namespace {

constexpr const char* kUsage =
    "usage:\n"
    "  daep-world import WORLD.world --out OUT.yaml [--model-path DIR]... [--people LAUNCH]\n"
    "             [--box-config EXPLORATION.yaml] [--starts EXPERIMENTS.yaml --starts-key NAME]\n"
    "             [--name NAME] [--skip-missing]\n"
    "      Converts a Gazebo SDF world (collision boxes, cylinders, spheres, meshes, includes\n"
    "      resolved through the --model-path dirs) into a world file; people from a launch\n"
    "      file's field_motion.py waypoints, the box from boundary/min|max|volume, the starts\n"
    "      from spawn_positions/NAME. --skip-missing skips (with a warning) missing models and\n"
    "      meshes and unsupported geometry instead of failing.\n"
    "  daep-world render WORLD --out IMAGE.png [--size PX]\n"
    "      Draws a top-down view of a world file or built-in world (default 1000 x 1000 px).\n"
    "  daep-world reach WORLD [--start N] [--resolution R] [--robot-radius R] [--climb M]\n"
    "      Per start (every start unless --start), the most of the exploration box a run can\n"
    "      observe, in % of the exploration volume: the free space connected to where a drone\n"
    "      of the robot radius (default 0.3 m) can fly after the climb (default 1 m), and the\n"
    "      surfaces it ends on, on the map's grid (default 0.2 m cells).\n";

struct Args {
    std::vector<std::string> positional;
    std::string out;
    int size = 1000;
    std::string startsFile;
    daep::world::GazeboImportOptions import;
    int start = -1;  ///< reach: -1 = every start
    daep::world::ReachParams reach;
    daep::world::LaserScanParams scan;
    double stationHeight = 1.3;
};

int parseSize(const std::string& text) {
    char* end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (end == text.c_str() || *end != '\0' || v < 200 || v > 10000)
        throw daep::InputError("--size: expected a whole number of pixels in 200..10000, got '" +
                               text + "'");
    return static_cast<int>(v);
}

int parseStart(const std::string& text) {
    char* end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (end == text.c_str() || *end != '\0' || v < 0 || v > 1000000)
        throw daep::InputError("--start: expected a start index >= 0, got '" + text + "'");
    return static_cast<int>(v);
}

/** A number for `flag` that must be > 0 (or >= 0 when zeroAllowed). */
double parseLength(const std::string& flag, const std::string& text, bool zeroAllowed) {
    const double v = daep::parseNumber(flag, text.c_str());
    if (!std::isfinite(v) || v < 0 || (!zeroAllowed && v == 0))
        throw daep::InputError(flag + ": expected a length " + (zeroAllowed ? ">= 0" : "> 0") +
                               " in metres, got '" + text + "'");
    return v;
}

Eigen::Vector3d parseStation(const std::string& text) {
    Eigen::Vector3d p;
    std::istringstream in(text);
    char comma1 = 0, comma2 = 0;
    if (!(in >> p.x() >> comma1 >> p.y() >> comma2 >> p.z()) || comma1 != ',' || comma2 != ',' ||
        !(in >> std::ws).eof() || !p.allFinite())
        throw daep::InputError("--station: expected X,Y,Z in metres, got '" + text + "'");
    return p;
}

/** The options of `command` (import, render or reach); nullopt after --help or --version. */
std::optional<Args> parseArgs(const std::string& command, int argc, char** argv) {
    Args a;
    auto& o = a.import;
    daep::CommandLine cli("daep-world " + command, kUsage);
    cli.positionals(a.positional, 1, 1, "input file");
    if (command != "reach")
        cli.option("--out", a.out);
    if (command == "import")
        cli.repeated("--model-path", o.modelPaths)
            .option("--people", o.peopleFile)
            .option("--box-config", o.boxConfig)
            .option("--starts", o.startsFile)
            .option("--starts-key", o.startsKey)
            .option("--name", o.name)
            .flag("--skip-missing", o.skipMissing);
    if (command == "render")
        cli.option("--size", [&a](const std::string& text) { a.size = parseSize(text); });
    if (command == "reach")
        cli.option("--start", [&a](const std::string& t) { a.start = parseStart(t); })
            .option("--resolution",
                    [&a](const std::string& t) {
                        a.reach.resolution = parseLength("--resolution", t, false);
                    })
            .option("--robot-radius",
                    [&a](const std::string& t) {
                        a.reach.robotRadius = parseLength("--robot-radius", t, true);
                    })
            .option("--climb", [&a](const std::string& t) {
                a.reach.climb = parseLength("--climb", t, true);
            });
    if (command == "scan")
        cli.option("--resolution",
                   [&a](const std::string& t) {
                       a.reach.resolution = parseLength("--resolution", t, false);
                   })
            .option("--station",
                    [&a](const std::string& t) { a.scan.stations.push_back(parseStation(t)); })
            .option(
                "--height",
                [&a](const std::string& t) { a.stationHeight = parseLength("--height", t, true); })
            .option("--step-deg",
                    [&a](const std::string& t) {
                        a.scan.stepDeg = parseLength("--step-deg", t, false);
                    })
            .option("--max-range", [&a](const std::string& t) {
                a.scan.maxRange = parseLength("--max-range", t, false);
            });
    if (!cli.parse(argc, argv))
        return std::nullopt;
    return a;
}

void requireOut(const Args& a) {
    if (a.out.empty())
        throw daep::InputError("--out is required");
}

int runImport(const Args& a) {
    requireOut(a);
    auto options = a.import;
    if (!options.startsFile.empty() && options.startsKey.empty())
        throw daep::InputError("--starts needs --starts-key");
    const auto world = daep::world::importGazeboWorld(a.positional[0], options);
    for (const auto& w : world.warnings)
        std::cerr << "warning: " << w << "\n";
    daep::world::saveWorldYaml(world, a.out);
    const auto check = daep::world::loadWorldFile(a.out);  // the output must load
    std::cout << "wrote " << a.out << ": " << world.boxes.size() << " boxes, "
              << world.cylinders.size() << " cylinders, " << world.meshes.size() << " meshes, "
              << world.people.size() << " people, " << check.starts.size() << " starts"
              << (world.warnings.empty()
                      ? std::string()
                      : ", " + std::to_string(world.warnings.size()) + " warnings")
              << "\n";
    return 0;
}

int runRender(const Args& a) {
    requireOut(a);
    const auto world = daep::world::loadWorldFile(daep::world::resolveWorldPath(a.positional[0]));
    daep::eval::renderWorldPng(world, a.out, a.size);
    std::cout << "wrote " << a.out << " (" << a.size << " x " << a.size << " px)\n";
    return 0;
}

std::string formatPoint(const Eigen::Vector3d& p) {
    std::ostringstream o;
    o << std::defaultfloat << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
    return o.str();
}

void printReach(int index, const Eigen::Vector3d& start, const daep::world::ReachableVolume& r) {
    std::cout << "start " << index << " " << formatPoint(start) << ": reachable " << std::fixed
              << std::setprecision(2) << r.reachablePercent << " %  (observable "
              << std::setprecision(1) << r.observableVolume << " m^3; the drone's own cells "
              << r.droneVolume << " m^3 = " << std::setprecision(2) << r.dronePercent << " %)";
    if (r.seedMoved)
        std::cout << "  [spawn cell solid: filled from " << formatPoint(r.seed) << "]";
    else if (!r.seedClear)
        std::cout << "  [spawn cell lacks the drone's clearance]";
    std::cout << std::defaultfloat << "\n";
}

int runReach(const Args& a) {
    const auto world = daep::world::loadWorldFile(daep::world::resolveWorldPath(a.positional[0]));
    const int starts = static_cast<int>(world.starts.size());
    if (a.start >= starts)
        throw daep::InputError("--start: " + std::to_string(a.start) + " is out of range 0.." +
                               std::to_string(starts - 1) + " for world " + world.name);
    const auto& p = a.reach;
    std::cout << world.name << ": exploration volume " << world.explorationVolume()
              << " m^3, resolution " << p.resolution << " m, robot radius " << p.robotRadius
              << " m, climb " << p.climb << " m\n";
    for (int s = 0; s < starts; ++s)
        if (a.start < 0 || s == a.start)
            printReach(s, world.starts[std::size_t(s)],
                       daep::world::computeReachableVolume(world, world.starts[std::size_t(s)], p));
    return 0;
}

/** No command, or an unknown one: --help and --version still work. */
int withoutCommand(int argc, char** argv) {
    std::vector<std::string> command;
    daep::CommandLine cli("daep-world", kUsage);
    cli.positionals(command, 0, 1, "command");
    if (!cli.parse(argc, argv))
        return 0;
    if (command.empty())
        throw daep::InputError(
            "daep-world: no command (import, render, reach or scan; see daep-world --help)");
    throw daep::InputError("daep-world: unknown command '" + command.front() +
                           "' (import, render, reach or scan; see daep-world --help)");
}

int runScan(const Args& a) {
    requireOut(a);
    const auto world = daep::world::loadWorldFile(daep::world::resolveWorldPath(a.positional[0]));
    auto params = a.scan;
    params.resolution = a.reach.resolution;
    if (params.stations.empty())
        for (const auto& s : world.starts)
            params.stations.push_back(s + Eigen::Vector3d(0.0, 0.0, a.stationHeight));
    const auto r = daep::world::scanWorldToFile(world, params, a.out);
    std::cout << "wrote " << a.out << ": " << params.stations.size() << " stations, " << r.rays
              << " rays, " << r.returns << " returns";
    if (r.nodes > 0)
        std::cout << ", " << r.nodes << " nodes (" << r.occupiedLeaves << " occupied leaves) at "
                  << params.resolution << " m";
    std::cout << "\n";
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string command = argc > 1 ? argv[1] : "";
    if (command == "help") {
        std::cout << kUsage;
        return 0;
    }
    return daep::runApp([&] {
        if (command != "import" && command != "render" && command != "reach" && command != "scan")
            return withoutCommand(argc, argv);
        const auto args = parseArgs(command, argc - 1, argv + 1);
        if (!args)
            return 0;
        if (command == "reach")
            return runReach(*args);
        if (command == "scan")
            return runScan(*args);
        return command == "import" ? runImport(*args) : runRender(*args);
    });
}
