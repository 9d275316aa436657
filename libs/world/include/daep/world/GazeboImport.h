#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "daep/common/Types.h"
#include "daep/world/WorldSpec.h"

namespace daep::world {

/** Where the Gazebo importer finds models and the benchmark's side files. */
struct GazeboImportOptions {
    std::vector<std::string> modelPaths;  ///< dirs holding <name>/model.sdf, for model:// URIs
    std::string peopleFile;  ///< ROS launch file with field_motion.py waypoints; "" = no people
    std::string boxConfig;   ///< <world>_exploration.yaml; "" = bounds of the geometry
    std::string startsFile;  ///< experiments.yaml with spawn_positions
    std::string startsKey;   ///< world key inside spawn_positions
    std::string name;        ///< world name; "" = the .world file's stem
    /** Skip (with a warning) missing models/meshes and unsupported geometry instead of failing. */
    bool skipMissing = false;
};

/** A mesh as the world format references it: a file plus its placement. */
struct MeshPlacement {
    std::string name;
    std::string file;  ///< absolute path
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();
};

/** The static geometry of an SDF world plus the benchmark's box, starts and people. */
struct ImportedWorld {
    std::string name;
    std::string source;   ///< the .world file
    bool ground = false;  ///< a ground plane (z-up plane at z = 0) was present
    std::vector<BoxShape> boxes;
    std::vector<CylinderShape> cylinders;
    std::vector<MeshPlacement> meshes;
    bool hasBox = false;
    Aabb box;
    double volume = 0.0;  ///< boundary/volume, 0 when absent
    std::vector<Eigen::Vector3d> starts;
    std::vector<PersonRoute> people;
    std::vector<std::string> warnings;  ///< skipped items and approximations
};

/**
 * Imports the collision geometry of SDF text (a <world> or a <model>). `sourceName` names the
 * text in messages; `baseDir` resolves relative and file:// URIs. Poses are composed model *
 * link * collision; a <state> section's model poses (and link poses, which Gazebo stores in
 * the world frame) override the declared ones. Spheres become enclosing cylinders (warned).
 * Throws InputError "<source>:<line>: <element>: ..." on bad or missing input.
 */
ImportedWorld importSdfText(const std::string& text, const std::string& sourceName,
                            const std::string& baseDir, const GazeboImportOptions& options);

/** importSdfText on a .world file, then people, box and starts from the options' files. */
ImportedWorld importGazeboWorld(const std::string& worldFile, const GazeboImportOptions& options);

/** People of a ROS launch file: every node whose args are "'NAME' '[(x, y), ...]' ...". */
std::vector<PersonRoute> readLaunchPeople(const std::string& launchFile);

/** `boundary/min`, `boundary/max` and optional `boundary/volume` (0 if absent) of a yaml. */
void readExplorationBoundary(const std::string& yamlFile, Aabb& box, double& volume);

/** `spawn_positions: <key>: - (x,y,z) ...` of the benchmark's experiments.yaml. */
std::vector<Eigen::Vector3d> readSpawnPositions(const std::string& yamlFile,
                                                const std::string& key);

/**
 * The world as world-format YAML (WORLD_FORMAT.md) with a commented header. Mesh files are
 * written relative to `yamlDir` (absolute when they share no top directory). Without a box, the box
 * is the geometry's bounds (meshes are read to find them); without starts, one start at the box
 * centre 0.3 m above its floor.
 */
std::string worldToYaml(const ImportedWorld& world, const std::string& yamlDir);

/** worldToYaml written to `yamlPath`; throws InputError when it cannot be written. */
void saveWorldYaml(const ImportedWorld& world, const std::string& yamlPath);

}  // namespace daep::world
