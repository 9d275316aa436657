#include "daep/mission/BenchmarkCheck.h"

#include <mrpt/config/CConfigFileBase.h>
#include <openssl/evp.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <map>
#include <stdexcept>

#include "MissionSetup.h"
#include "Outputs.h"
#include "daep/common/Error.h"
#include "daep/common/IniText.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/PeopleInput.h"
#include "daep/planning/Planner.h"
#include "daep/planning/PlannerRegistry.h"
#include "daep/sim/DepthCamera.h"
#include "daep/sim/Drone.h"
#include "daep/world/People.h"

namespace fs = std::filesystem;

namespace daep::mission {
namespace {

/** A world of the matrix: its number of starts and its files with their digests. */
struct WorldInputs {
    int starts = 0;
    std::vector<std::pair<std::string, std::string>> files;
};

std::string fileDigest(const std::string& path) {
    return sha256Hex(readTextFile(path));
}

/**
 * The files a world is built from: the world file, then every file it references (meshes, voxel
 * maps), named relative to the world file's folder so that the names do not depend on where the
 * tree lies.
 */
std::vector<std::pair<std::string, std::string>> worldFiles(const world::WorldSpec& w) {
    const fs::path base = fs::path(w.sourceFile).parent_path();
    std::vector<std::pair<std::string, std::string>> files{
        {fs::path(w.sourceFile).filename().string(), fileDigest(w.sourceFile)}};
    const auto add = [&](const std::string& source) {
        const std::string name = fs::path(source).lexically_relative(base).string();
        const bool listed = std::any_of(files.begin(), files.end(),
                                        [&name](const auto& f) { return f.first == name; });
        if (!listed)
            files.emplace_back(name, fileDigest(source));
    };
    for (const auto& mesh : w.meshes)
        add(mesh.source);
    for (const auto& map : w.voxelMaps)
        add(map.source);
    return files;
}

std::string joined(const std::vector<std::string>& items) {
    std::string out;
    for (const auto& s : items)
        out += (out.empty() ? "" : ", ") + s;
    return out;
}

void checkPlanners(const eval::BenchmarkConfig& config) {
    const auto known = planning::plannerNames();
    for (const auto& p : config.planners)
        if (std::find(known.begin(), known.end(), p) == known.end())
            throw InputError(config.where("planners") +
                             ": [benchmark] planners: unknown planner '" + p +
                             "' (known: " + joined(known) + ")");
}

/** Every [set] / --set key must be one daep-explore knows, or every run would fail on it. */
void checkSetKeys(const eval::BenchmarkConfig& config, const ExperimentConfig& base) {
    for (const auto& [key, value] : config.sets) {
        const auto dot = key.find('.');
        const std::string section = key.substr(0, dot), name = key.substr(dot + 1);
        if (!base.config().keyExists(section, name))
            throw InputError(config.where(key) + ": unknown key '" + key +
                             "' (not in defaults.ini, the planner files or " + config.experiment +
                             ")");
    }
}

std::map<std::string, WorldInputs> loadWorlds(const eval::BenchmarkConfig& config) {
    std::map<std::string, WorldInputs> worlds;
    for (const auto& name : config.worlds) {
        world::WorldSpec w;
        try {
            w = world::loadWorldFile(resolveExperimentWorld(name, config.experiment));
        } catch (const InputError& e) {
            throw InputError(config.where("worlds") + ": [benchmark] worlds: " + e.what());
        }
        const int starts = static_cast<int>(w.starts.size());
        for (int s : config.starts)
            if (s >= starts)
                throw InputError(config.where("starts") + ": [benchmark] starts: start " +
                                 std::to_string(s) + " is out of range 0.." +
                                 std::to_string(starts - 1) + " for world " + name);
        worlds[name] = {starts, worldFiles(w)};
    }
    return worlds;
}

/** Loads every component's parameters as a run would, so that a bad value fails here. */
void checkParameters(const ExperimentConfig& experiment) {
    const auto& cfg = experiment.config();
    const Settings settings = loadSettings(experiment);
    world::PeopleParams::fromConfig(cfg);
    sim::CameraParams::fromConfig(cfg);
    sim::DroneParams::fromConfig(cfg);
    mapping::MapParams::fromConfig(cfg);
    loadOutputParams(cfg);
    PeopleInputParams::fromConfig(cfg);
    planning::createPlanner(settings.plannerName, cfg, settings.seed);
}

/**
 * The runs get [set] as --set; an error about a value the user wrote in the benchmark file's
 * [set] section names that file and line instead.
 */
[[noreturn]] void rethrowAtSetOrigin(const eval::BenchmarkConfig& config, const InputError& e) {
    const std::string message = e.what();
    for (const auto& [key, value] : config.sets) {
        const std::string asSet = "--set " + key + ": ";
        const std::string origin = config.where(key);
        if (message.rfind(asSet, 0) == 0 && origin.rfind("--set ", 0) != 0)
            throw InputError(origin + ": " + message.substr(asSet.size()));
    }
    throw e;
}

eval::RunInputs runInputs(const eval::BenchmarkConfig& config, const eval::RunSpec& run,
                          const WorldInputs& world) {
    const ExperimentConfig experiment =
        ExperimentConfig::fromFile(config.experiment, config.runOverrides(run));
    try {
        checkParameters(experiment);
    } catch (const InputError& e) {
        rethrowAtSetOrigin(config, e);
    }
    eval::RunInputs inputs;
    inputs.parameters = experiment.dump();
    inputs.files = world.files;
    std::string text = "daep run inputs 1\n[parameters]\n" + inputs.parameters + "[files]\n";
    for (const auto& [name, digest] : inputs.files)
        text += name + " " + digest + "\n";
    inputs.digest = sha256Hex(text);
    return inputs;
}

}  // namespace

std::string sha256Hex(const std::string& bytes) {
    std::array<unsigned char, EVP_MAX_MD_SIZE> md{};
    unsigned int size = 0;
    if (EVP_Digest(bytes.data(), bytes.size(), md.data(), &size, EVP_sha256(), nullptr) != 1)
        throw std::runtime_error("SHA-256 failed (OpenSSL)");
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < size; ++i)
        out += std::string{hex[md[i] >> 4], hex[md[i] & 15]};
    return out;
}

std::vector<eval::RunSpec> checkBenchmark(const eval::BenchmarkConfig& config) {
    checkPlanners(config);
    const ExperimentConfig base = ExperimentConfig::fromFile(config.experiment);
    checkSetKeys(config, base);
    const auto worlds = loadWorlds(config);
    auto runs = config.expand();
    for (auto& run : runs)
        run.inputs = runInputs(config, run, worlds.at(run.world));
    return runs;
}

}  // namespace daep::mission
