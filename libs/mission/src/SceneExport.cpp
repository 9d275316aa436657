#include "SceneExport.h"

#include <mrpt/img/CImage.h>
#include <mrpt/img/color_maps.h>
#include <mrpt/io/CFileGZInputStream.h>
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

#include <cstdio>
#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <stdexcept>

#include "daep/common/Error.h"
#include "daep/common/Sanitizers.h"
#include "daep/eval/ImageOverlay.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/SceneColors.h"
#include "daep/perception/PeopleTracker.h"

namespace daep::mission {
namespace {

using mrpt::math::TPoint3D;
using mrpt::opengl::COpenGLScene;
namespace gl = mrpt::opengl;

constexpr unsigned kVoxelsInBox = 0;
constexpr unsigned kVoxelsAbove = 1;  ///< ceilings: hidden in the top-down render
/** Drawn over the voxels in the PNGs, so walls and ceilings never hide them. */
const std::vector<std::string> kOnTop = {"trajectory", "predicted_paths", "drone"};

TPoint3D toPoint(const Eigen::Vector3d& p) {
    return {p.x(), p.y(), p.z()};
}

mrpt::img::TColor toColor(SceneColor c, unsigned char alpha = 255) {
    return {c.r, c.g, c.b, alpha};
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
        const auto color = toColor(voxelColor((p.z() - box.min.z()) / zSpan));
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
    auto lines = makeLines("trajectory", toColor(kTrajectoryColor), 3.0f);
    for (std::size_t i = 1; i < points.size(); ++i)
        lines->appendLine(toPoint(points[i - 1]), toPoint(points[i]));
    return lines;
}

gl::CSetOfLines::Ptr makeTree(const std::vector<planning::TreeEdge>& edges) {
    // Thin and light: context for the plan, not the subject of the picture.
    auto lines = makeLines("tree", toColor(kTreeColor, 110), 1.0f);
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
        body->setColor_u8(toColor(kPersonColor));
        body->setPose(mrpt::poses::CPose3D(s.position.x(), s.position.y(), 0, s.heading, 0, 0));
        people->insert(body);
    }
    return people;
}

/** Constant-velocity extrapolation of each person's true velocity, drawn at knee height. */
gl::CSetOfLines::Ptr makePredictions(const SceneContent& c) {
    auto lines = makeLines("predicted_paths", toColor(kPredictionColor), 3.0f);
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
    box->setColor_u8(toColor(kDroneColor));
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

/** A camera and the depth range that holds the scene, for depth precision (no z-fighting). */
struct View {
    gl::CCamera camera;
    float nearClip, farClip;
    double metresPerPixel = 0.0;  ///< on the ground, for a scale bar; 0 in perspective
};

/** Perspective: from the south-west, above, framing the whole exploration box. */
View perspectiveView(const Aabb& box) {
    View v;
    const Eigen::Vector3d centre = box.center();
    const double diagonal = box.size().norm(), distance = 1.25 * diagonal;
    v.camera.setPointingAt(centre.x(), centre.y(), centre.z());
    v.camera.setProjectiveModel(true);
    v.camera.setProjectiveFOVdeg(40.0f);
    v.camera.setAzimuthDegrees(-60.0f);
    v.camera.setElevationDegrees(55.0f);
    v.camera.setZoomDistance(static_cast<float>(distance));
    // The grid reaches 1 m beyond the box on every side.
    v.nearClip = static_cast<float>(std::max(0.05, 0.1 * distance));
    v.farClip = static_cast<float>(distance + diagonal + 4.0);
    return v;
}

/**
 * Top-down, +x right and +y up: a narrow perspective from high above, nearly orthographic
 * (MRPT's orthographic mode scales with the viewport in ways that vary between versions).
 */
View topView(const Aabb& box, int width, int height) {
    constexpr double kFovDeg = 15.0;
    View v;
    const Eigen::Vector3d centre = box.center();
    v.camera.setPointingAt(centre.x(), centre.y(), 0.0);
    v.camera.setProjectiveModel(true);
    v.camera.setProjectiveFOVdeg(static_cast<float>(kFovDeg));
    v.camera.setAzimuthDegrees(-90.0f);
    v.camera.setElevationDegrees(89.9f);
    const double aspect = double(width) / height;
    const double extent = 1.15 * std::max(box.size().x() / aspect, box.size().y());
    const double distance = extent / (2 * std::tan(kFovDeg * M_PI / 360));
    v.camera.setZoomDistance(static_cast<float>(distance));
    const double depth = std::max(box.max.z(), 0.0) - std::min(box.min.z(), 0.0) + 2.0;
    v.nearClip = static_cast<float>(std::max(0.05, distance - box.max.z() - 2.0));
    v.farClip = static_cast<float>(distance + depth);
    v.metresPerPixel = extent / height;  // the field of view is vertical
    return v;
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

eval::Rgb toRgb(SceneColor c) {
    return {c.r, c.g, c.b};
}

/**
 * Headless GL draws lines 1 px wide whatever their width: the trajectory gets copies shifted
 * by about a pixel (`step` metres) in x and y, which read as one bold line.
 */
void thicken(gl::CSetOfLines& lines, double step) {
    const std::size_t n = lines.getLineCount();
    for (const auto& [dx, dy] : {std::pair{step, 0.0}, {-step, 0.0}, {0.0, step}, {0.0, -step}}) {
        for (std::size_t i = 0; i < n; ++i) {
            double x0, y0, z0, x1, y1, z1;
            lines.getLineByIndex(i, x0, y0, z0, x1, y1, z1);
            lines.appendLine(x0 + dx, y0 + dy, z0, x1 + dx, y1 + dy, z1);
        }
    }
}

/** Moves the objects named in kOnTop into a viewport drawn after the main one (its own depth). */
void liftOnTop(COpenGLScene& scene, double pixelMetres) {
    if (auto trajectory = scene.getByName("trajectory"))
        thicken(dynamic_cast<gl::CSetOfLines&>(*trajectory), 0.7 * pixelMetres);
    auto overlay = scene.createViewport("on_top");
    overlay->setTransparent(true);
    for (const auto& name : kOnTop)
        if (auto object = scene.getByName(name)) {
            scene.removeObject(object);
            overlay->insert(object);
        }
}

eval::Overlay overlayFor(const Aabb& box, const std::string& title) {
    using Shape = eval::LegendSwatch::Shape;
    eval::Overlay o;
    o.title = title;
    o.legend = {{"trajectory", toRgb(kTrajectoryColor), Shape::Line},
                {"drone", toRgb(kDroneColor), Shape::Box},
                {"people (true position)", toRgb(kPersonColor), Shape::Box},
                {"predicted paths (10 s ahead)", toRgb(kPredictionColor), Shape::Line},
                {"last planning tree", toRgb(kTreeColor), Shape::Thin},
                {"exploration box", {60, 60, 60}, Shape::Thin}};
    for (double h = 0.0; h <= 1.0 + 1e-9; h += 0.125)
        o.colorBar.stops.push_back(toRgb(voxelColor(h)));
    char low[32], high[32];
    std::snprintf(low, sizeof low, "%.1f m", box.min.z());
    std::snprintf(high, sizeof high, "%.1f m", box.max.z());
    o.colorBar = {"occupied voxels by height", o.colorBar.stops, low, high};
    return o;
}

/** Renders `view` (every viewport gets its camera and depth range) and writes the PNG. */
void renderView(gl::CFBORender& fbo, COpenGLScene& scene, const View& view,
                const eval::Overlay& overlay, const std::string& path) {
    for (const auto& viewport : scene.viewports()) {
        viewport->getCamera() = view.camera;
        viewport->setViewportClipDistances(view.nearClip, view.farClip);
    }
    fbo.setCamera(scene, view.camera);
    mrpt::img::CImage image;
    fbo.render_RGB(scene, image);
    const cv::Mat& bgr = image.asCvMatRef();
    eval::writeAnnotatedPng(bgr.ptr<unsigned char>(0), bgr.cols, bgr.rows, bgr.step, overlay, path);
}

void renderPngs(gl::CFBORender& fbo, COpenGLScene& scene, const Aabb& box,
                const std::string& directory, int width, int height) {
    liftOnTop(scene, 1.15 * std::max(box.size().x(), box.size().y()) / height);
    const View perspective = perspectiveView(box);
    eval::Overlay overlay = overlayFor(box, "Perspective view");
    overlay.legend.push_back(
        {"ground grid: 1 m", {170, 170, 180}, eval::LegendSwatch::Shape::Thin});
    renderView(fbo, scene, perspective, overlay, directory + "/scene_perspective.png");

    scene.getByClass<gl::COctoMapVoxels>()->showVoxels(kVoxelsAbove, false);
    const View top = topView(box, width, height);
    overlay = overlayFor(box, "Top view");
    overlay.metresPerPixel = top.metresPerPixel;
    renderView(fbo, scene, top, overlay, directory + "/scene_top.png");
}

}  // namespace

SceneColor voxelColor(double heightFraction) {
    const double h = std::isnan(heightFraction) ? 0.0 : std::clamp(heightFraction, 0.0, 1.0);
    const auto c = mrpt::img::colormap(mrpt::img::cmJET, float(0.15 + 0.75 * h));
    return {c.R, c.G, c.B};
}

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
    scene.getViewport()->getCamera() = perspectiveView(box).camera;
    saveScene(scene, directory_ + "/scene.3Dscene");
    if (!renderPng_)
        return;
    try {
        if (!impl_->renderer) {
            leakCheckBeforeDynamicTls();
            impl_->renderer = std::make_unique<gl::CFBORender>(params_.pngWidth, params_.pngHeight);
        }
        renderPngs(*impl_->renderer, scene, box, directory_, params_.pngWidth, params_.pngHeight);
    } catch (const std::exception& e) {
        renderPng_ = false;
        impl_->renderer.reset();
        const std::string what = oneLine(e.what());
        (log_ ? *log_ : std::cerr) << "warning: cannot render the scene to PNG (no EGL/OpenGL?), "
                                      "skipping PNGs: "
                                   << what << std::endl;
    }
}

void renderSceneFile(const std::string& directory, int width, int height) {
    const std::string path = directory + "/scene.3Dscene";
    if (!std::filesystem::is_regular_file(path))
        throw InputError("no scene to render: " + path + " does not exist");
    COpenGLScene scene;
    try {
        mrpt::io::CFileGZInputStream in(path);
        mrpt::serialization::archiveFrom(in) >> scene;
    } catch (const std::exception& e) {
        throw InputError("cannot read the scene " + path + ": " + oneLine(e.what()));
    }
    const auto frame = std::dynamic_pointer_cast<gl::CBox>(scene.getByName("box"));
    if (!frame || !scene.getByClass<gl::COctoMapVoxels>())
        throw InputError(path + ": not a daep-explore scene (no exploration box or voxels)");
    TPoint3D low, high;
    frame->getBoxCorners(low, high);
    const Aabb box{{low.x, low.y, low.z}, {high.x, high.y, high.z}};
    try {
        leakCheckBeforeDynamicTls();
        gl::CFBORender renderer(width, height);
        renderPngs(renderer, scene, box, directory, width, height);
    } catch (const std::exception& e) {
        throw std::runtime_error("cannot render " + path +
                                 " (no EGL/OpenGL?): " + oneLine(e.what()));
    }
}

std::vector<world::PersonState> tracksAsPeople(
    double t, const std::vector<perception::PersonForecast>& tracks) {
    std::vector<world::PersonState> out;
    for (const perception::PersonForecast& f : tracks) {
        world::PersonState p;
        p.position = f.at(t).mean;
        p.velocity = f.velocity();
        p.heading = std::atan2(p.velocity.y(), p.velocity.x());
        out.push_back(p);
    }
    return out;
}

}  // namespace daep::mission
