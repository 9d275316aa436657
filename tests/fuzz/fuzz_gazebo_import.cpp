// The Gazebo import: SDF world text, the ROS launch file with the people, the exploration-box
// yaml and experiments.yaml with the starts, then the world file it writes, loaded back as
// `daep-world import` does. A unit cube mesh, cube.obj, lies beside the world file. Input: the four
// texts separated by lines "====" (missing = none).
#include <cstdint>

#include "FuzzSupport.h"
#include "daep/world/GazeboImport.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string mesh = daep::fuzz::writeCubeMesh();
    const auto parts = daep::fuzz::splitParts(data, size, "====");
    const auto dir = daep::fuzz::scratchDir();
    daep::world::GazeboImportOptions options;
    options.modelPaths = {dir.string()};
    options.skipMissing = true;
    if (parts.size() > 1)
        options.peopleFile = daep::fuzz::writeScratch("people.launch", parts[1]);
    if (parts.size() > 2)
        options.boxConfig = daep::fuzz::writeScratch("exploration.yaml", parts[2]);
    if (parts.size() > 3) {
        options.startsFile = daep::fuzz::writeScratch("experiments.yaml", parts[3]);
        options.startsKey = "fuzz";
    }
    const std::string worldFile = daep::fuzz::writeScratch("fuzz.world", parts[0]);
    daep::fuzz::expectOnlyInputErrors([&] {
        const auto world = daep::world::importGazeboWorld(worldFile, options);
        const std::string yamlPath = (dir / "imported.yaml").string();
        daep::world::saveWorldYaml(world, yamlPath);
        daep::world::loadWorldFile(yamlPath);
    });
    return 0;
}
