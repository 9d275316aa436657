// The world-file loader (YAML). A small OBJ mesh, cube.obj, lies beside the world file so that
// `meshes:` entries can name one.
#include <cstdint>

#include "FuzzSupport.h"
#include "daep/world/WorldSpec.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const std::string mesh = daep::fuzz::writeCubeMesh();
    const std::string path = daep::fuzz::writeScratch(
        "world.yaml", std::string(reinterpret_cast<const char*>(data), size));
    daep::fuzz::expectOnlyInputErrors([&] {
        const daep::world::WorldSpec world = daep::world::loadWorldFile(path);
        world.bounds();
        world.explorationVolume();
    });
    return 0;
}
