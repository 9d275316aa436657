// ImportedWorld -> world-format YAML (WORLD_FORMAT.md).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <limits>
#include <sstream>

#include "MeshImport.h"
#include "daep/common/Error.h"
#include "daep/world/GazeboImport.h"

namespace daep::world {
namespace {

namespace fs = std::filesystem;
constexpr double kRadToDeg = 180.0 / M_PI;

/** Fixed 4 decimals, without "-0.0000". */
std::string num(double v) {
    std::ostringstream ss;
    ss << std::fixed << std::setprecision(4) << v;
    std::string s = ss.str();
    if (s.find_first_not_of("-0.") == std::string::npos)
        s = "0.0000";
    return s;
}

std::string list(const std::vector<double>& v) {
    std::string s = "[";
    for (size_t i = 0; i < v.size(); ++i)
        s += (i ? ", " : "") + num(v[i]);
    return s + "]";
}

std::string vec(const Eigen::Vector3d& v) {
    return list({v.x(), v.y(), v.z()});
}

std::string quoted(const std::string& s) {
    std::string q = "\"";
    for (char c : s)
        q += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    return q + "\"";
}

/** Roll, pitch, yaw (R = Rz Ry Rx) of a rotation matrix. */
Eigen::Vector3d rpyOf(const Eigen::Matrix3d& r) {
    const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
    return {std::atan2(r(2, 1), r(2, 2)), pitch, std::atan2(r(1, 0), r(0, 0))};
}

/** ", yaw_deg: a" for a pure yaw, else ", rpy_deg: [r, p, y]". */
std::string orientation(const Eigen::Matrix3d& r) {
    const Eigen::Vector3d rpy = rpyOf(r);
    if (std::abs(r(2, 2) - 1.0) < 1e-9)
        return ", yaw_deg: " + num(rpy.z() * kRadToDeg);
    return ", rpy_deg: " + vec(rpy * kRadToDeg);
}

std::string relativeFile(const std::string& file, const std::string& yamlDir) {
    // Relative when both share a top-level directory, else absolute (no "../../work/...").
    const fs::path dir = fs::absolute(yamlDir).lexically_normal();
    const fs::path target = fs::path(file).lexically_normal();
    const bool shareTop = dir.begin() != dir.end() && std::next(dir.begin()) != dir.end() &&
                          std::next(target.begin()) != target.end() &&
                          *std::next(dir.begin()) == *std::next(target.begin());
    const fs::path rel = target.lexically_relative(dir);
    return shareTop && !rel.empty() ? rel.string() : file;
}

/** Bounds of all geometry (meshes read from disk), for worlds without a box config. */
Aabb geometryBounds(const ImportedWorld& w) {
    WorldSpec spec;
    spec.explorationBox.min.setConstant(std::numeric_limits<double>::infinity());
    spec.explorationBox.max.setConstant(-std::numeric_limits<double>::infinity());
    spec.boxes = w.boxes;
    spec.cylinders = w.cylinders;
    for (const auto& m : w.meshes) {
        TriangleMesh mesh;
        std::string error;
        Eigen::Affine3d t(m.pose.matrix());
        t.scale(m.scale);
        if (!importMesh(m.file, t, mesh, error))
            throw InputError(m.file + ": " + error);
        spec.meshes.push_back(std::move(mesh));
    }
    const Aabb b = spec.bounds();
    if (!(b.max.array() > b.min.array()).all())
        throw InputError(w.source + ": no geometry to take the exploration box from");
    return b;
}

void writeHeader(std::ostream& os, const ImportedWorld& w) {
    os << "# World '" << w.name << "' imported by `daep-world import` (format:\n"
       << "# libs/world/WORLD_FORMAT.md) from the Gazebo world\n#   " << w.source << "\n"
       << "# Static geometry: the collision shapes at their effective poses.\n";
    if (!w.hasBox)
        os << "# exploration_box: the bounds of the geometry (no --box-config given)\n";
    if (w.starts.empty())
        os << "# starts: the box centre (no --starts given)\n";
    for (const auto& warning : w.warnings)
        os << "# warning: " << warning << "\n";
}

void writeShapes(std::ostream& os, const ImportedWorld& w, const std::string& yamlDir) {
    if (!w.boxes.empty())
        os << "boxes:\n";
    for (const auto& b : w.boxes)
        os << "  - {name: " << quoted(b.name) << ", center: " << vec(b.pose.translation())
           << ", size: " << vec(b.size) << orientation(b.pose.linear()) << "}\n";
    if (!w.cylinders.empty())
        os << "cylinders:\n";
    for (const auto& c : w.cylinders)
        os << "  - {name: " << quoted(c.name) << ", center: " << vec(c.pose.translation())
           << ", radius: " << num(c.radius) << ", length: " << num(c.length)
           << orientation(c.pose.linear()) << "}\n";
    if (!w.meshes.empty())
        os << "meshes:\n";
    for (const auto& m : w.meshes)
        os << "  - {name: " << quoted(m.name) << ", file: " << quoted(relativeFile(m.file, yamlDir))
           << ", position: " << vec(m.pose.translation()) << orientation(m.pose.linear())
           << ", scale: " << vec(m.scale) << "}\n";
}

void writePeople(std::ostream& os, const ImportedWorld& w) {
    if (!w.people.empty())
        os << "people:\n";
    for (const auto& p : w.people) {
        os << "  - name: " << quoted(p.name) << "\n    waypoints: [";
        for (size_t i = 0; i < p.waypoints.size(); ++i)
            os << (i ? ", " : "") << list({p.waypoints[i].x(), p.waypoints[i].y()});
        os << "]\n";
    }
}

}  // namespace

std::string worldToYaml(const ImportedWorld& w, const std::string& yamlDir) {
    std::ostringstream os;
    writeHeader(os, w);
    const Aabb box = w.hasBox ? w.box : geometryBounds(w);
    os << "name: " << quoted(w.name) << "\n"
       << "exploration_box: {min: " << vec(box.min) << ", max: " << vec(box.max) << "}\n";
    if (w.volume > 0.0)
        os << "exploration_volume: " << num(w.volume) << "\n";
    os << "starts:\n";
    if (w.starts.empty())
        os << "  - " << vec({box.center().x(), box.center().y(), box.min.z() + 0.3}) << "\n";
    for (const auto& s : w.starts)
        os << "  - " << vec(s) << "\n";
    os << "ground: " << (w.ground ? "true" : "false") << "\n";
    writeShapes(os, w, yamlDir);
    writePeople(os, w);
    return os.str();
}

void saveWorldYaml(const ImportedWorld& world, const std::string& yamlPath) {
    const fs::path dir = fs::absolute(yamlPath).parent_path();
    const std::string text = worldToYaml(world, dir.string());
    std::ofstream f(yamlPath);
    if (!(f << text))
        throw InputError(yamlPath + ": cannot write file");
}

}  // namespace daep::world
