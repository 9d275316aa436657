#include <mrpt/containers/yaml.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>

#include "MeshImport.h"
#include "Shapes.h"
#include "StderrCapture.h"
#include "WorldValidation.h"
#include "YamlDuplicateKeys.h"
#include "daep/common/Config.h"
#include "daep/common/Error.h"
#include "daep/common/FileChecks.h"
#include "daep/world/VoxelMaps.h"
#include "daep/world/WorldSpec.h"

namespace fs = std::filesystem;

namespace daep::world {
namespace {

using mrpt::containers::yaml;
using YNode = yaml::node_t;

constexpr double kDeg = M_PI / 180.0;
constexpr double kGroundThickness = 0.1;
constexpr double kGroundMargin = 2.0;

/** A YAML value plus its key path and line, so that every error can say where it is. */
class Field {
public:
    Field(const YNode& node, std::string path, int line0, const std::string& file)
        : node_(&node), path_(std::move(path)), line0_(line0), file_(&file) {}

    [[noreturn]] void fail(const std::string& what) const {
        std::string msg = *file_;
        if (line0_ >= 0)
            msg += ":" + std::to_string(line0_ + 1);
        msg += ": ";
        if (!path_.empty())
            msg += path_ + ": ";
        throw InputError(msg + what);
    }

    std::optional<Field> find(const std::string& key) const {
        requireMap();
        for (const auto& [k, v] : node_->asMap()) {
            if (k.isScalar() && k.as<std::string>() == key)
                return Field(v, childPath(key), v.isNullNode() ? k.marks.line : v.marks.line,
                             *file_);
        }
        return std::nullopt;
    }

    Field at(const std::string& key) const {
        if (auto f = find(key))
            return *f;
        fail("required key '" + key + "' is missing");
    }

    void allowOnly(const std::vector<std::string>& keys) const {
        requireMap();
        for (const auto& [k, v] : node_->asMap()) {
            const std::string name = k.isScalar() ? k.as<std::string>() : "?";
            if (std::find(keys.begin(), keys.end(), name) != keys.end())
                continue;
            std::string known;
            for (const auto& key : keys)
                known += (known.empty() ? "" : ", ") + key;
            Field(k, childPath(name), k.marks.line, *file_)
                .fail("unknown key (expected one of: " + known + ")");
        }
    }

    std::vector<Field> items() const {
        if (!node_->isSequence())
            fail("expected a list, got " + typeName());
        std::vector<Field> out;
        const auto& seq = node_->asSequence();
        for (std::size_t i = 0; i < seq.size(); ++i) {
            const int line = seq[i].isNullNode() ? line0_ : seq[i].marks.line;
            out.emplace_back(seq[i], path_ + "[" + std::to_string(i) + "]", line, *file_);
        }
        return out;
    }

    std::string text() const {
        if (!node_->isScalar())
            fail("expected a text, got " + typeName());
        return node_->as<std::string>();
    }

    double number() const {
        if (!node_->isScalar())
            fail("expected a number, got " + typeName());
        const std::string s = node_->as<std::string>();
        char* end = nullptr;
        const double d = std::strtod(s.c_str(), &end);
        if (s.empty() || *end != '\0' || !std::isfinite(d))
            fail("'" + s + "' is not a number");
        return d;
    }

    double positive() const {
        const double d = number();
        if (d <= 0.0)
            fail("must be > 0, got " + node_->as<std::string>());
        return d;
    }

    bool boolean() const {
        const std::string s = text();
        if (s == "true" || s == "True" || s == "yes")
            return true;
        if (s == "false" || s == "False" || s == "no")
            return false;
        fail("'" + s + "' is not a boolean (true|false)");
    }

    Eigen::VectorXd numbers(std::size_t n) const {
        const std::vector<Field> list = node_->isSequence() ? items() : std::vector<Field>{};
        if (list.size() != n)
            fail("expected " + std::to_string(n) + " numbers, got " + describeCount());
        Eigen::VectorXd v(static_cast<Eigen::Index>(n));
        for (std::size_t i = 0; i < n; ++i)
            v[static_cast<Eigen::Index>(i)] = list[i].number();
        return v;
    }

    Eigen::Vector3d vec3() const { return numbers(3); }
    Eigen::Vector2d vec2() const { return numbers(2); }

    Eigen::Vector3d positiveVec3() const {
        const Eigen::Vector3d v = vec3();
        if ((v.array() <= 0.0).any())
            fail("all 3 numbers must be > 0");
        return v;
    }

    const std::string& path() const { return path_; }
    bool isScalar() const { return node_->isScalar(); }

private:
    void requireMap() const {
        if (!node_->isMap())
            fail("expected a map of keys, got " + typeName());
    }
    std::string childPath(const std::string& key) const {
        return path_.empty() ? key : path_ + "." + key;
    }
    std::string typeName() const {
        if (node_->isNullNode())
            return "nothing";
        if (node_->isScalar())
            return "'" + node_->as<std::string>() + "'";
        return node_->isMap() ? "a map" : "a list";
    }
    std::string describeCount() const {
        if (!node_->isSequence())
            return typeName();
        return std::to_string(node_->asSequence().size());
    }

    const YNode* node_;
    std::string path_;
    int line0_;
    const std::string* file_;
};

std::size_t indentOf(const std::string& line) {
    return line.find_first_not_of(' ');
}

bool isBlankOrComment(const std::string& line) {
    const auto i = line.find_first_not_of(" \t\r");
    return i == std::string::npos || line[i] == '#';
}

/** Best effort for MRPT's line-less "empty scalar" error: the first `key:` with no value. */
std::optional<int> findEmptyValueLine(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream is(text);
    for (std::string l; std::getline(is, l);)
        lines.push_back(l);
    static const std::regex keyOnly(R"(^(\s*(?:-\s+)?)[^\s#\-][^:#]*:\s*(#.*)?\r?$)");
    static const std::regex emptyFlowItem(R"([\[,]\s*,|:\s*,)");
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (std::regex_search(lines[i], emptyFlowItem))
            return static_cast<int>(i);
        std::smatch m;
        if (!std::regex_match(lines[i], m, keyOnly))
            continue;
        const std::size_t keyCol = m[1].length();
        std::size_t j = i + 1;
        while (j < lines.size() && isBlankOrComment(lines[j]))
            ++j;
        if (j == lines.size())
            return static_cast<int>(i);
        const std::size_t next = indentOf(lines[j]);
        const bool child = next > keyCol || (next == keyCol && lines[j].compare(next, 1, "-") == 0);
        if (!child)
            return static_cast<int>(i);
    }
    return std::nullopt;
}

std::string mrptMessage(const std::string& what) {
    std::string msg = what;
    if (const auto p = msg.find("Message:"); p != std::string::npos)
        msg = msg.substr(p + 8);
    msg = msg.substr(0, msg.find('\n'));
    if (const auto p = msg.find(" Re-run with"); p != std::string::npos)
        msg.resize(p);
    const auto b = msg.find_first_not_of(' ');
    return b == std::string::npos ? std::string("unreadable YAML") : msg.substr(b);
}

std::string syntaxError(const std::string& file, const std::string& text,
                        const std::string& diagnostics, const std::string& what) {
    static const std::regex located(R"(:(\d+):(\d+): error: ([^\n]*))");
    std::smatch m;
    if (std::regex_search(diagnostics, m, located))
        return file + ":" + m[1].str() + ":" + m[2].str() + ": YAML syntax error: " + m[3].str();
    if (what.find("empty scalar") != std::string::npos) {
        if (const auto line = findEmptyValueLine(text))
            return file + ":" + std::to_string(*line + 1) +
                   ": YAML syntax error: a key or list item has no value";
    }
    return file + ": YAML syntax error: " + mrptMessage(what);
}

/**
 * Bytes after `lead` in its UTF-8 sequence, and the range its first continuation byte must lie
 * in (RFC 3629: no overlong forms, no surrogates, nothing beyond U+10FFFF); -1 if no lead.
 */
int utf8Continuations(unsigned char lead, unsigned char& low, unsigned char& high) {
    low = 0x80;
    high = 0xbf;
    if (lead < 0x80)
        return 0;
    if (lead >= 0xc2 && lead <= 0xdf)
        return 1;
    if (lead >= 0xe0 && lead <= 0xef) {
        low = lead == 0xe0 ? 0xa0 : 0x80;
        high = lead == 0xed ? 0x9f : 0xbf;
        return 2;
    }
    if (lead >= 0xf0 && lead <= 0xf4) {
        low = lead == 0xf0 ? 0x90 : 0x80;
        high = lead == 0xf4 ? 0x8f : 0xbf;
        return 3;
    }
    return -1;
}

/** The 1-based line of the first byte sequence that is not UTF-8 in `text`; 0 if none. */
int firstLineNotUtf8(const std::string& text) {
    int line = 1;
    for (std::size_t i = 0; i < text.size();) {
        const auto c = static_cast<unsigned char>(text[i]);
        unsigned char low = 0, high = 0;
        const int more = utf8Continuations(c, low, high);
        if (more < 0 || text.size() - i <= static_cast<std::size_t>(more))
            return line;
        for (int k = 1; k <= more; ++k) {
            const auto b = static_cast<unsigned char>(text[i + k]);
            if (b < (k == 1 ? low : 0x80) || b > (k == 1 ? high : 0xbf))
                return line;
        }
        line += c == '\n';
        i += 1 + static_cast<std::size_t>(more);
    }
    return 0;
}

yaml parseYaml(const std::string& text, const std::string& file) {
    // YAML is Unicode text; libfyaml loops forever on some invalid bytes (a '%' directive
    // followed by 0xff: found by fuzz_world_file), so they are refused before it sees them.
    if (const int line = firstLineNotUtf8(text))
        throw InputError(file + ":" + std::to_string(line) + ": not UTF-8 text");
    StderrCapture capture;
    yaml doc;
    try {
        doc = yaml::FromText(text);
    } catch (const std::exception& e) {
        const std::string diagnostics = capture.finish();
        throw InputError(syntaxError(file, text, diagnostics, e.what()));
    }
    const std::string diagnostics = capture.finish();
    // Some libfyaml errors end the parse early without MRPT throwing: a truncated document.
    if (diagnostics.find(": error: ") != std::string::npos)
        throw InputError(syntaxError(file, text, diagnostics, ""));
    if (!diagnostics.empty())
        std::fputs(diagnostics.c_str(), stderr);
    return doc;
}

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in || daep::isDirectory(path))
        throw InputError(path + ": cannot read the world file");
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string nameOr(const Field& f, const std::string& fallback) {
    const auto n = f.find("name");
    return n ? n->text() : fallback;
}

Eigen::Matrix3d parseRotation(const Field& f) {
    const auto yaw = f.find("yaw_deg");
    const auto rpy = f.find("rpy_deg");
    if (yaw && rpy)
        rpy->fail("give either yaw_deg or rpy_deg, not both");
    Eigen::Vector3d angles = Eigen::Vector3d::Zero();
    if (yaw)
        angles.z() = yaw->number();
    if (rpy)
        angles = rpy->vec3();
    return rotationFromRpy(angles * kDeg);
}

Eigen::Isometry3d parsePose(const Field& f, const std::string& positionKey) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = parseRotation(f);
    pose.translation() = f.at(positionKey).vec3();
    return pose;
}

Aabb parseExplorationBox(const Field& f) {
    f.allowOnly({"min", "max"});
    Aabb box;
    box.min = f.at("min").vec3();
    box.max = f.at("max").vec3();
    if ((box.max.array() <= box.min.array()).any())
        f.fail("max must exceed min on every axis");
    return box;
}

BoxShape parseBox(const Field& f) {
    f.allowOnly({"name", "center", "size", "yaw_deg", "rpy_deg"});
    BoxShape b;
    b.name = nameOr(f, f.path());
    b.pose = parsePose(f, "center");
    b.size = f.at("size").positiveVec3();
    return b;
}

CylinderShape parseCylinder(const Field& f) {
    f.allowOnly({"name", "center", "radius", "length", "yaw_deg", "rpy_deg"});
    CylinderShape c;
    c.name = nameOr(f, f.path());
    c.pose = parsePose(f, "center");
    c.radius = f.at("radius").positive();
    c.length = f.at("length").positive();
    return c;
}

TriangleMesh parseMesh(const Field& f, const fs::path& baseDir) {
    f.allowOnly({"name", "file", "position", "yaw_deg", "rpy_deg", "scale"});
    const Field fileField = f.at("file");
    const std::string rel = fileField.text();
    const fs::path file = fs::path(rel).is_absolute() ? fs::path(rel) : baseDir / rel;
    if (!daep::isRegularFile(file))
        fileField.fail("mesh file '" + rel + "' not found (looked for " + file.string() + ")");
    const auto position = f.find("position");
    const auto scale = f.find("scale");
    Eigen::Affine3d transform = Eigen::Affine3d::Identity();
    transform.translate(position ? position->vec3() : Eigen::Vector3d::Zero());
    transform.rotate(parseRotation(f));
    transform.scale(scale ? scale->positiveVec3() : Eigen::Vector3d::Ones());

    TriangleMesh mesh;
    mesh.name = nameOr(f, f.path());
    mesh.source = file.string();
    std::string error;
    if (!importMesh(file.string(), transform, mesh, error))
        fileField.fail("cannot load mesh '" + rel + "': " + error);
    if (mesh.triangles.empty())
        fileField.fail("mesh '" + rel + "' has no triangles");
    return mesh;
}

PersonRoute parsePerson(const Field& f) {
    f.allowOnly({"name", "waypoints"});
    PersonRoute route;
    route.name = nameOr(f, f.path());
    const Field wps = f.at("waypoints");
    for (const Field& w : wps.items())
        route.waypoints.push_back(w.vec2());
    if (route.waypoints.size() < 2)
        wps.fail("a person needs at least 2 waypoints, got " +
                 std::to_string(route.waypoints.size()));
    return route;
}

/** A data file named by a world key, relative to the world file's directory. */
std::string dataFile(const Field& fileField, const fs::path& baseDir, const std::string& what) {
    const std::string rel = fileField.text();
    const fs::path file = fs::path(rel).is_absolute() ? fs::path(rel) : baseDir / rel;
    if (!daep::isRegularFile(file))
        fileField.fail(what + " file '" + rel + "' not found (looked for " + file.string() + ")");
    return file.string();
}

/** Runs a voxel map loader; its InputError (naming the data file) gets the world file's line. */
template <typename Load>
VoxelMap loadVoxels(const Field& fileField, Load&& load) {
    try {
        return load();
    } catch (const InputError& e) {
        fileField.fail(e.what());
    }
}

/** `octomap: FILE` or `octomap: {file: FILE, position: [x, y, z]}`. */
VoxelMap parseOctomap(const Field& f, const fs::path& baseDir) {
    if (f.isScalar()) {
        const std::string file = dataFile(f, baseDir, "octomap");
        return loadVoxels(f, [&] { return loadOctomap(file, Eigen::Vector3d::Zero()); });
    }
    f.allowOnly({"file", "position"});
    const Field fileField = f.at("file");
    const std::string file = dataFile(fileField, baseDir, "octomap");
    const auto position = f.find("position");
    const Eigen::Vector3d offset = position ? position->vec3() : Eigen::Vector3d::Zero();
    return loadVoxels(fileField, [&] { return loadOctomap(file, offset); });
}

/** `point_cloud: {file: FILE.ply, voxel_size: S, position: [x, y, z]}`. */
VoxelMap parsePointCloud(const Field& f, const fs::path& baseDir) {
    f.allowOnly({"file", "voxel_size", "position"});
    const Field fileField = f.at("file");
    const std::string file = dataFile(fileField, baseDir, "point cloud");
    const double voxelSize = f.at("voxel_size").positive();
    const auto position = f.find("position");
    const Eigen::Vector3d offset = position ? position->vec3() : Eigen::Vector3d::Zero();
    return loadVoxels(fileField, [&] { return voxelisePointCloud(file, voxelSize, offset); });
}

void parseVoxelMaps(const Field& top, const fs::path& baseDir, WorldSpec& w) {
    if (const auto f = top.find("octomap"))
        w.voxelMaps.push_back(parseOctomap(*f, baseDir));
    if (const auto f = top.find("point_cloud"))
        w.voxelMaps.push_back(parsePointCloud(*f, baseDir));
}

template <typename Parse>
void parseList(const Field& top, const std::string& key, Parse&& parse) {
    if (const auto list = top.find(key)) {
        for (const Field& item : list->items())
            parse(item);
    }
}

BoxShape groundSlab(const WorldSpec& world) {
    const Aabb b = world.bounds();
    BoxShape ground;
    ground.name = "ground";
    ground.pose.translation() =
        Eigen::Vector3d(b.center().x(), b.center().y(), -0.5 * kGroundThickness);
    ground.size = Eigen::Vector3d(b.size().x() + 2.0 * kGroundMargin,
                                  b.size().y() + 2.0 * kGroundMargin, kGroundThickness);
    return ground;
}

void parseTop(const Field& top, const std::string& path, WorldSpec& w) {
    top.allowOnly({"name", "description", "exploration_box", "exploration_volume", "starts",
                   "ground", "boxes", "cylinders", "meshes", "people", "octomap", "point_cloud"});
    const auto name = top.find("name");
    w.name = name ? name->text() : fs::path(path).stem().string();
    if (const auto d = top.find("description"))
        w.description = d->text();
    w.explorationBox = parseExplorationBox(top.at("exploration_box"));
    if (const auto v = top.find("exploration_volume"))
        w.declaredVolume = v->positive();

    const Field starts = top.at("starts");
    for (const Field& s : starts.items())
        w.starts.push_back(s.vec3());
    if (w.starts.empty())
        starts.fail("at least one start position is needed");

    const fs::path baseDir = fs::path(path).parent_path();
    parseList(top, "boxes", [&](const Field& f) { w.boxes.push_back(parseBox(f)); });
    parseList(top, "cylinders", [&](const Field& f) { w.cylinders.push_back(parseCylinder(f)); });
    parseList(top, "meshes", [&](const Field& f) { w.meshes.push_back(parseMesh(f, baseDir)); });
    parseVoxelMaps(top, baseDir, w);
    parseList(top, "people", [&](const Field& f) { w.people.push_back(parsePerson(f)); });

    const auto ground = top.find("ground");
    if (ground && ground->boolean())
        w.boxes.push_back(groundSlab(w));
}

void extend(Aabb& box, const Eigen::Vector3d& p) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
}

}  // namespace

Aabb WorldSpec::bounds() const {
    Aabb b = explorationBox;
    for (const auto& box : boxes)
        for (const auto& c : boxCorners(box.pose, box.size))
            extend(b, c);
    for (const auto& cyl : cylinders) {
        const Eigen::Vector3d size(2 * cyl.radius, 2 * cyl.radius, cyl.length);
        for (const auto& c : boxCorners(cyl.pose, size))
            extend(b, c);
    }
    for (const auto& mesh : meshes)
        for (const auto& v : mesh.vertices)
            extend(b, v.cast<double>());
    for (const auto& map : voxelMaps)
        for (const auto& box : map.boxes) {
            extend(b, box.min);
            extend(b, box.max);
        }
    return b;
}

WorldSpec loadWorldFile(const std::string& path) {
    const std::string text = readText(path);
    const yaml doc = parseYaml(text, path);
    if (const auto dup = findDuplicateKey(text))
        throw InputError(path + ":" + std::to_string(dup->line) + ": duplicate key '" + dup->key +
                         "' (first given on line " + std::to_string(dup->firstLine) + ")");
    const YNode& root = doc.node();
    if (!root.isMap())
        throw InputError(path +
                         ": the world file must be a map of keys (name, exploration_box, "
                         "starts, boxes, ...)");
    WorldSpec world;
    world.sourceFile = path;
    parseTop(Field(root, "", -1, path), path, world);
    validateWorld(world);
    return world;
}

std::vector<std::string> builtinWorldNames() {
    std::vector<std::string> names;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(fs::path(shareDirectory()) / "worlds", ec)) {
        if (e.is_regular_file() && e.path().extension() == ".yaml")
            names.push_back(e.path().stem().string());
    }
    std::sort(names.begin(), names.end());
    return names;
}

std::string resolveWorldPath(const std::string& nameOrPath) {
    if (daep::isRegularFile(nameOrPath))
        return nameOrPath;
    const fs::path builtin = fs::path(shareDirectory()) / "worlds" / (nameOrPath + ".yaml");
    if (!nameOrPath.empty() && daep::isRegularFile(builtin))
        return builtin.string();
    std::string known;
    for (const auto& n : builtinWorldNames())
        known += (known.empty() ? "" : ", ") + n;
    throw InputError("world '" + nameOrPath + "': no such file and no such built-in world (" +
                     (known.empty() ? "none found in " + shareDirectory() + "/worlds" : known) +
                     ")");
}

}  // namespace daep::world
