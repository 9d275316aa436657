// Gazebo SDF -> ImportedWorld: the collision geometry of a .world file with its includes.
#include "daep/world/GazeboImport.h"

#include <tinyxml2.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "daep/common/Error.h"
#include "daep/common/FileChecks.h"
#include "daep/common/IniText.h"

namespace daep::world {
namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;
using Pose = Eigen::Isometry3d;

/** Parses XML text, throwing "<source>:<line>: XML error ..." when it is malformed. */
void parseXml(tinyxml2::XMLDocument& doc, const std::string& text, const std::string& source) {
    if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS)
        throw InputError(source + ":" + std::to_string(doc.ErrorLineNum()) +
                         ": XML error: " + doc.ErrorStr());
}

/** One SDF file being read: its name for messages and its directory for relative URIs. */
struct SdfFile {
    std::string source;
    std::string dir;

    [[noreturn]] void fail(const XMLElement* e, const std::string& what) const {
        throw InputError(source + ":" + std::to_string(e->GetLineNum()) + ": <" + e->Name() +
                         ">: " + what);
    }
    std::string where(const XMLElement* e) const {
        return source + ":" + std::to_string(e->GetLineNum());
    }
};

std::string childText(const XMLElement* e, const char* child) {
    const XMLElement* c = e->FirstChildElement(child);
    const char* t = c ? c->GetText() : nullptr;
    return t ? std::string(t) : std::string();
}

std::string trim(const std::string& s) {
    const auto a = s.find_first_not_of(" \t\r\n");
    if (a == std::string::npos)
        return "";
    return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
}

/** Exactly `n` numbers of an element's text. */
std::vector<double> numbers(const SdfFile& f, const XMLElement* e, size_t n) {
    std::istringstream ss(e->GetText() ? e->GetText() : "");
    std::vector<double> v;
    std::string tok;
    while (ss >> tok) {
        char* end = nullptr;
        const double x = std::strtod(tok.c_str(), &end);
        if (end == tok.c_str() || *end != '\0' || !std::isfinite(x))
            f.fail(e, "'" + tok + "' is not a number");
        v.push_back(x);
    }
    if (v.size() != n)
        f.fail(e, "expected " + std::to_string(n) + " numbers, got " + std::to_string(v.size()));
    return v;
}

double positiveNumber(const SdfFile& f, const XMLElement* parent, const char* child) {
    const XMLElement* e = parent->FirstChildElement(child);
    if (!e)
        f.fail(parent, std::string("missing <") + child + ">");
    const double v = numbers(f, e, 1)[0];
    if (v <= 0.0)
        f.fail(e, "must be > 0");
    return v;
}

Pose poseFromXyzRpy(const std::vector<double>& v) {
    Pose p = Pose::Identity();
    p.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
    p.linear() = (Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitZ()) *
                  Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitY()) *
                  Eigen::AngleAxisd(v[3], Eigen::Vector3d::UnitX()))
                     .toRotationMatrix();
    return p;
}

/** The element's <pose> (identity when absent); a non-empty frame is not supported. */
Pose childPose(const SdfFile& f, const XMLElement* e) {
    const XMLElement* p = e->FirstChildElement("pose");
    if (!p)
        return Pose::Identity();
    for (const char* attr : {"frame", "relative_to"}) {
        const char* frame = p->Attribute(attr);
        if (frame && *frame)
            f.fail(p, std::string(attr) + "='" + frame + "' is not supported (only '')");
    }
    return poseFromXyzRpy(numbers(f, p, 6));
}

std::string nameOf(const XMLElement* e) {
    const char* n = e->Attribute("name");
    return n ? n : "";
}

/** Effective poses of one model from the world's <state>. */
struct StateModel {
    Pose pose = Pose::Identity();
    std::map<std::string, Pose> links;  ///< world-frame link poses
};

std::map<std::string, StateModel> readState(const SdfFile& f, const XMLElement* world) {
    std::map<std::string, StateModel> out;
    const XMLElement* state = world->FirstChildElement("state");
    if (!state)
        return out;
    for (auto* m = state->FirstChildElement("model"); m; m = m->NextSiblingElement("model")) {
        StateModel sm;
        sm.pose = childPose(f, m);
        for (auto* l = m->FirstChildElement("link"); l; l = l->NextSiblingElement("link"))
            if (l->FirstChildElement("pose"))
                sm.links[nameOf(l)] = childPose(f, l);
        out[nameOf(m)] = sm;
    }
    return out;
}

bool startsWith(const std::string& s, const std::string& prefix) {
    return s.compare(0, prefix.size(), prefix) == 0;
}

std::string joinPaths(const std::vector<std::string>& dirs) {
    std::string s;
    for (const auto& d : dirs)
        s += (s.empty() ? "" : ", ") + d;
    return s.empty() ? "(no --model-path given)" : s;
}

class SdfImporter {
public:
    SdfImporter(const GazeboImportOptions& options, ImportedWorld& out)
        : options_(options), out_(out) {}

    void importText(const std::string& text, const SdfFile& file) {
        tinyxml2::XMLDocument doc;
        parseXml(doc, text, file.source);
        const XMLElement* sdf = doc.RootElement();
        if (!sdf || std::string(sdf->Name()) != "sdf")
            throw InputError(file.source + ": root element is not <sdf>");
        if (const XMLElement* world = sdf->FirstChildElement("world"))
            importWorld(file, world);
        else if (const XMLElement* model = sdf->FirstChildElement("model"))
            importModel(file, model, Pose::Identity(), "", nullptr);
        else
            file.fail(sdf, "has neither <world> nor <model>");
    }

private:
    void importWorld(const SdfFile& f, const XMLElement* world) {
        const auto state = readState(f, world);
        for (auto* e = world->FirstChildElement(); e; e = e->NextSiblingElement()) {
            const std::string tag = e->Name();
            if (tag == "model") {
                const auto it = state.find(nameOf(e));
                importModel(f, e, Pose::Identity(), "", it == state.end() ? nullptr : &it->second);
            } else if (tag == "include") {
                importInclude(f, e, Pose::Identity(), "", &state);
            }
        }
    }

    void importModel(const SdfFile& f, const XMLElement* model, const Pose& parent,
                     const std::string& prefix, const StateModel* state,
                     const std::string& nameOverride = "") {
        const std::string name = prefix + (nameOverride.empty() ? nameOf(model) : nameOverride);
        const Pose pose = state ? state->pose : parent * childPose(f, model);
        for (auto* e = model->FirstChildElement(); e; e = e->NextSiblingElement()) {
            const std::string tag = e->Name();
            if (tag == "link")
                importLink(f, e, pose, name, state);
            else if (tag == "model")
                importModel(f, e, pose, name + "/", nullptr);
            else if (tag == "include")
                importInclude(f, e, pose, name + "/", nullptr);
        }
    }

    void importLink(const SdfFile& f, const XMLElement* link, const Pose& modelPose,
                    const std::string& modelName, const StateModel* state) {
        Pose pose = modelPose * childPose(f, link);
        if (state) {
            const auto it = state->links.find(nameOf(link));
            if (it != state->links.end())
                pose = it->second;
        }
        const std::string name = modelName + "/" + nameOf(link);
        int count = 0;
        for (auto* c = link->FirstChildElement("collision"); c;
             c = c->NextSiblingElement("collision"))
            ++count;
        for (auto* c = link->FirstChildElement("collision"); c;
             c = c->NextSiblingElement("collision"))
            importCollision(f, c, link, pose * childPose(f, c),
                            count > 1 ? name + "/" + nameOf(c) : name);
    }

    void importCollision(const SdfFile& f, const XMLElement* collision, const XMLElement* link,
                         const Pose& pose, const std::string& name) {
        const XMLElement* geometry = collision->FirstChildElement("geometry");
        if (!geometry)
            f.fail(collision, "missing <geometry>");
        const XMLElement* shape = geometry->FirstChildElement();
        if (!shape)
            return;  // <geometry/> or <empty/>: nothing to collide with
        const std::string tag = shape->Name();
        if (tag == "box")
            addBox(f, shape, pose, name);
        else if (tag == "cylinder")
            addCylinder(f, shape, pose, name);
        else if (tag == "sphere")
            addSphere(f, shape, pose, name);
        else if (tag == "plane")
            addPlane(f, shape, pose, name);
        else if (tag == "mesh")
            addMesh(f, shape, link, pose, name);
        else if (tag != "empty")
            skipOrFail(f, shape, "geometry <" + tag + "> is not supported");
    }

    void addBox(const SdfFile& f, const XMLElement* box, const Pose& pose,
                const std::string& name) {
        const XMLElement* size = box->FirstChildElement("size");
        if (!size)
            f.fail(box, "missing <size>");
        const auto v = numbers(f, size, 3);
        if (v[0] <= 0 || v[1] <= 0 || v[2] <= 0)
            f.fail(size, "all sizes must be > 0");
        out_.boxes.push_back({name, pose, Eigen::Vector3d(v[0], v[1], v[2])});
    }

    void addCylinder(const SdfFile& f, const XMLElement* cyl, const Pose& pose,
                     const std::string& name) {
        out_.cylinders.push_back(
            {name, pose, positiveNumber(f, cyl, "radius"), positiveNumber(f, cyl, "length")});
    }

    void addSphere(const SdfFile& f, const XMLElement* sphere, const Pose& pose,
                   const std::string& name) {
        const double r = positiveNumber(f, sphere, "radius");
        out_.cylinders.push_back({name, pose, r, 2.0 * r});
        out_.warnings.push_back(f.where(sphere) + ": sphere '" + name +
                                "' imported as its enclosing cylinder");
    }

    void addPlane(const SdfFile& f, const XMLElement* plane, const Pose& pose,
                  const std::string& name) {
        Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
        if (const XMLElement* n = plane->FirstChildElement("normal")) {
            const auto v = numbers(f, n, 3);
            normal = Eigen::Vector3d(v[0], v[1], v[2]).normalized();
        }
        const Eigen::Vector3d worldNormal = pose.linear() * normal;
        if (worldNormal.z() > 0.999 && std::abs(pose.translation().z()) < 1e-6) {
            out_.ground = true;
            return;
        }
        skipOrFail(f, plane, "plane '" + name + "' is not a z-up ground plane at z = 0");
    }

    void addMesh(const SdfFile& f, const XMLElement* mesh, const XMLElement* link, const Pose& pose,
                 const std::string& name) {
        if (mesh->FirstChildElement("submesh"))
            return skipOrFail(f, mesh, "<submesh> is not supported");
        const std::string uri = trim(childText(mesh, "uri"));
        if (uri.empty())
            f.fail(mesh, "missing <uri>");
        Eigen::Vector3d scale = Eigen::Vector3d::Ones();
        if (const XMLElement* s = mesh->FirstChildElement("scale")) {
            const auto v = numbers(f, s, 3);
            scale = Eigen::Vector3d(v[0], v[1], v[2]);
        }
        if ((scale.array() <= 0.0).any() && !visualScale(f, link, uri, scale)) {
            return skipOrFail(f, mesh,
                              "mesh '" + uri + "' has a scale <= 0 and no visual to take it from");
        }
        const std::string file = resolveUri(f, mesh, uri);
        if (!file.empty())
            out_.meshes.push_back({name, file, pose, scale});
    }

    /**
     * Gazebo worlds sometimes give a collision mesh scale 0 (the maze); the drone's camera sees
     * the visual, so take the scale of the link's visual with the same mesh.
     */
    bool visualScale(const SdfFile& f, const XMLElement* link, const std::string& uri,
                     Eigen::Vector3d& scale) {
        for (auto* v = link->FirstChildElement("visual"); v; v = v->NextSiblingElement("visual")) {
            const XMLElement* g = v->FirstChildElement("geometry");
            const XMLElement* m = g ? g->FirstChildElement("mesh") : nullptr;
            if (!m || trim(childText(m, "uri")) != uri || !m->FirstChildElement("scale"))
                continue;
            const auto s = numbers(f, m->FirstChildElement("scale"), 3);
            const Eigen::Vector3d vs(s[0], s[1], s[2]);
            if ((vs.array() <= 0.0).any())
                continue;
            out_.warnings.push_back(f.where(m) + ": collision mesh '" + uri +
                                    "' has scale <= 0; using the visual's scale");
            scale = vs;
            return true;
        }
        return false;
    }

    void importInclude(const SdfFile& f, const XMLElement* inc, const Pose& parent,
                       const std::string& prefix, const std::map<std::string, StateModel>* state) {
        const std::string uri = trim(childText(inc, "uri"));
        if (uri.empty())
            f.fail(inc, "missing <uri>");
        const std::string name = trim(childText(inc, "name"));
        if (startsWith(name, "person_walking") || startsWith(uri, "model://person_walking"))
            return;  // people come from the waypoint file
        const std::string dir = resolveUri(f, inc, uri);
        if (dir.empty())
            return;
        const std::string sdfPath = modelSdfPath(dir);
        tinyxml2::XMLDocument doc;
        const SdfFile sub{sdfPath, dir};
        parseXml(doc, readTextFile(sdfPath), sdfPath);
        const XMLElement* root = doc.RootElement();
        const XMLElement* model = root ? root->FirstChildElement("model") : nullptr;
        if (!model)
            throw InputError(sdfPath + ": no <sdf><model> element");
        const std::string modelName = name.empty() ? nameOf(model) : name;
        const StateModel* sm = nullptr;
        if (state) {
            const auto it = state->find(modelName);
            sm = it == state->end() ? nullptr : &it->second;
        }
        // The include's pose, when given, replaces the model file's own pose.
        const Pose pose =
            parent * (inc->FirstChildElement("pose") ? childPose(f, inc) : childPose(sub, model));
        StateModel placed{pose, {}};
        importModel(sub, model, Pose::Identity(), prefix, sm ? sm : &placed, modelName);
    }

    /** model.sdf of a model dir, or the file named by model.config's <sdf>. */
    static std::string modelSdfPath(const std::string& dir) {
        const fs::path config = fs::path(dir) / "model.config";
        if (daep::pathExists(config)) {
            tinyxml2::XMLDocument doc;
            parseXml(doc, readTextFile(config.string()), config.string());
            const XMLElement* root = doc.RootElement();
            const XMLElement* sdf = root ? root->FirstChildElement("sdf") : nullptr;
            if (sdf && sdf->GetText()) {
                const fs::path p = fs::path(dir) / trim(sdf->GetText());
                if (daep::pathExists(p))
                    return p.string();
            }
        }
        const fs::path p = fs::path(dir) / "model.sdf";
        if (!daep::pathExists(p))
            throw InputError(dir + ": no model.sdf (and no <sdf> in model.config)");
        return p.string();
    }

    /** A model:// or file:// URI (or a relative path) -> existing path; "" when skipped. */
    std::string resolveUri(const SdfFile& f, const XMLElement* where, const std::string& uri) {
        if (startsWith(uri, "model://")) {
            const std::string rest = uri.substr(8);
            for (const auto& dir : options_.modelPaths) {
                const fs::path p = fs::path(dir) / rest;
                if (daep::pathExists(p))
                    return fs::absolute(p).lexically_normal().string();
            }
            skipOrFail(
                f, where,
                "'" + uri + "' not found in the model path " + joinPaths(options_.modelPaths));
            return "";
        }
        std::string path = uri;
        if (startsWith(uri, "file://"))
            path = uri.substr(7);
        else if (uri.find("://") != std::string::npos)
            f.fail(where, "URI scheme of '" + uri + "' is not supported");
        fs::path p(path);
        if (p.is_relative())
            p = fs::path(f.dir) / p;
        if (daep::pathExists(p))
            return fs::absolute(p).lexically_normal().string();
        skipOrFail(f, where, "'" + uri + "' not found (looked for " + p.string() + ")");
        return "";
    }

    void skipOrFail(const SdfFile& f, const XMLElement* e, const std::string& what) {
        if (!options_.skipMissing)
            f.fail(e, what);
        out_.warnings.push_back(f.where(e) + ": <" + e->Name() + ">: skipped: " + what);
    }

    const GazeboImportOptions& options_;
    ImportedWorld& out_;
};

/** "key: [a, b, c]" of a flat yaml, or false when the key is absent. */
bool yamlValue(const std::string& text, const std::string& key, std::string& value) {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        line = line.substr(0, line.find('#'));
        if (trim(line).rfind(key + ":", 0) == 0) {
            value = trim(trim(line).substr(key.size() + 1));
            return true;
        }
    }
    return false;
}

/** "[a, b, c]" or "(a,b,c)" -> numbers; throws naming `what` when malformed. */
std::vector<double> numberList(std::string s, const std::string& what) {
    s = trim(s);
    if (s.size() < 2 ||
        !((s.front() == '[' && s.back() == ']') || (s.front() == '(' && s.back() == ')')))
        throw InputError(what + ": expected a bracketed list, got '" + s + "'");
    std::vector<double> v;
    std::istringstream ss(s.substr(1, s.size() - 2));
    std::string tok;
    while (std::getline(ss, tok, ',')) {
        tok = trim(tok);
        char* end = nullptr;
        const double x = std::strtod(tok.c_str(), &end);
        if (tok.empty() || *end != '\0')
            throw InputError(what + ": '" + tok + "' is not a number");
        v.push_back(x);
    }
    return v;
}

Eigen::Vector3d vec3(const std::string& s, const std::string& what) {
    const auto v = numberList(s, what);
    if (v.size() != 3)
        throw InputError(what + ": expected 3 numbers, got " + std::to_string(v.size()));
    return Eigen::Vector3d(v[0], v[1], v[2]);
}

/** The single-quoted tokens of a launch args string. */
std::vector<std::string> quotedTokens(const std::string& args) {
    std::vector<std::string> out;
    size_t at = 0;
    while ((at = args.find('\'', at)) != std::string::npos) {
        const size_t end = args.find('\'', at + 1);
        if (end == std::string::npos)
            break;
        out.push_back(args.substr(at + 1, end - at - 1));
        at = end + 1;
    }
    return out;
}

/** "[(x, y), (x, y)]" -> points. */
std::vector<Eigen::Vector2d> waypointList(const std::string& s, const std::string& what) {
    const std::string t = trim(s);
    if (t.size() < 2 || t.front() != '[' || t.back() != ']')
        throw InputError(what + ": expected '[(x, y), ...]'");
    std::vector<Eigen::Vector2d> out;
    size_t at = 1;
    while ((at = t.find('(', at)) != std::string::npos) {
        const size_t end = t.find(')', at);
        if (end == std::string::npos)
            throw InputError(what + ": unclosed '('");
        const auto v = numberList(t.substr(at, end - at + 1), what);
        if (v.size() != 2)
            throw InputError(what + ": waypoint with " + std::to_string(v.size()) + " numbers");
        out.emplace_back(v[0], v[1]);
        at = end + 1;
    }
    return out;
}

}  // namespace

ImportedWorld importSdfText(const std::string& text, const std::string& sourceName,
                            const std::string& baseDir, const GazeboImportOptions& options) {
    ImportedWorld out;
    out.source = sourceName;
    SdfImporter(options, out).importText(text, SdfFile{sourceName, baseDir});
    return out;
}

ImportedWorld importGazeboWorld(const std::string& worldFile, const GazeboImportOptions& options) {
    const std::string dir = fs::absolute(worldFile).parent_path().string();
    ImportedWorld w = importSdfText(readTextFile(worldFile), worldFile, dir, options);
    w.name = options.name.empty() ? fs::path(worldFile).stem().string() : options.name;
    if (!options.peopleFile.empty())
        w.people = readLaunchPeople(options.peopleFile);
    if (!options.boxConfig.empty()) {
        readExplorationBoundary(options.boxConfig, w.box, w.volume);
        w.hasBox = true;
    }
    if (!options.startsFile.empty())
        w.starts = readSpawnPositions(options.startsFile, options.startsKey);
    return w;
}

std::vector<PersonRoute> readLaunchPeople(const std::string& launchFile) {
    tinyxml2::XMLDocument doc;
    parseXml(doc, readTextFile(launchFile), launchFile);
    std::vector<PersonRoute> people;
    const XMLElement* root = doc.RootElement();
    for (auto* n = root ? root->FirstChildElement("node") : nullptr; n;
         n = n->NextSiblingElement("node")) {
        const char* args = n->Attribute("args");
        const auto tokens = quotedTokens(args ? args : "");
        if (tokens.size() < 2 || trim(tokens[1]).rfind('[', 0) != 0)
            continue;
        const std::string what =
            launchFile + ":" + std::to_string(n->GetLineNum()) + ": " + tokens[0];
        PersonRoute route{tokens[0], waypointList(tokens[1], what)};
        if (route.waypoints.size() < 2)
            throw InputError(what + ": a route needs at least 2 waypoints");
        people.push_back(route);
    }
    return people;
}

void readExplorationBoundary(const std::string& yamlFile, Aabb& box, double& volume) {
    const std::string text = readTextFile(yamlFile);
    std::string minText, maxText, volumeText;
    if (!yamlValue(text, "boundary/min", minText) || !yamlValue(text, "boundary/max", maxText))
        throw InputError(yamlFile + ": boundary/min and boundary/max are required");
    box.min = vec3(minText, yamlFile + ": boundary/min");
    box.max = vec3(maxText, yamlFile + ": boundary/max");
    if ((box.max.array() <= box.min.array()).any())
        throw InputError(yamlFile + ": boundary/max must be greater than boundary/min");
    volume = 0.0;
    if (yamlValue(text, "boundary/volume", volumeText)) {
        char* end = nullptr;
        volume = std::strtod(volumeText.c_str(), &end);
        if (end == volumeText.c_str() || *end != '\0' || volume <= 0.0)
            throw InputError(yamlFile + ": boundary/volume: '" + volumeText +
                             "' is not a number > 0");
    }
}

std::vector<Eigen::Vector3d> readSpawnPositions(const std::string& yamlFile,
                                                const std::string& key) {
    std::istringstream in(readTextFile(yamlFile));
    std::string line;
    bool inSection = false, inKey = false;
    std::vector<Eigen::Vector3d> out;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        const std::string t = trim(line.substr(0, line.find('#')));
        if (t.empty())
            continue;
        const bool topLevel = !std::isspace(static_cast<unsigned char>(line[0]));
        if (topLevel) {
            if (inKey)
                break;
            inSection = t == "spawn_positions:";
            continue;
        }
        if (!inSection)
            continue;
        if (t[0] == '-') {
            if (inKey)
                out.push_back(vec3(t.substr(1), yamlFile + ":" + std::to_string(lineNo)));
        } else if (inKey) {
            break;
        } else {
            inKey = trim(t.substr(0, t.find(':'))) == key;
        }
    }
    if (out.empty())
        throw InputError(yamlFile + ": no spawn_positions for '" + key + "'");
    return out;
}

}  // namespace daep::world
