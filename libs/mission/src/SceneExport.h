#pragma once

#include <Eigen/Core>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "Outputs.h"
#include "daep/common/Types.h"
#include "daep/planning/Planner.h"
#include "daep/world/People.h"

namespace daep::mapping {
class ExplorationMap;
}
namespace daep::perception {
struct PersonForecast;
}

namespace daep::mission {

/** Tracks drawn as people: where each is at `t`, walking as it is predicted to. */
std::vector<world::PersonState> tracksAsPeople(
    double t, const std::vector<perception::PersonForecast>& tracks);

/**
 * Renders DIR/scene.3Dscene, as SceneExporter wrote it, to DIR/scene_perspective.png and
 * DIR/scene_top.png: the PNGs of a run made with render_png = false. Throws InputError naming
 * the file when it is missing, unreadable or not such a scene, std::runtime_error when it
 * cannot be rendered (no EGL/OpenGL).
 */
void renderSceneFile(const std::string& directory, int width, int height);

/** What one scene shows; the pointers must outlive SceneExporter::write(). */
struct SceneContent {
    const mapping::ExplorationMap* map = nullptr;
    const std::vector<Eigen::Vector3d>* trajectory = nullptr;
    const std::vector<planning::TreeEdge>* tree = nullptr;
    std::vector<world::PersonState> people;
    Eigen::Vector3d bodySize = Eigen::Vector3d(1.0, 1.0, 1.8);
    FlatPose drone;
};

/**
 * Writes DIR/scene.3Dscene (SceneViewer3D) and, when enabled, renders it headless with
 * CFBORender (EGL) to DIR/scene_perspective.png and DIR/scene_top.png. Objects are named:
 * occupied_voxels, trajectory, people, predicted_paths, tree, box, grid, drone.
 * People's predicted paths extrapolate their true current velocity for kPredictionHorizon.
 * If EGL/GL is unavailable, one warning line is printed and PNGs are skipped from then on.
 */
class SceneExporter {
public:
    static constexpr double kPredictionHorizon = 10.0;  ///< s

    SceneExporter(const OutputParams& params, std::string directory, std::ostream* log);
    ~SceneExporter();
    SceneExporter(const SceneExporter&) = delete;
    SceneExporter& operator=(const SceneExporter&) = delete;

    /** Overwrites the files; throws std::runtime_error if the .3Dscene cannot be written. */
    void write(const SceneContent& content);

    /** False once rendering failed (or when render_png = false). */
    bool rendersPng() const { return renderPng_; }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    OutputParams params_;
    std::string directory_;
    std::ostream* log_;
    bool renderPng_;
};

}  // namespace daep::mission
