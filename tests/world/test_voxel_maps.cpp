// Worlds whose static geometry is a user's own map: an OctoMap (.bt, .ot) or a PLY point cloud.
#include <gtest/gtest.h>
#include <octomap/ColorOcTree.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "TestFiles.h"
#include "daep/common/Error.h"
#include "daep/world/RayCaster.h"
#include "daep/world/ReachableVolume.h"
#include "daep/world/VoxelMaps.h"
#include "daep/world/WorldSpec.h"

namespace daep::world {
namespace {

using test::TempDir;

/** The world file around a map: a 4 x 4 x 2 m box with one start. */
std::string worldYaml(const std::string& geometry) {
    return "exploration_box: {min: [-2, -2, 0], max: [2, 2, 2]}\n"
           "starts: [[-1.5, 0, 0.3]]\n" +
           geometry + "\n";
}

/** A wall x in [1.0, 1.2), y in [-1, 1), z in [0, 2): 2 x 20 x 20 cells of 0.1 m. */
template <typename Tree>
void fillWall(Tree& tree) {
    for (int i = 10; i < 12; ++i)
        for (int j = -10; j < 10; ++j)
            for (int k = 0; k < 20; ++k)
                tree.updateNode(
                    octomap::point3d(0.1f * i + 0.05f, 0.1f * j + 0.05f, 0.1f * k + 0.05f), true);
    // Free space seen in front of the wall stays free.
    for (int i = -15; i < 10; ++i)
        tree.updateNode(octomap::point3d(0.1f * i + 0.05f, 0.05f, 1.05f), false);
    tree.updateInnerOccupancy();
}

std::string writeWallBt(const TempDir& dir, const std::string& rel) {
    octomap::OcTree tree(0.1);
    fillWall(tree);
    const std::string path = (dir.path() / rel).string();
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    EXPECT_TRUE(tree.writeBinary(path));
    return path;
}

/** The wall as the same box written in the world format: the reference the map must match. */
WorldSpec wallAsBox() {
    WorldSpec w;
    w.explorationBox.min = Eigen::Vector3d(-2, -2, 0);
    w.explorationBox.max = Eigen::Vector3d(2, 2, 2);
    w.starts = {Eigen::Vector3d(-1.5, 0, 0.3)};
    BoxShape b;
    b.pose.translation() = Eigen::Vector3d(1.1, 0, 1);
    b.size = Eigen::Vector3d(0.2, 2, 2);
    w.boxes.push_back(b);
    return w;
}

void expectRaysMeetTheWall(const WorldSpec& w) {
    const RayCaster rc(w);
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_NEAR(rc.castRay({0, 0, 1}, {1, 0, 0}, 10.0f), 1.0f, 1e-5);      // the wall's face
    EXPECT_NEAR(rc.castRay({3, 0.5f, 1}, {-1, 0, 0}, 10.0f), 1.8f, 1e-5);  // its back
    EXPECT_EQ(rc.castRay({0, 0, 1}, {-1, 0, 0}, 10.0f), inf);    // free cells are not solid
    EXPECT_EQ(rc.castRay({0, 1.5f, 1}, {1, 0, 0}, 10.0f), inf);  // past its end
    EXPECT_EQ(rc.castRay({0, 0, 2.5f}, {1, 0, 0}, 10.0f), inf);  // over its top
    std::vector<float> ranges;
    rc.castRays({0, 0, 1}, {{1, 0, 0}, {0, 1, 0}, Eigen::Vector3f(1, 0.5f, 0).normalized()}, 10.0f,
                ranges);
    EXPECT_NEAR(ranges[0], 1.0f, 1e-5);
    EXPECT_EQ(ranges[1], inf);
    EXPECT_NEAR(ranges[2], std::hypot(1.0f, 0.5f), 1e-5);
}

void expectCollisionsAtTheWall(const WorldSpec& w) {
    const StaticCollisionChecker checker(w);
    const Eigen::Vector3d drone(0.4, 0.4, 0.1);
    EXPECT_TRUE(checker.overlaps({1.1, 0, 1}, drone, 0.0));
    EXPECT_TRUE(checker.overlaps({0.85, 0.9, 1}, drone, 0.3));  // a corner reaches in
    EXPECT_FALSE(checker.overlaps({0.7, 0, 1}, drone, 0.0));
    EXPECT_FALSE(checker.overlaps({1.1, 1.3, 1}, drone, 0.0));
}

TEST(VoxelMaps, BinaryOctomapIsSolidWhereOccupied) {
    TempDir dir;
    writeWallBt(dir, "maps/wall.bt");
    const WorldSpec w = loadWorldFile(dir.write("w.yaml", worldYaml("octomap: maps/wall.bt")));
    ASSERT_EQ(w.voxelMaps.size(), 1u);
    const VoxelMap& map = w.voxelMaps[0];
    EXPECT_DOUBLE_EQ(map.resolution, 0.1);
    EXPECT_EQ(map.cells, 800u);
    EXPECT_EQ(map.boxes.size(), 1u);  // the wall's leaves merge into the one box they fill
    EXPECT_TRUE(map.boxes[0].min.isApprox(Eigen::Vector3d(1.0, -1.0, 0.0)));
    EXPECT_TRUE(map.boxes[0].max.isApprox(Eigen::Vector3d(1.2, 1.0, 2.0)));
    expectRaysMeetTheWall(w);
    expectCollisionsAtTheWall(w);
}

TEST(VoxelMaps, FullOctomapsOfEachTreeType) {
    TempDir dir;
    octomap::OcTree tree(0.1);
    fillWall(tree);
    ASSERT_TRUE(tree.write((dir.path() / "wall.ot").string()));
    octomap::ColorOcTree coloured(0.1);
    fillWall(coloured);
    ASSERT_TRUE(coloured.write((dir.path() / "colour.ot").string()));
    for (const char* file : {"wall.ot", "colour.ot"}) {
        const WorldSpec w = loadWorldFile(
            dir.write("w.yaml", worldYaml(std::string("octomap: {file: ") + file + "}")));
        ASSERT_EQ(w.voxelMaps.size(), 1u) << file;
        EXPECT_EQ(w.voxelMaps[0].cells, 800u) << file;
        expectRaysMeetTheWall(w);
        expectCollisionsAtTheWall(w);
    }
}

TEST(VoxelMaps, PositionShiftsTheMap) {
    TempDir dir;
    writeWallBt(dir, "wall.bt");
    const WorldSpec w = loadWorldFile(
        dir.write("w.yaml", worldYaml("octomap: {file: wall.bt, position: [-0.5, 0, 0]}")));
    const RayCaster rc(w);
    EXPECT_NEAR(rc.castRay({0, 0, 1}, {1, 0, 0}, 10.0f), 0.5f, 1e-5);
}

TEST(VoxelMaps, PathsAreRelativeToTheWorldFile) {
    TempDir dir;
    writeWallBt(dir, "scans/wall.bt");
    const std::string path =
        dir.write("worlds/deep/w.yaml", worldYaml("octomap: ../../scans/wall.bt"));
    const WorldSpec w = loadWorldFile(path);
    ASSERT_EQ(w.voxelMaps.size(), 1u);
    EXPECT_EQ(std::filesystem::canonical(w.voxelMaps[0].source),
              std::filesystem::canonical(dir.path() / "scans/wall.bt"));
}

TEST(VoxelMaps, MapsAddToBoundsAndGround) {
    TempDir dir;
    writeWallBt(dir, "wall.bt");
    const WorldSpec w =
        loadWorldFile(dir.write("w.yaml",
                                "exploration_box: {min: [-1, -1, 0], max: [0, 0, 1]}\n"
                                "starts: [[-0.5, -0.5, 0.3]]\nground: true\n"
                                "octomap: wall.bt\n"));
    EXPECT_NEAR(w.bounds().max.x(), 1.2 + 2.0, 1e-9);  // the slab reaches 2 m past the map
    ASSERT_EQ(w.boxes.size(), 1u);
    EXPECT_EQ(w.boxes[0].name, "ground");
}

TEST(VoxelMaps, ReachMatchesTheSameWallAsABox) {
    TempDir dir;
    writeWallBt(dir, "wall.bt");
    const WorldSpec fromMap = loadWorldFile(dir.write("w.yaml", worldYaml("octomap: wall.bt")));
    const WorldSpec fromBox = wallAsBox();
    const auto a = computeReachableVolume(fromMap, fromMap.starts[0]);
    const auto b = computeReachableVolume(fromBox, fromBox.starts[0]);
    EXPECT_EQ(a.observableCells, b.observableCells);
    EXPECT_EQ(a.droneCells, b.droneCells);
    EXPECT_LT(a.droneCells, a.gridCells);
}

const char* kAsciiCloud = R"(ply
format ascii 1.0
comment two points in one 0.2 m voxel, one in another, one NaN
element vertex 4
property float x
property float y
property float z
property uchar red
element face 1
property list uchar int vertex_indices
end_header
1.01 0.01 1.01 255
1.19 0.19 1.19 0
1.25 0.05 1.05 7
nan 0 0 1
3 0 1 2
)";

TEST(VoxelMaps, AsciiPointCloudIsVoxelised) {
    TempDir dir;
    dir.write("cloud.ply", kAsciiCloud);
    const WorldSpec w = loadWorldFile(
        dir.write("w.yaml", worldYaml("point_cloud: {file: cloud.ply, voxel_size: 0.2}")));
    ASSERT_EQ(w.voxelMaps.size(), 1u);
    const VoxelMap& map = w.voxelMaps[0];
    EXPECT_EQ(map.cells, 2u);
    ASSERT_EQ(map.boxes.size(), 1u);  // two neighbours along x: one box
    EXPECT_TRUE(map.boxes[0].min.isApprox(Eigen::Vector3d(1.0, 0.0, 1.0)));
    EXPECT_TRUE(map.boxes[0].max.isApprox(Eigen::Vector3d(1.4, 0.2, 1.2)));
    const RayCaster rc(w);
    EXPECT_NEAR(rc.castRay({0, 0.1f, 1.1f}, {1, 0, 0}, 10.0f), 1.0f, 1e-5);
}

TEST(VoxelMaps, BinaryPointCloudsOfBothByteOrders) {
    TempDir dir;
    const float pts[3][3] = {{1.01f, -0.99f, 0.01f}, {1.05f, 0.95f, 1.95f}, {1.15f, 0.0f, 1.0f}};
    for (const bool little : {true, false}) {
        std::ofstream out(dir.path() / "cloud.ply", std::ios::binary);
        out << "ply\nformat " << (little ? "binary_little_endian" : "binary_big_endian")
            << " 1.0\nelement vertex 3\nproperty double x\nproperty float y\nproperty float z\n"
               "end_header\n";
        auto put = [&](const void* v, int n) {
            char b[8];
            std::memcpy(b, v, std::size_t(n));
            if (!little)
                std::reverse(b, b + n);
            out.write(b, n);
        };
        for (const auto& p : pts) {
            const double x = p[0];
            put(&x, 8);
            put(&p[1], 4);
            put(&p[2], 4);
        }
        out.close();
        const WorldSpec w = loadWorldFile(
            dir.write("w.yaml", worldYaml("point_cloud: {file: cloud.ply, voxel_size: 0.1}")));
        ASSERT_EQ(w.voxelMaps.size(), 1u);
        EXPECT_EQ(w.voxelMaps[0].cells, 3u) << (little ? "little" : "big");
        const RayCaster rc(w);
        EXPECT_NEAR(rc.castRay({0, 0.05f, 1.05f}, {1, 0, 0}, 10.0f), 1.1f, 1e-5);
    }
}

/** The error of loading `yaml` (with the given data files), which must be one line. */
std::string loadError(const TempDir& dir, const std::string& yaml) {
    try {
        loadWorldFile(dir.write("w.yaml", yaml));
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        return msg;
    }
    ADD_FAILURE() << "no error for " << yaml;
    return {};
}

bool has(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

TEST(VoxelMaps, BadMapsAreOneLineErrorsNamingTheFile) {
    TempDir dir;
    const std::string world = (dir.path() / "w.yaml").string();
    std::string e = loadError(dir, worldYaml("octomap: nowhere.bt"));
    EXPECT_TRUE(has(e, world + ":3: octomap: octomap file 'nowhere.bt' not found")) << e;

    dir.write("text.bt", "just some text\n");
    e = loadError(dir, worldYaml("octomap: {file: text.bt}"));
    EXPECT_TRUE(has(e, world + ":3: octomap.file: ")) << e;
    EXPECT_TRUE(has(e, "text.bt: not an OctoMap file")) << e;

    octomap::OcTree freeOnly(0.1);
    freeOnly.updateNode(octomap::point3d(0.05f, 0.05f, 0.05f), false);
    ASSERT_TRUE(freeOnly.writeBinary((dir.path() / "free.bt").string()));
    e = loadError(dir, worldYaml("octomap: free.bt"));
    EXPECT_TRUE(has(e, "free.bt: the OctoMap has no occupied cell")) << e;

    octomap::OcTree none(0.1);
    ASSERT_TRUE(none.write((dir.path() / "empty.ot").string()));
    e = loadError(dir, worldYaml("octomap: empty.ot"));
    EXPECT_TRUE(has(e, "empty.ot: the OctoMap has no occupied cell")) << e;

    const std::string full = writeWallBt(dir, "wall.bt");
    std::string bytes;
    {
        std::ifstream in(full, std::ios::binary);
        bytes.assign(std::istreambuf_iterator<char>(in), {});
    }
    std::ofstream(dir.path() / "cut.bt", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    e = loadError(dir, worldYaml("octomap: cut.bt"));
    EXPECT_TRUE(has(e, "cut.bt: ")) << e;

    std::filesystem::create_directories(dir.path() / "folder.bt");
    e = loadError(dir, worldYaml("octomap: folder.bt"));
    EXPECT_TRUE(has(e, "octomap file 'folder.bt' not found")) << e;
}

TEST(VoxelMaps, BadPointCloudsAreOneLineErrorsNamingTheFile) {
    TempDir dir;
    const std::string world = (dir.path() / "w.yaml").string();
    std::string e = loadError(dir, worldYaml("point_cloud: {file: cloud.ply}"));
    EXPECT_TRUE(has(e, "point cloud file 'cloud.ply' not found")) << e;

    dir.write("cloud.ply", kAsciiCloud);
    e = loadError(dir, worldYaml("point_cloud: {file: cloud.ply}"));
    EXPECT_TRUE(has(e, world + ":3: point_cloud: required key 'voxel_size' is missing")) << e;
    e = loadError(dir, worldYaml("point_cloud: {file: cloud.ply, voxel_size: 0}"));
    EXPECT_TRUE(has(e, "point_cloud.voxel_size: must be > 0")) << e;
    e = loadError(dir, worldYaml("point_cloud: {file: cloud.ply, voxel: 0.1}"));
    EXPECT_TRUE(has(e, "point_cloud.voxel: unknown key")) << e;

    dir.write("notply.ply", "solid cube\n");
    e = loadError(dir, worldYaml("point_cloud: {file: notply.ply, voxel_size: 0.1}"));
    EXPECT_TRUE(has(e, "notply.ply: not a PLY file")) << e;

    dir.write("short.ply",
              "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
              "property float y\nproperty float z\nend_header\n1 2 3\n4 5\n");
    e = loadError(dir, worldYaml("point_cloud: {file: short.ply, voxel_size: 0.1}"));
    EXPECT_TRUE(has(e, "short.ply: the PLY data ends early")) << e;

    dir.write("noxyz.ply",
              "ply\nformat ascii 1.0\nelement vertex 1\nproperty float a\n"
              "end_header\n1\n");
    e = loadError(dir, worldYaml("point_cloud: {file: noxyz.ply, voxel_size: 0.1}"));
    EXPECT_TRUE(has(e, "noxyz.ply: the PLY vertex element has no x, y and z")) << e;

    dir.write("empty.ply",
              "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
              "property float y\nproperty float z\nend_header\n");
    e = loadError(dir, worldYaml("point_cloud: {file: empty.ply, voxel_size: 0.1}"));
    EXPECT_TRUE(has(e, "empty.ply: the point cloud has no finite point")) << e;
}

TEST(VoxelMaps, ScanOfAWorldGivesItsMapBack) {
    TempDir dir;
    const WorldSpec box = wallAsBox();
    LaserScanParams params;
    params.stations = {Eigen::Vector3d(0, 0, 1)};
    params.resolution = 0.1;
    params.stepDeg = 1.0;
    const std::string bt = (dir.path() / "scan.bt").string();
    const LaserScanSummary s = scanWorldToFile(box, params, bt);
    EXPECT_EQ(s.rays, 180u * 360u);
    EXPECT_GT(s.returns, 0u);
    EXPECT_GT(s.occupiedLeaves, 0u);
    const WorldSpec scanned = loadWorldFile(dir.write("w.yaml", worldYaml("octomap: scan.bt")));
    // The face the scanner saw is where the wall's face is; the scan has only that face.
    const RayCaster rc(scanned);
    EXPECT_NEAR(rc.castRay({0, 0.05f, 1.05f}, {1, 0, 0}, 10.0f), 1.0f, 1e-5);
    EXPECT_EQ(rc.castRay({0, 0, 1}, {-1, 0, 0}, 10.0f), std::numeric_limits<float>::infinity());
    for (const Aabb& b : scanned.voxelMaps[0].boxes) {
        EXPECT_GE(b.min.x(), 1.0 - 1e-9);
        EXPECT_LE(b.max.x(), 1.1 + 1e-9);  // only the cells just behind the face
    }
    const std::string ply = (dir.path() / "scan.ply").string();
    EXPECT_EQ(scanWorldToFile(box, params, ply).returns, s.returns);
    const WorldSpec cloud = loadWorldFile(
        dir.write("w.yaml", worldYaml("point_cloud: {file: scan.ply, voxel_size: 0.1}")));
    EXPECT_EQ(cloud.voxelMaps[0].cells, scanned.voxelMaps[0].cells);
    EXPECT_THROW(scanWorldToFile(box, params, (dir.path() / "scan.obj").string()), InputError);
}

TEST(VoxelMaps, ShippedScansOfTheTinyRoomHaveItsWalls) {
    const std::string maps = std::string(DAEP_SOURCE_DIR) + "/tests/e2e/data/maps/";
    for (const char* file : {"tiny_room_bt.yaml", "tiny_room_ot.yaml", "tiny_room_ply.yaml"}) {
        const WorldSpec w = loadWorldFile(maps + file);
        ASSERT_EQ(w.voxelMaps.size(), 1u) << file;
        const double res = w.voxelMaps[0].resolution;
        const RayCaster rc(w);
        // From the west room towards the partition's face at x = -0.075, and up into the sky.
        const float d = rc.castRay({-2, -1, 1}, {1, 0, 0}, 10.0f);
        EXPECT_NEAR(d, 1.925f, res + 1e-4) << file;
        EXPECT_EQ(rc.castRay({-2, -1, 1}, {0, 0, 1}, 10.0f), std::numeric_limits<float>::infinity())
            << file;
        const StaticCollisionChecker checker(w);
        for (const auto& s : w.starts)
            EXPECT_FALSE(checker.overlaps(s + Eigen::Vector3d(0, 0, 1), {0.4, 0.4, 0.1}, 0.0))
                << file;
    }
}

}  // namespace
}  // namespace daep::world
