// daep-world: imports Gazebo worlds into the world format and draws worlds as PNG.
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "WorldRender.h"
#include "daep/common/AppMain.h"
#include "daep/common/Error.h"
#include "daep/world/GazeboImport.h"
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
    "      Draws a top-down view of a world file or built-in world (default 1000 x 1000 px).\n";

struct Args {
    std::vector<std::string> positional;
    std::string out;
    int size = 1000;
    std::string startsFile;
    daep::world::GazeboImportOptions import;
};

std::string nextValue(int& i, int argc, char** argv) {
    if (i + 1 >= argc)
        throw daep::InputError(std::string(argv[i]) + " needs a value");
    return argv[++i];
}

int parseSize(const std::string& text) {
    char* end = nullptr;
    const long v = std::strtol(text.c_str(), &end, 10);
    if (end == text.c_str() || *end != '\0' || v < 200 || v > 10000)
        throw daep::InputError("--size: expected a whole number of pixels in 200..10000, got '" +
                               text + "'");
    return static_cast<int>(v);
}

Args parseArgs(int argc, char** argv) {
    Args a;
    auto& o = a.import;
    for (int i = 2; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--out")
            a.out = nextValue(i, argc, argv);
        else if (arg == "--size")
            a.size = parseSize(nextValue(i, argc, argv));
        else if (arg == "--model-path")
            o.modelPaths.push_back(nextValue(i, argc, argv));
        else if (arg == "--people")
            o.peopleFile = nextValue(i, argc, argv);
        else if (arg == "--box-config")
            o.boxConfig = nextValue(i, argc, argv);
        else if (arg == "--starts")
            o.startsFile = nextValue(i, argc, argv);
        else if (arg == "--starts-key")
            o.startsKey = nextValue(i, argc, argv);
        else if (arg == "--name")
            o.name = nextValue(i, argc, argv);
        else if (arg == "--skip-missing")
            o.skipMissing = true;
        else if (!arg.empty() && arg[0] == '-')
            throw daep::InputError("unknown option " + arg);
        else
            a.positional.push_back(arg);
    }
    if (a.positional.size() != 1)
        throw daep::InputError("expected exactly one input file");
    if (a.out.empty())
        throw daep::InputError("--out is required");
    return a;
}

int runImport(const Args& a) {
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
    const auto world = daep::world::loadWorldFile(daep::world::resolveWorldPath(a.positional[0]));
    daep::worldapp::renderWorldPng(world, a.out, a.size);
    std::cout << "wrote " << a.out << " (" << a.size << " x " << a.size << " px)\n";
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string command = argc > 1 ? argv[1] : "";
    if (command == "--help" || command == "-h" || command == "help") {
        std::cout << kUsage;
        return 0;
    }
    if (command != "import" && command != "render") {
        std::cerr << (command.empty() ? "error: no command\n"
                                      : "error: unknown command '" + command + "'\n")
                  << kUsage;
        return 1;
    }
    return daep::runApp([&] {
        const Args args = parseArgs(argc, argv);
        return command == "import" ? runImport(args) : runRender(args);
    });
}
