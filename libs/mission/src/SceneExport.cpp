#include "SceneExport.h"

#include <mrpt/img/CImage.h>
#include <mrpt/img/color_maps.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/opengl/CBox.h>
#include <mrpt/opengl/CFBORender.h>
#include <mrpt/opengl/CGridPlaneXY.h>
#include <mrpt/opengl/COctoMapVoxels.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/serialization/CArchive.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "daep/mapping/ExplorationMap.h"

namespace daep::mission {
namespace {

using mrpt::math::TPoint3D;
using mrpt::opengl::COpenGLScene;
namespace gl = mrpt::opengl;

constexpr unsigned kVoxelsInBox = 0;
constexpr unsigned kVoxelsAbove = 1;  ///< ceilings: hidden in the top-down render

TPoint3D toPoint(const Eigen::Vector3d& p) {
    return {p.x(), p.y(), p.z()};
}

gl::COctoMapVoxels::Ptr makeVoxels(const mapping::ExplorationMap& map) {
    const Aabb& box = map.explorationBox();
    auto voxels = gl::COctoMapVoxels::Create();
    voxels->setName("occupied_voxels");
    voxels->resizeVoxelSets(2);
    voxels->showGridLines(false);
    voxels->enableCubeTransparency(false);
    voxels->enableLights(true);
    const octomap::OcTree& tree = map.octree();
    const double zSpan = std::max(box.size().z(), 1e-3);
    Eigen::Vector3d lo = box.min, hi = box.max;
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
        if (!tree.isNodeOccupied(*it))
            continue;
        const auto c = it.getCoordinate();
        const Eigen::Vector3d p(c.x(), c.y(), c.z());
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
        // Jet without its darkest blue and red ends: the floor stays readable under lighting.
        const double h = std::clamp((p.z() - box.min.z()) / zSpan, 0.0, 1.0);
        const auto color = mrpt::img::colormap(mrpt::img::cmJET, float(0.15 + 0.75 * h));
        const unsigned set = p.z() > box.max.z() ? kVoxelsAbove : kVoxelsInBox;
        voxels->push_back_Voxel(set, {{c.x(), c.y(), c.z()}, it.getSize(), color});
    }
    voxels->setBoundingBox(toPoint(lo), toPoint(hi));
    return voxels;
}

gl::CSetOfLines::Ptr makeLines(const std::string& name, mrpt::img::TColor color, float width) {
    auto lines = gl::CSetOfLines::Create();
    lines->setName(name);
    lines->setColor_u8(color);
    lines->setLineWidth(width);
    lines->enableAntiAliasing(false);  // blending washes thin lines out against the voxels
    return lines;
}

gl::CSetOfLines::Ptr makeTrajectory(const std::vector<Eigen::Vector3d>& points) {
    auto lines = makeLines("trajectory", {255, 110, 0}, 3.0f);
    for (std::size_t i = 1; i < points.size(); ++i)
        lines->appendLine(toPoint(points[i - 1]), toPoint(points[i]));
    return lines;
}

gl::CSetOfLines::Ptr makeTree(const std::vector<planning::TreeEdge>& edges) {
    auto lines = makeLines("tree", {0, 110, 40}, 1.0f);
    for (const auto& e : edges)
        lines->appendLine(toPoint(e.from), toPoint(e.to));
    return lines;
}

gl::CSetOfObjects::Ptr makePeople(const SceneContent& c) {
    auto people = gl::CSetOfObjects::Create();
    people->setName("people");
    const Eigen::Vector3d half = 0.5 * c.bodySize;
    for (std::size_t i = 0; i < c.people.size(); ++i) {
        const auto& s = c.people[i];
        auto body = gl::CBox::Create(TPoint3D(-half.x(), -half.y(), 0),
                                     TPoint3D(half.x(), half.y(), c.bodySize.z()));
        body->setName("person_" + std::to_string(i));
        body->setColor_u8(200, 30, 60, 220);
        body->setPose(mrpt::poses::CPose3D(s.position.x(), s.position.y(), 0, s.heading, 0, 0));
        people->insert(body);
    }
    return people;
}

/** Constant-velocity extrapolation of each person's true velocity, drawn at knee height. */
gl::CSetOfLines::Ptr makePredictions(const SceneContent& c) {
    auto lines = makeLines("predicted_paths", {170, 0, 220}, 3.0f);
    const double z = 0.3;
    for (const auto& s : c.people) {
        const Eigen::Vector2d end = s.position + SceneExporter::kPredictionHorizon * s.velocity;
        lines->appendLine(s.position.x(), s.position.y(), z, end.x(), end.y(), z);
    }
    return lines;
}

gl::CBox::Ptr makeDrone(const FlatPose& drone) {
    auto box = gl::CBox::Create(TPoint3D(-0.25, -0.25, -0.08), TPoint3D(0.25, 0.25, 0.08));
    box->setName("drone");
    box->setColor_u8(20, 20, 20);
    const Eigen::Vector3d& p = drone.position;
    box->setPose(mrpt::poses::CPose3D(p.x(), p.y(), p.z(), drone.yaw, 0, 0));
    return box;
}

COpenGLScene buildScene(const SceneContent& c) {
    const Aabb& box = c.map->explorationBox();
    COpenGLScene scene;
    auto viewport = scene.getViewport();
    viewport->setCustomBackgroundColor({0.96f, 0.96f, 0.98f});
    auto& light = viewport->lightParameters();
    light.ambient = {0.55f, 0.55f, 0.55f, 1.0f};
    light.diffuse = {0.5f, 0.5f, 0.5f, 1.0f};
    light.direction = mrpt::math::TVector3Df(-0.3f, 0.45f, -0.84f).unitarize();
    auto grid = gl::CGridPlaneXY::Create(std::floor(box.min.x()) - 1, std::ceil(box.max.x()) + 1,
                                         std::floor(box.min.y()) - 1, std::ceil(box.max.y()) + 1,
                                         0.0f, 1.0f);
    grid->setName("grid");
    grid->setColor_u8(170, 170, 180);
    scene.insert(grid);
    auto frame = gl::CBox::Create(toPoint(box.min), toPoint(box.max), true, 2.0f);
    frame->setName("box");
    frame->setColor_u8(60, 60, 60);
    scene.insert(frame);
    scene.insert(makeVoxels(*c.map));
    scene.insert(makeTrajectory(*c.trajectory));
    scene.insert(makeTree(*c.tree));
    scene.insert(makePeople(c));
    scene.insert(makePredictions(c));
    scene.insert(makeDrone(c.drone));
    return scene;
}

/** Perspective: from the south-west, above, framing the whole exploration box. */
gl::CCamera perspectiveCamera(const Aabb& box) {
    gl::CCamera cam;
    const Eigen::Vector3d centre = box.center();
    cam.setPointingAt(centre.x(), centre.y(), centre.z());
    cam.setProjectiveModel(true);
    cam.setProjectiveFOVdeg(40.0f);
    cam.setAzimuthDegrees(-60.0f);
    cam.setElevationDegrees(55.0f);
    cam.setZoomDistance(static_cast<float>(1.25 * box.size().norm()));
    return cam;
}

/**
 * Top-down, +x right and +y up: a narrow perspective from high above, nearly orthographic
 * (MRPT's orthographic mode scales with the viewport in ways that vary between versions).
 */
gl::CCamera topCamera(const Aabb& box, double aspect) {
    constexpr double kFovDeg = 15.0;
    gl::CCamera cam;
    const Eigen::Vector3d centre = box.center();
    cam.setPointingAt(centre.x(), centre.y(), 0.0);
    cam.setProjectiveModel(true);
    cam.setProjectiveFOVdeg(static_cast<float>(kFovDeg));
    cam.setAzimuthDegrees(-90.0f);
    cam.setElevationDegrees(89.9f);
    const double extent = 1.15 * std::max(box.size().x() / aspect, box.size().y());
    cam.setZoomDistance(static_cast<float>(extent / (2 * std::tan(kFovDeg * M_PI / 360))));
    return cam;
}

void saveScene(const COpenGLScene& scene, const std::string& path) {
    const std::string tmp = path + ".tmp";
    {
        mrpt::io::CFileGZOutputStream out;
        std::string error;
        if (!out.open(tmp, 1, error))
            throw std::runtime_error("cannot write " + tmp + ": " + error);
        mrpt::serialization::archiveFrom(out) << scene;
    }
    std::filesystem::rename(tmp, path);
}

/** MRPT exceptions are multi-line with a call stack: keep the message, on one line. */
std::string oneLine(const std::string& text) {
    const std::size_t begin = text.find("Message:");
    const std::size_t end = text.find("Location:");
    std::string message = begin == std::string::npos || end == std::string::npos || end < begin
                              ? text.substr(0, text.find('\n'))
                              : text.substr(begin + 8, end - begin - 8);
    std::replace(message.begin(), message.end(), '\n', ' ');
    const std::size_t first = message.find_first_not_of(' ');
    const std::size_t last = message.find_last_not_of(' ');
    return first == std::string::npos ? message : message.substr(first, last - first + 1);
}

void savePng(const mrpt::img::CImage& image, const std::string& path) {
    if (!image.saveToFile(path))
        throw std::runtime_error("cannot write " + path);
}

}  // namespace

struct SceneExporter::Impl {
    std::unique_ptr<gl::CFBORender> renderer;
};

SceneExporter::SceneExporter(const OutputParams& params, std::string directory, std::ostream* log)
    : impl_(std::make_unique<Impl>()),
      params_(params),
      directory_(std::move(directory)),
      log_(log),
      renderPng_(params.renderPng) {}

SceneExporter::~SceneExporter() = default;

void SceneExporter::write(const SceneContent& content) {
    COpenGLScene scene = buildScene(content);
    const Aabb& box = content.map->explorationBox();
    scene.getViewport()->getCamera() = perspectiveCamera(box);
    saveScene(scene, directory_ + "/scene.3Dscene");
    if (!renderPng_)
        return;
    try {
        if (!impl_->renderer)
            impl_->renderer = std::make_unique<gl::CFBORender>(params_.pngWidth, params_.pngHeight);
        auto& fbo = *impl_->renderer;
        mrpt::img::CImage image;
        fbo.setCamera(scene, perspectiveCamera(box));
        fbo.render_RGB(scene, image);
        savePng(image, directory_ + "/scene_perspective.png");
        auto voxels = scene.getByClass<gl::COctoMapVoxels>();
        voxels->showVoxels(kVoxelsAbove, false);
        fbo.setCamera(scene, topCamera(box, double(params_.pngWidth) / params_.pngHeight));
        fbo.render_RGB(scene, image);
        savePng(image, directory_ + "/scene_top.png");
    } catch (const std::exception& e) {
        renderPng_ = false;
        impl_->renderer.reset();
        const std::string what = oneLine(e.what());
        (log_ ? *log_ : std::cerr) << "warning: cannot render the scene to PNG (no EGL/OpenGL?), "
                                      "skipping PNGs: "
                                   << what << std::endl;
    }
}

}  // namespace daep::mission
