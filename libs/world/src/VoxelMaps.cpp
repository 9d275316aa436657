#include "daep/world/VoxelMaps.h"

#include <octomap/ColorOcTree.h>
#include <octomap/OcTree.h>
#include <octomap/OcTreeStamped.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>

#include "CellBoxes.h"
#include "PlyPoints.h"
#include "StderrCapture.h"
#include "daep/common/Error.h"
#include "daep/common/FileChecks.h"

namespace daep::world {
namespace {

const char* const kBinaryHeader = "# Octomap OcTree binary file";
const char* const kFullHeader = "# Octomap OcTree file";

[[noreturn]] void fail(const std::string& path, const std::string& what) {
    throw InputError(path + ": " + what);
}

std::string firstLine(const std::string& path) {
    if (daep::isDirectory(path))
        fail(path, "is a directory, not an OctoMap file");
    std::ifstream in(path, std::ios::binary);
    if (!in)
        fail(path, "cannot read the OctoMap file");
    std::string line;
    std::getline(in, line);
    if (!line.empty() && line.back() == '\r')
        line.pop_back();
    return line;
}

/** OctoMap's own complaint, from what it printed on stderr, as one line. */
std::string octomapReason(const std::string& printed) {
    std::string text = printed.substr(0, printed.find('\n'));
    if (text.rfind("ERROR: ", 0) == 0)
        text = text.substr(7);
    return text.empty() ? std::string() : " (" + text + ")";
}

/** The occupied leaves as boxes of the finest cells (cell k spans [k res, (k + 1) res)). */
template <typename Tree>
std::vector<CellBox> occupiedLeaves(const Tree& tree) {
    const double res = tree.getResolution();
    const unsigned depth = tree.getTreeDepth();
    std::vector<CellBox> out;
    for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
        if (!tree.isNodeOccupied(*it))
            continue;
        const auto cells = std::int64_t(1) << (depth - it.getDepth());
        const octomap::point3d c = it.getCoordinate();
        CellBox b;
        for (int k = 0; k < 3; ++k) {
            b.lo[std::size_t(k)] = std::llround(double(c(k)) / res - 0.5 * double(cells));
            b.hi[std::size_t(k)] = b.lo[std::size_t(k)] + cells;
        }
        out.push_back(b);
    }
    return out;
}

std::size_t cellCount(const std::vector<CellBox>& boxes) {
    std::size_t n = 0;
    for (const CellBox& b : boxes)
        n += std::size_t((b.hi[0] - b.lo[0]) * (b.hi[1] - b.lo[1]) * (b.hi[2] - b.lo[2]));
    return n;
}

struct LeafSet {
    double resolution = 0.0;
    std::vector<CellBox> leaves;
};

LeafSet readBinaryTree(const std::string& path) {
    octomap::OcTree tree(0.1);
    StderrCapture capture;
    const bool ok = tree.readBinary(path);
    const std::string printed = capture.finish();
    if (!ok)
        fail(path, "cannot read the binary OctoMap" + octomapReason(printed));
    return {tree.getResolution(), occupiedLeaves(tree)};
}

LeafSet readFullTree(const std::string& path) {
    StderrCapture capture;
    std::unique_ptr<octomap::AbstractOcTree> tree(octomap::AbstractOcTree::read(path));
    const std::string printed = capture.finish();
    if (!tree)
        fail(path, "cannot read the OctoMap" + octomapReason(printed));
    if (const auto* t = dynamic_cast<const octomap::OcTree*>(tree.get()))
        return {t->getResolution(), occupiedLeaves(*t)};
    if (const auto* t = dynamic_cast<const octomap::ColorOcTree*>(tree.get()))
        return {t->getResolution(), occupiedLeaves(*t)};
    if (const auto* t = dynamic_cast<const octomap::OcTreeStamped*>(tree.get()))
        return {t->getResolution(), occupiedLeaves(*t)};
    fail(path, "OctoMap tree type '" + tree->getTreeType() +
                   "' has no occupancy (expected OcTree, ColorOcTree or OcTreeStamped)");
}

VoxelMap makeVoxelMap(const std::string& path, double res, std::vector<CellBox> cells,
                      const Eigen::Vector3d& offset) {
    VoxelMap map;
    map.name = std::filesystem::path(path).filename().string();
    map.source = path;
    map.resolution = res;
    map.cells = cellCount(cells);
    map.boxes = toMetres(mergeCellBoxes(std::move(cells)), res, offset);
    return map;
}

}  // namespace

VoxelMap loadOctomap(const std::string& path, const Eigen::Vector3d& offset) {
    const std::string header = firstLine(path);
    LeafSet set;
    if (header.rfind(kBinaryHeader, 0) == 0)
        set = readBinaryTree(path);
    else if (header.rfind(kFullHeader, 0) == 0)
        set = readFullTree(path);
    else
        fail(path, std::string("not an OctoMap file (its first line is not '") + kBinaryHeader +
                       "' (.bt) or '" + kFullHeader + "' (.ot))");
    if (set.leaves.empty())
        fail(path, "the OctoMap has no occupied cell");
    return makeVoxelMap(path, set.resolution, std::move(set.leaves), offset);
}

VoxelMap voxelisePointCloud(const std::string& path, double voxelSize,
                            const Eigen::Vector3d& offset) {
    if (!(voxelSize > 0.0) || !std::isfinite(voxelSize))
        fail(path, "voxel size must be > 0");
    std::vector<CellBox> cells;
    for (const Eigen::Vector3d& p : readPlyPoints(path)) {
        if (!p.allFinite())
            continue;
        if ((p.array().abs() / voxelSize).maxCoeff() > 1e15)
            fail(path, "a point lies too far from the origin for the voxel size");
        CellBox b;
        for (int k = 0; k < 3; ++k) {
            b.lo[std::size_t(k)] = std::int64_t(std::floor(p[k] / voxelSize));
            b.hi[std::size_t(k)] = b.lo[std::size_t(k)] + 1;
        }
        cells.push_back(b);
    }
    if (cells.empty())
        fail(path, "the point cloud has no finite point");
    std::sort(cells.begin(), cells.end(),
              [](const CellBox& a, const CellBox& b) { return a.lo < b.lo; });
    cells.erase(std::unique(cells.begin(), cells.end(),
                            [](const CellBox& a, const CellBox& b) { return a.lo == b.lo; }),
                cells.end());
    return makeVoxelMap(path, voxelSize, std::move(cells), offset);
}

}  // namespace daep::world
