#include <octomap/OcTree.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "PlyPoints.h"
#include "daep/common/Error.h"
#include "daep/world/RayCaster.h"
#include "daep/world/VoxelMaps.h"

namespace daep::world {
namespace {

/** A return lies this far behind the surface it hit: inside the solid, as a real return. */
constexpr float kBehindSurface = 0.001f;

/** Unit directions on a full sphere: rings of constant elevation, `stepDeg` apart both ways. */
std::vector<Eigen::Vector3f> sphereDirections(double stepDeg) {
    std::vector<Eigen::Vector3f> dirs;
    const int rings = int(std::lround(180.0 / stepDeg));
    const int perRing = int(std::lround(360.0 / stepDeg));
    for (int i = 0; i < rings; ++i) {
        const double elevation = (-90.0 + (i + 0.5) * 180.0 / rings) * M_PI / 180.0;
        for (int j = 0; j < perRing; ++j) {
            const double azimuth = 2.0 * M_PI * j / perRing;
            dirs.push_back(Eigen::Vector3d(std::cos(elevation) * std::cos(azimuth),
                                           std::cos(elevation) * std::sin(azimuth),
                                           std::sin(elevation))
                               .cast<float>());
        }
    }
    return dirs;
}

std::vector<Eigen::Vector3f> scanReturns(const RayCaster& caster, const Eigen::Vector3f& origin,
                                         const std::vector<Eigen::Vector3f>& dirs, float maxRange,
                                         std::vector<float>& ranges) {
    caster.castRays(origin, dirs, maxRange, ranges);
    std::vector<Eigen::Vector3f> points;
    for (std::size_t i = 0; i < dirs.size(); ++i)
        if (std::isfinite(ranges[i]))
            points.push_back(origin + (ranges[i] + kBehindSurface) * dirs[i]);
    return points;
}

void validate(const LaserScanParams& p) {
    if (p.stations.empty())
        throw InputError("laser scan: at least one station is needed");
    if (!(p.resolution > 0.0) || !std::isfinite(p.resolution))
        throw InputError("laser scan: resolution must be > 0");
    if (!(p.stepDeg >= 0.01 && p.stepDeg <= 45.0))
        throw InputError("laser scan: the angular step must be in 0.01 .. 45 degrees");
    if (!(p.maxRange > 0.0) || !std::isfinite(p.maxRange))
        throw InputError("laser scan: max range must be > 0");
}

std::string describe(const LaserScanParams& p, const WorldSpec& world) {
    std::ostringstream s;
    s << "daep-world scan of " << world.name << ": " << p.stations.size() << " stations, step "
      << p.stepDeg << " deg, max range " << p.maxRange << " m";
    return s.str();
}

void writeOctomap(octomap::OcTree& tree, const std::string& path, bool binary,
                  LaserScanSummary& summary) {
    tree.updateInnerOccupancy();
    if (binary)
        tree.toMaxLikelihood();
    tree.prune();
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it)
        summary.occupiedLeaves += tree.isNodeOccupied(*it) ? 1 : 0;
    summary.nodes = tree.size();
    const bool ok = binary ? tree.writeBinary(path) : tree.write(path);
    if (!ok)
        throw std::runtime_error(path + ": cannot write the OctoMap");
}

}  // namespace

LaserScanSummary scanWorldToFile(const WorldSpec& world, const LaserScanParams& params,
                                 const std::string& outPath) {
    validate(params);
    const std::string ext = std::filesystem::path(outPath).extension().string();
    if (ext != ".bt" && ext != ".ot" && ext != ".ply")
        throw InputError(outPath + ": the output must end in .bt, .ot or .ply");

    const RayCaster caster(world);  // static geometry only: people are never added
    const std::vector<Eigen::Vector3f> dirs = sphereDirections(params.stepDeg);
    const auto maxRange = float(params.maxRange);
    octomap::OcTree tree(params.resolution);
    std::vector<Eigen::Vector3f> cloud;
    std::vector<float> ranges;
    LaserScanSummary summary;
    for (const Eigen::Vector3d& station : params.stations) {
        const Eigen::Vector3f origin = station.cast<float>();
        const auto points = scanReturns(caster, origin, dirs, maxRange, ranges);
        summary.rays += dirs.size();
        summary.returns += points.size();
        if (ext == ".ply") {
            cloud.insert(cloud.end(), points.begin(), points.end());
            continue;
        }
        octomap::Pointcloud scan;
        scan.reserve(points.size());
        for (const auto& p : points)
            scan.push_back(p.x(), p.y(), p.z());
        tree.insertPointCloud(scan, octomap::point3d(origin.x(), origin.y(), origin.z()),
                              params.maxRange, false, true);
    }
    if (ext == ".ply")
        writePlyPoints(outPath, cloud, describe(params, world));
    else
        writeOctomap(tree, outPath, ext == ".bt", summary);
    return summary;
}

}  // namespace daep::world
