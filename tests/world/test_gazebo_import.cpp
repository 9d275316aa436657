#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "TestFiles.h"
#include "daep/common/Error.h"
#include "daep/world/GazeboImport.h"
#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace daep::world {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

const std::string kWorld = R"(<?xml version="1.0"?>
<!-- a comment <model name='ignored'/> -->
<sdf version='1.6'>
  <world name='default'>
    <include><uri>model://ground_plane</uri></include>
    <model name='walls'>
      <pose frame=''>10 0 0 0 0 0</pose>
      <link name='a'>
        <pose>1 0 0 0 0 1.5707963267948966</pose>
        <collision name='c'>
          <pose>0 2 0.5 0 0 0</pose>
          <geometry><box><size>2 0.2 1</size></box></geometry>
        </collision>
      </link>
      <link name='b'>
        <collision name='c'>
          <geometry><cylinder><radius>0.3</radius><length>2</length></cylinder></geometry>
        </collision>
        <collision name='s'>
          <pose>0 0 3 0 0 0</pose>
          <geometry><sphere><radius>0.5</radius></sphere></geometry>
        </collision>
      </link>
    </model>
    <model name='moved'>
      <pose>0 0 0 0 0 0</pose>
      <link name='l'>
        <collision name='c'>
          <geometry><box><size>1 1 1</size></box></geometry>
        </collision>
      </link>
    </model>
    <include>
      <uri>model://crate</uri>
      <name>crate_1</name>
      <pose>0 -5 0 0 0 0</pose>
    </include>
    <include><uri>model://person_walking_fixed</uri><name>person_walking1</name></include>
    <state world_name='default'>
      <model name='moved'>
        <pose frame=''>3 4 0.5 0 -0 0</pose>
        <link name='l'><pose frame=''>3 4 0.5 0 -0 0</pose></link>
      </model>
    </state>
  </world>
</sdf>
)";

const std::string kCrate = R"(<?xml version="1.0" ?>
<sdf version="1.6">
  <model name="crate">
    <pose>100 100 100 0 0 0</pose>
    <link name="body">
      <collision name="mesh">
        <pose>0 0 0.25 0 0 0</pose>
        <geometry><mesh><uri>model://crate/meshes/crate.obj</uri><scale>2 3 0.5</scale></mesh></geometry>
      </collision>
    </link>
  </model>
</sdf>
)";

const std::string kGroundPlane = R"(<?xml version="1.0" ?>
<sdf version="1.5"><model name="ground_plane"><static>true</static><link name="link">
  <collision name="collision"><geometry><plane><normal>0 0 1</normal><size>100 100</size></plane></geometry></collision>
</link></model></sdf>
)";

const std::string kCube =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

struct Models {
    TempDir dir;
    Models() {
        dir.write("models/crate/model.config",
                  "<?xml version='1.0'?><model><name>Crate</name><sdf version='1.6'>crate.sdf"
                  "</sdf></model>");
        dir.write("models/crate/crate.sdf", kCrate);
        dir.write("models/crate/meshes/crate.obj", kCube);
        dir.write("models/ground_plane/model.sdf", kGroundPlane);
    }
    GazeboImportOptions options() const {
        GazeboImportOptions o;
        o.modelPaths = {(dir.path() / "models").string()};
        return o;
    }
};

const BoxShape& boxNamed(const ImportedWorld& w, const std::string& name) {
    for (const auto& b : w.boxes)
        if (b.name == name)
            return b;
    throw std::runtime_error("no box " + name);
}

TEST(GazeboImport, ComposesModelLinkAndCollisionPoses) {
    Models m;
    const auto w = importSdfText(kWorld, "inline.world", m.dir.path().string(), m.options());
    const auto& wall = boxNamed(w, "walls/a");
    // model (10,0,0) * link (1,0,0 yaw 90) * collision (0,2,0.5): local +y becomes world -x.
    EXPECT_NEAR(wall.pose.translation().x(), 9.0, 1e-9);
    EXPECT_NEAR(wall.pose.translation().y(), 0.0, 1e-9);
    EXPECT_NEAR(wall.pose.translation().z(), 0.5, 1e-9);
    EXPECT_NEAR((wall.pose.linear() * Eigen::Vector3d::UnitX()).y(), 1.0, 1e-9);
    EXPECT_EQ(wall.size, Eigen::Vector3d(2, 0.2, 1));
    EXPECT_TRUE(w.ground);
}

TEST(GazeboImport, CylindersSpheresAndMultipleCollisionsPerLink) {
    Models m;
    const auto w = importSdfText(kWorld, "inline.world", m.dir.path().string(), m.options());
    ASSERT_EQ(w.cylinders.size(), 2u);
    EXPECT_EQ(w.cylinders[0].name, "walls/b/c");
    EXPECT_DOUBLE_EQ(w.cylinders[0].radius, 0.3);
    EXPECT_DOUBLE_EQ(w.cylinders[0].length, 2.0);
    EXPECT_EQ(w.cylinders[1].name, "walls/b/s");  // sphere as its enclosing cylinder
    EXPECT_DOUBLE_EQ(w.cylinders[1].length, 1.0);
    EXPECT_NEAR(w.cylinders[1].pose.translation().z(), 3.0, 1e-12);
    ASSERT_FALSE(w.warnings.empty());
    EXPECT_NE(w.warnings[0].find("sphere"), std::string::npos);
}

TEST(GazeboImport, StatePosesOverrideDeclaredPoses) {
    Models m;
    const auto w = importSdfText(kWorld, "inline.world", m.dir.path().string(), m.options());
    const auto& moved = boxNamed(w, "moved/l");
    EXPECT_NEAR((moved.pose.translation() - Eigen::Vector3d(3, 4, 0.5)).norm(), 0.0, 1e-12);
}

TEST(GazeboImport, IncludeResolvesModelPathConfigAndMeshScale) {
    Models m;
    const auto w = importSdfText(kWorld, "inline.world", m.dir.path().string(), m.options());
    ASSERT_EQ(w.meshes.size(), 1u);  // the person include is skipped
    const auto& mesh = w.meshes[0];
    EXPECT_EQ(mesh.name, "crate_1/body");
    EXPECT_EQ(fs::path(mesh.file), m.dir.path() / "models/crate/meshes/crate.obj");
    EXPECT_EQ(mesh.scale, Eigen::Vector3d(2, 3, 0.5));
    // The include's pose replaces the model file's pose (100, 100, 100).
    EXPECT_NEAR((mesh.pose.translation() - Eigen::Vector3d(0, -5, 0.25)).norm(), 0.0, 1e-12);
}

TEST(GazeboImport, WrittenYamlLoadsWithTheSameGeometry) {
    Models m;
    auto w = importSdfText(kWorld, "inline.world", m.dir.path().string(), m.options());
    w.name = "inline";
    const std::string yaml = (m.dir.path() / "out/inline.yaml").string();
    fs::create_directories(m.dir.path() / "out");
    saveWorldYaml(w, yaml);
    const WorldSpec spec = loadWorldFile(yaml);
    EXPECT_EQ(spec.boxes.size(), 3u);  // two boxes and the ground slab
    ASSERT_EQ(spec.meshes.size(), 1u);
    EXPECT_EQ(spec.meshes[0].triangles.size(), 12u);
    // Cube [0,1]^3 scaled (2, 3, 0.5), at (0, -5, 0.25).
    Eigen::Vector3f lo = spec.meshes[0].vertices[0], hi = lo;
    for (const auto& v : spec.meshes[0].vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    EXPECT_NEAR((lo - Eigen::Vector3f(0, -5, 0.25)).norm(), 0.0, 1e-5);
    EXPECT_NEAR((hi - Eigen::Vector3f(2, -2, 0.75)).norm(), 0.0, 1e-5);
    // No box config: the box is the geometry's bounds.
    EXPECT_NEAR(spec.explorationBox.max.x(), 10.5, 1e-3);  // the sphere at x = 10, r 0.5
    EXPECT_EQ(spec.starts.size(), 1u);
}

TEST(GazeboImport, MissingModelNamesUriAndSearchPath) {
    GazeboImportOptions o;
    o.modelPaths = {"/nonexistent/models"};
    try {
        importSdfText(kWorld, "inline.world", "/tmp", o);
        FAIL() << "expected an InputError";
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("inline.world:5:"), std::string::npos) << msg;
        EXPECT_NE(msg.find("model://ground_plane"), std::string::npos) << msg;
        EXPECT_NE(msg.find("/nonexistent/models"), std::string::npos) << msg;
    }
    o.skipMissing = true;
    const auto w = importSdfText(kWorld, "inline.world", "/tmp", o);
    EXPECT_EQ(w.meshes.size(), 0u);
    EXPECT_EQ(w.boxes.size(), 2u);
    EXPECT_FALSE(w.ground);
}

void expectError(const std::string& sdf, const std::string& expected) {
    try {
        importSdfText(sdf, "bad.world", "/tmp", {});
        FAIL() << "expected an InputError containing " << expected;
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
}

TEST(GazeboImport, ErrorsNameFileLineAndElement) {
    expectError(
        "<sdf><world><model name='m'><link name='l'><collision name='c'>\n"
        "<geometry><box><size>1 2</size></box></geometry></collision></link></model>"
        "</world></sdf>",
        "bad.world:2: <size>: expected 3 numbers, got 2");
    expectError("<sdf><world><model name='m'>\n<pose>0 0 x 0 0 0</pose></model></world></sdf>",
                "bad.world:2: <pose>: 'x' is not a number");
    expectError(
        "<sdf><world><model name='m'><link name='l'><collision name='c'>\n"
        "<geometry><cylinder><radius>-1</radius><length>1</length></cylinder>"
        "</geometry></collision></link></model></world></sdf>",
        "bad.world:2: <radius>: must be > 0");
    expectError(
        "<sdf><world><model name='m'><link name='l'><collision name='c'><geometry>\n"
        "<heightmap/></geometry></collision></link></model></world></sdf>",
        "bad.world:2: <heightmap>: geometry <heightmap> is not supported");
    expectError("<sdf><world>\n<model name='m'></world></sdf>", "bad.world:");
    expectError("<world/>", "root element is not <sdf>");
}

TEST(GazeboImport, SideFilesPeopleBoxAndStarts) {
    TempDir d;
    const auto launch =
        d.write("p.launch",
                "<launch><!-- <node args=\"'ghost' '[(0, 0), (1, 1)]'\"/> -->\n"
                "<node pkg='x' type='field_motion.py' name='m1' "
                "args=\"'person_walking7' '[(-1.5, 2), (3, 4.25), (0, 0)]' $(arg avoidance)\" />\n"
                "<node pkg='x' type='other' name='o' args='--flag'/></launch>");
    const auto people = readLaunchPeople(launch);
    ASSERT_EQ(people.size(), 1u);
    EXPECT_EQ(people[0].name, "person_walking7");
    ASSERT_EQ(people[0].waypoints.size(), 3u);
    EXPECT_EQ(people[0].waypoints[1], Eigen::Vector2d(3, 4.25));

    const auto cfg = d.write("b.yaml",
                             "res: 0.2\nboundary/min: [-5, -11, 0.0]\n"
                             "boundary/max: [4, 12, 2.5]\nboundary/volume: 510 # x\n");
    Aabb box;
    double volume = 0;
    readExplorationBoundary(cfg, box, volume);
    EXPECT_EQ(box.min, Eigen::Vector3d(-5, -11, 0));
    EXPECT_EQ(box.max, Eigen::Vector3d(4, 12, 2.5));
    EXPECT_DOUBLE_EQ(volume, 510.0);

    const auto exp = d.write("e.yaml",
                             "spawn_positions:\n  cafe :\n  - (-3.5,-9.8,0.2)\n"
                             "  - (3,8.7,0.2)\n\n  maze :\n  - (12.1,-0.1,0.1)\n"
                             "other: 1\n");
    const auto starts = readSpawnPositions(exp, "cafe");
    ASSERT_EQ(starts.size(), 2u);
    EXPECT_EQ(starts[1], Eigen::Vector3d(3, 8.7, 0.2));
    EXPECT_EQ(readSpawnPositions(exp, "maze").size(), 1u);
    EXPECT_THROW(readSpawnPositions(exp, "patrol"), InputError);
}

// ---- the benchmark's real worlds ----

const std::string kBench = std::string(DAEP_SHARED_DIR) + "/datasets/daep-benchmark";

GazeboImportOptions benchOptions(const std::string& world) {
    GazeboImportOptions o;
    o.modelPaths = {kBench + "/models"};
    o.peopleFile = kBench + "/launch/" + world + "_dynamic.launch";
    o.boxConfig = kBench + "/config/" + world + "_exploration.yaml";
    o.startsFile = kBench + "/config/experiments.yaml";
    o.startsKey = world;
    o.name = world;
    return o;
}

double footprintArea(const std::vector<BoxShape>& boxes) {
    double a = 0;
    for (const auto& b : boxes)
        if (b.name != "ground")
            a += b.size.x() * b.size.y();
    return a;
}

TEST(GazeboImportBenchmark, ExhibitionMatchesTheBuiltinWorld) {
    if (!fs::exists(kBench))
        GTEST_SKIP() << kBench << " not present";
    const auto w =
        importGazeboWorld(kBench + "/worlds/exhibition_static.world", benchOptions("exhibition"));
    TempDir d;
    saveWorldYaml(w, (d.path() / "exhibition.yaml").string());
    const WorldSpec imported = loadWorldFile((d.path() / "exhibition.yaml").string());
    const WorldSpec builtin = loadWorldFile(resolveWorldPath("exhibition"));
    EXPECT_EQ(imported.boxes.size(), builtin.boxes.size());
    EXPECT_NEAR(footprintArea(imported.boxes), footprintArea(builtin.boxes), 1e-6);
    for (size_t i = 0; i < builtin.boxes.size(); ++i)
        EXPECT_NEAR(
            (imported.boxes[i].pose.translation() - builtin.boxes[i].pose.translation()).norm(),
            0.0, 1e-3)
            << builtin.boxes[i].name;
    EXPECT_EQ(imported.explorationBox.min, builtin.explorationBox.min);
    EXPECT_EQ(imported.explorationBox.max, builtin.explorationBox.max);
    EXPECT_DOUBLE_EQ(imported.explorationVolume(), 450.0);
    EXPECT_EQ(imported.starts, builtin.starts);
    ASSERT_EQ(imported.people.size(), builtin.people.size());
    for (size_t i = 0; i < builtin.people.size(); ++i)
        EXPECT_EQ(imported.people[i].waypoints, builtin.people[i].waypoints);
}

TEST(GazeboImportBenchmark, MazeMeshLoadsAndBlocksRays) {
    if (!fs::exists(kBench))
        GTEST_SKIP() << kBench << " not present";
    auto o = benchOptions("maze");
    o.skipMissing = true;  // the nist_maze_wall models are not in the data set
    const auto w = importGazeboWorld(kBench + "/worlds/maze_static.world", o);
    ASSERT_EQ(w.meshes.size(), 1u);
    EXPECT_EQ(w.meshes[0].scale, Eigen::Vector3d::Constant(0.1));  // the visual's scale
    TempDir d;
    saveWorldYaml(w, (d.path() / "maze.yaml").string());
    const WorldSpec maze = loadWorldFile((d.path() / "maze.yaml").string());
    ASSERT_EQ(maze.meshes.size(), 1u);
    EXPECT_GT(maze.meshes[0].triangles.size(), 1000u);
    EXPECT_EQ(maze.starts.size(), 5u);
    EXPECT_EQ(maze.people.size(), 5u);

    // From each start, at 1.3 m, a ray in some horizontal direction hits a maze wall nearby.
    RayCaster caster(maze);
    for (const auto& s : maze.starts) {
        const Eigen::Vector3f origin = (s + Eigen::Vector3d(0, 0, 1.2)).cast<float>();
        float nearest = 1e9f;
        for (int k = 0; k < 8; ++k) {
            const float a = static_cast<float>(k * M_PI / 4);
            nearest =
                std::min(nearest, caster.castRay(origin, {std::cos(a), std::sin(a), 0}, 30.f));
        }
        EXPECT_LT(nearest, 10.f) << s.transpose();
    }
    // The drone fits at every start, but not on top of a wall (the mesh's wall at y = -2.6).
    StaticCollisionChecker checker(maze);
    for (const auto& s : maze.starts)
        EXPECT_FALSE(checker.overlaps(s + Eigen::Vector3d(0, 0, 1.0), {0.4, 0.4, 0.1}, 0.0));
    bool hitWall = false;
    for (double x = -7; x < 13.5 && !hitWall; x += 0.1)
        hitWall = checker.overlaps({x, -3.0, 1.2}, {0.4, 0.4, 0.1}, 0.0);
    EXPECT_TRUE(hitWall);
}

}  // namespace
}  // namespace daep::world
