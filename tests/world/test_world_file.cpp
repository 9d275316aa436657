#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>

#include "TestFiles.h"
#include "daep/common/Error.h"
#include "daep/world/WorldSpec.h"

namespace daep::world {
namespace {

using test::TempDir;

const char* kTriangleObj =
    "v 0 0 0\n"
    "v 1 0 0\n"
    "v 0 1 0\n"
    "f 1 2 3\n";

const char* kTinyWorld = R"(# a small world
name: tiny
description: "test world: with a colon"
exploration_box: {min: [-1, -2, 0], max: [3, 4, 2.5]}
exploration_volume: 50
starts: [[0, 0, 0.3], [1, 1, 0.3]]
ground: true
boxes:
  - {name: b1, center: [1, 2, 0.5], size: [1, 2, 1], yaw_deg: 90}
  - name: b2
    center: [0, 3, 1]
    size: [0.5, 0.5, 0.5]
    rpy_deg: [90, 0, 0]
cylinders:
  - {name: c1, center: [2, 0, 1], radius: 0.3, length: 2}
meshes:
  - {name: tri, file: meshes/tri.obj, position: [10, 0, 0], rpy_deg: [0, 0, 90], scale: [2, 2, 2]}
people:
  - {name: p1, waypoints: [[0, 0], [1, 0], [1, 1]]}
)";

TEST(WorldFile, LoadsEveryKindOfEntry) {
    TempDir dir;
    dir.write("meshes/tri.obj", kTriangleObj);
    const std::string path = dir.write("tiny.yaml", kTinyWorld);
    const WorldSpec w = loadWorldFile(path);

    EXPECT_EQ(w.name, "tiny");
    EXPECT_EQ(w.description, "test world: with a colon");
    EXPECT_EQ(w.sourceFile, path);
    EXPECT_TRUE(w.explorationBox.min.isApprox(Eigen::Vector3d(-1, -2, 0)));
    EXPECT_TRUE(w.explorationBox.max.isApprox(Eigen::Vector3d(3, 4, 2.5)));
    EXPECT_DOUBLE_EQ(w.explorationVolume(), 50.0);
    ASSERT_EQ(w.starts.size(), 2u);
    EXPECT_TRUE(w.starts[1].isApprox(Eigen::Vector3d(1, 1, 0.3)));

    ASSERT_EQ(w.boxes.size(), 3u);  // b1, b2 and the ground slab
    EXPECT_EQ(w.boxes[0].name, "b1");
    EXPECT_TRUE(w.boxes[0].pose.translation().isApprox(Eigen::Vector3d(1, 2, 0.5)));
    EXPECT_TRUE(w.boxes[0].pose.linear().col(0).isApprox(Eigen::Vector3d(0, 1, 0), 1e-12));
    EXPECT_TRUE(w.boxes[0].size.isApprox(Eigen::Vector3d(1, 2, 1)));
    // Roll 90 deg turns the local y axis onto +z.
    EXPECT_TRUE(w.boxes[1].pose.linear().col(1).isApprox(Eigen::Vector3d(0, 0, 1), 1e-12));

    ASSERT_EQ(w.cylinders.size(), 1u);
    EXPECT_DOUBLE_EQ(w.cylinders[0].radius, 0.3);
    EXPECT_DOUBLE_EQ(w.cylinders[0].length, 2.0);

    ASSERT_EQ(w.meshes.size(), 1u);
    const TriangleMesh& m = w.meshes[0];
    ASSERT_EQ(m.triangles.size(), 1u);
    ASSERT_EQ(m.vertices.size(), 3u);
    // (1,0,0) scaled by 2, turned 90 deg about z, moved by (10,0,0).
    EXPECT_TRUE(m.vertices[m.triangles[0][1]].isApprox(Eigen::Vector3f(10, 2, 0), 1e-6f));
    EXPECT_NE(m.source.find("tri.obj"), std::string::npos);

    ASSERT_EQ(w.people.size(), 1u);
    EXPECT_EQ(w.people[0].name, "p1");
    ASSERT_EQ(w.people[0].waypoints.size(), 3u);
    EXPECT_TRUE(w.people[0].waypoints[2].isApprox(Eigen::Vector2d(1, 1)));
}

TEST(WorldFile, GroundSlabTopsAtZeroAndCoversBoundsWithMargin) {
    TempDir dir;
    dir.write("meshes/tri.obj", kTriangleObj);
    const WorldSpec w = loadWorldFile(dir.write("tiny.yaml", kTinyWorld));
    const BoxShape& g = w.boxes.back();
    EXPECT_EQ(g.name, "ground");
    EXPECT_NEAR(g.pose.translation().z() + 0.5 * g.size.z(), 0.0, 1e-12);
    // Without the slab, geometry spans x in [-1, 10] (mesh) and y in [-2, 4] (box).
    EXPECT_NEAR(g.pose.translation().x() - 0.5 * g.size.x(), -1.0 - 2.0, 1e-9);
    EXPECT_NEAR(g.pose.translation().x() + 0.5 * g.size.x(), 10.0 + 2.0, 1e-9);
    EXPECT_NEAR(g.pose.translation().y() - 0.5 * g.size.y(), -2.0 - 2.0, 1e-9);
    EXPECT_NEAR(g.pose.translation().y() + 0.5 * g.size.y(), 4.0 + 2.0, 1e-9);
}

TEST(WorldFile, DefaultsAndBounds) {
    TempDir dir;
    const std::string path = dir.write("plain.yaml",
                                       "exploration_box: {min: [0, 0, 0], max: [2, 3, 4]}\n"
                                       "starts: [[1, 1, 1]]\n"
                                       "boxes: [{center: [5, 0, 1], size: [2, 2, 2]}]\n");
    const WorldSpec w = loadWorldFile(path);
    EXPECT_EQ(w.name, "plain");  // from the file name
    EXPECT_DOUBLE_EQ(w.explorationVolume(), 24.0);
    EXPECT_EQ(w.boxes.size(), 1u);  // no ground unless asked
    EXPECT_EQ(w.boxes[0].name, "boxes[0]");
    const Aabb b = w.bounds();
    EXPECT_TRUE(b.min.isApprox(Eigen::Vector3d(0, -1, 0)));
    EXPECT_TRUE(b.max.isApprox(Eigen::Vector3d(6, 3, 4)));
}

TEST(WorldFile, LoadsColladaWithUnitsFromBenchmarkData) {
    const std::string dae = std::string(DAEP_SHARED_DIR) +
                            "/datasets/daep-benchmark/models/cafe_table/meshes/cafe_table.dae";
    if (!std::filesystem::exists(dae))
        GTEST_SKIP() << "benchmark data not present: " << dae;
    TempDir dir;
    const WorldSpec w =
        loadWorldFile(dir.write("t.yaml",
                                "exploration_box: {min: [-1, -1, 0], max: [1, 1, 1]}\n"
                                "starts: [[0, 0, 1]]\n"
                                "meshes: [{file: " +
                                    dae + "}]\n"));
    ASSERT_EQ(w.meshes.size(), 1u);
    EXPECT_GT(w.meshes[0].triangles.size(), 10u);
    Eigen::Vector3f lo = Eigen::Vector3f::Constant(1e9f), hi = -lo;
    for (const auto& v : w.meshes[0].vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    // The file is in inches and z-up; its Gazebo collision boxes say: 0.913 m wide top at
    // 0.755 +- 0.02 m, standing on z = 0.
    EXPECT_NEAR(hi.x() - lo.x(), 0.913, 0.05);
    EXPECT_NEAR(hi.y() - lo.y(), 0.913, 0.05);
    EXPECT_NEAR(lo.z(), 0.0, 0.02);
    EXPECT_NEAR(hi.z(), 0.775, 0.03);
}

struct BadCase {
    const char* what;
    std::string yaml;
    std::vector<std::string> expected;  ///< substrings of the message
};

std::string validTail() {
    return "exploration_box: {min: [0, 0, 0], max: [1, 1, 1]}\nstarts: [[0.5, 0.5, 0.5]]\n";
}

std::vector<BadCase> badCases() {
    const std::string tail = validTail();
    return {
        {"missing box", "name: x\nstarts: [[0, 0, 0]]\n", {"exploration_box", "missing"}},
        {"two-number size",
         tail + "boxes:\n  - {center: [0, 0, 0], size: [1, 1, 1]}\n"
                "  - {center: [0, 0, 0], size: [1, 2]}\n",
         {":5:", "boxes[1].size", "expected 3 numbers, got 2"}},
        {"negative size",
         tail + "boxes:\n  - center: [0, 0, 0]\n    size: [1, -1, 1]\n",
         {":5:", "boxes[0].size", "> 0"}},
        {"one waypoint",
         tail + "people:\n  - {name: p, waypoints: [[1, 2]]}\n",
         {":4:", "people[0].waypoints", "at least 2 waypoints"}},
        {"unknown top-level key", tail + "boxs: []\n", {":3:", "boxs", "unknown key"}},
        {"unknown nested key",
         tail + "cylinders:\n  - {center: [0, 0, 0], radius: 1, length: 1,\n"
                "     colour: red}\n",
         {":5:", "cylinders[0].colour", "unknown key"}},
        {"not a number",
         tail + "boxes:\n  - {center: [0, x, 0], size: [1, 1, 1]}\n",
         {":4:", "boxes[0].center[1]", "'x' is not a number"}},
        {"yaw and rpy",
         tail + "boxes:\n  - {center: [0, 0, 0], size: [1, 1, 1], yaw_deg: 3,\n"
                "     rpy_deg: [0, 0, 3]}\n",
         {":5:", "boxes[0].rpy_deg", "either"}},
        {"missing mesh",
         tail + "meshes:\n  - {file: meshes/nope.stl}\n",
         {":4:", "meshes[0].file", "meshes/nope.stl", "not found"}},
        {"negative radius",
         tail + "cylinders:\n  - {center: [0, 0, 0], radius: -1, length: 1}\n",
         {":4:", "cylinders[0].radius", "> 0"}},
        {"empty box",
         "exploration_box: {min: [0, 0, 0], max: [1, 0, 1]}\nstarts: [[0, 0, 0]]\n",
         {":1:", "exploration_box", "max must exceed min"}},
        {"no starts",
         "exploration_box: {min: [0, 0, 0], max: [1, 1, 1]}\nstarts: []\n",
         {":2:", "starts", "at least one"}},
        {"start of 2 numbers",
         "exploration_box: {min: [0, 0, 0], max: [1, 1, 1]}\nstarts: [[0, 0]]\n",
         {":2:", "starts[0]", "expected 3 numbers"}},
        {"bad boolean", tail + "ground: maybe\n", {":3:", "ground", "not a boolean"}},
        {"boxes not a list", tail + "boxes: 3\n", {":3:", "boxes", "expected a list"}},
        {"syntax error", tail + "description: \"abc\nboxes: 3\n", {":3:", "YAML syntax error"}},
        {"key without value",
         tail + "boxes:\n  - center: [0, 0, 0]\n    size:\n",
         {":5:", "YAML syntax error", "no value"}},
        {"not a map", "- 1\n- 2\n", {"must be a map"}},
        {"flow list closed too far left",  // libfyaml stops early here without MRPT throwing
         tail + "people:\n  - name: a\n    waypoints: [\n      [0, 0], [1, 1]\n    ]\n"
                "  - {name: b, waypoints: [[0, 0], [1, 1]]}\n",
         {":7:", "YAML syntax error", "indented"}},
    };
}

TEST(WorldFile, ErrorsNameFileKeyPathAndLine) {
    TempDir dir;
    for (const BadCase& c : badCases()) {
        SCOPED_TRACE(c.what);
        const std::string path = dir.write("bad_world.yaml", c.yaml);
        try {
            loadWorldFile(path);
            ADD_FAILURE() << "no error for: " << c.yaml;
        } catch (const InputError& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find("bad_world.yaml"), std::string::npos) << msg;
            for (const auto& s : c.expected)
                EXPECT_NE(msg.find(s), std::string::npos) << msg;
            EXPECT_EQ(msg.find("bad_world.yaml"), msg.rfind("bad_world.yaml")) << msg;
        }
    }
}

TEST(WorldFile, MissingFileIsAnInputError) {
    try {
        loadWorldFile("/nonexistent/dir/w.yaml");
        FAIL();
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/w.yaml"), std::string::npos);
    }
}

TEST(WorldFile, UnreadableMeshIsNamed) {
    TempDir dir;
    dir.write("meshes/junk.obj", "this is not an obj file\x01\x02");
    const std::string path =
        dir.write("w.yaml", validTail() + "meshes:\n  - {name: junk, file: meshes/junk.obj}\n");
    try {
        loadWorldFile(path);
        FAIL();
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("w.yaml:4:"), std::string::npos) << msg;
        EXPECT_NE(msg.find("meshes/junk.obj"), std::string::npos) << msg;
    }
}

TEST(WorldFile, ResolvesBuiltinNamesAndPaths) {
    const auto names = builtinWorldNames();
    for (const char* n : {"apartment", "auditorium", "cafe", "crosswalks", "exhibition", "field",
                          "maze", "patrol", "tunnel", "village"})
        EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
    EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));

    const std::string p = resolveWorldPath("exhibition");
    EXPECT_EQ(std::filesystem::path(p).filename(), "exhibition.yaml");
    EXPECT_EQ(resolveWorldPath(p), p);
    try {
        resolveWorldPath("atlantis");
        FAIL();
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("atlantis"), std::string::npos) << msg;
        EXPECT_NE(msg.find("exhibition"), std::string::npos) << msg;
    }
}

}  // namespace
}  // namespace daep::world
