// Worlds that parse but cannot be flown, and duplicate keys: each is an InputError naming the
// file and the item (or line), never a crash or a silent run.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "../../libs/world/src/YamlDuplicateKeys.h"
#include "TestFiles.h"
#include "daep/common/Error.h"
#include "daep/world/WorldSpec.h"

namespace daep::world {
namespace {

using test::TempDir;

/** A 10 x 10 m room with a wall across its middle that has a 2 m door at y in [3, 5]. */
std::string room(const std::string& starts, const std::string& extra) {
    return "name: room\n"
           "exploration_box: {min: [-5, -5, 0], max: [5, 5, 2.5]}\n"
           "ground: true\n"
           "starts: " +
           starts +
           "\n"
           "boxes:\n"
           "  - {name: wall, center: [0, -1, 1.25], size: [0.2, 8, 2.5]}\n"
           "  - {name: crate, center: [-3, -3, 0.5], size: [1, 1, 1]}\n" +
           extra;
}

/** The message of the InputError loading `yaml` throws ("" if it loads). */
std::string loadError(const std::string& yaml) {
    TempDir dir;
    const std::string path = dir.write("bad_world.yaml", yaml);
    try {
        loadWorldFile(path);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

void expectError(const std::string& yaml, const std::vector<std::string>& parts) {
    const std::string msg = loadError(yaml);
    ASSERT_FALSE(msg.empty()) << "loaded: " << yaml;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_NE(msg.find("bad_world.yaml"), std::string::npos) << msg;
    for (const auto& p : parts)
        EXPECT_NE(msg.find(p), std::string::npos) << p << " not in: " << msg;
}

TEST(WorldValidation, AValidRoomLoads) {
    EXPECT_EQ(
        loadError(room("[[2, 2, 0.2]]",
                       "people:\n  - {name: ok, waypoints: [[-2, 4], [2, 4], [2, -3], [2, 4]]}\n")),
        "");
}

TEST(WorldValidation, StartInsideGeometry) {
    expectError(room("[[2, 2, 0.2], [-3, -3, 0.2]]", ""),
                {"starts[1]", "(-3.00, -3.00, 0.20)", "inside", "'crate'"});
}

TEST(WorldValidation, PersonRouteThroughAWall) {
    expectError(room("[[2, 2, 0.2]]",
                     "people:\n  - {name: ok, waypoints: [[-2, 4], [2, 4]]}\n"
                     "  - {name: ghost, waypoints: [[-2, 0], [2, 0]]}\n"),
                {"people[1] 'ghost'", "leg 0", "runs into", "'wall'"});
}

TEST(WorldValidation, TheClosingLegBackToTheFirstWaypointCounts) {
    // (-2, 4) -> (2, 4) -> (2, -3) is through the door; (2, -3) back to (-2, 4) is not.
    expectError(room("[[2, 2, 0.2]]",
                     "people:\n  - {name: loop, waypoints: [[-2, 4], [2, 4], [2, -3], [2, 4]]}\n"
                     "  - {name: back, waypoints: [[2, -3], [2, 4], [-2, 4], [-2, -3]]}\n"),
                {"people[1] 'back'", "leg 3", "(-2.00, -3.00) -> (2.00, -3.00)", "'wall'"});
}

TEST(WorldValidation, RoutePassingCloseToAWallIsFine) {
    // 0.2 m from the wall's face: people walk along walls.
    EXPECT_EQ(loadError(room("[[2, 2, 0.2]]",
                             "people:\n  - {name: hug, waypoints: [[0.3, -4], [0.3, 2]]}\n")),
              "");
}

TEST(WorldValidation, ExplorationBoxOfZeroOrNegativeSize) {
    for (const char* box :
         {"{min: [0, 0, 0], max: [10, 0, 2]}", "{min: [0, 0, 0], max: [-1, 5, 2]}"})
        expectError(std::string("exploration_box: ") + box + "\nstarts: [[1, 1, 0]]\n",
                    {"exploration_box", "max must exceed min"});
}

TEST(WorldValidation, NanOrHugeCoordinates) {
    expectError(room("[[nan, 2, 0.2]]", ""), {"starts", "is not a number"});
    expectError(
        room("[[2, 2, 0.2]]", "cylinders:\n  - {center: [1e300, 0, 1], radius: 1, length: 2}\n"),
        {"cylinders[0]", "farther than 5000 m"});
    expectError("exploration_box: {min: [0, 0, 0], max: [1e6, 1e6, 10]}\nstarts: [[1, 1, 0]]\n",
                {"exploration_box"});
    expectError(room("[[2, 2, 0.2]]", "people:\n  - {waypoints: [[0, 4], [9e9, 4]]}\n"),
                {"people[0]", "waypoint 1", "farther than"});
}

TEST(WorldValidation, MeshWithNoTriangles) {
    TempDir dir;
    dir.write("meshes/empty.obj", "# vertices only\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
    const std::string path =
        dir.write("bad_world.yaml",
                  room("[[2, 2, 0.2]]", "meshes:\n  - {name: flat, file: meshes/empty.obj}\n"));
    try {
        loadWorldFile(path);
        FAIL() << "a mesh without triangles loaded";
    } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("bad_world.yaml:"), std::string::npos) << msg;
        EXPECT_NE(msg.find("meshes/empty.obj"), std::string::npos) << msg;
    }
}

TEST(WorldValidation, DuplicateKeysNameTheLine) {
    expectError(room("[[2, 2, 0.2]]", "ground: true\n"),
                {"bad_world.yaml:8:", "duplicate key 'ground'", "first given on line 3"});
    expectError(room("[[2, 2, 0.2]]",
                     "  - {name: a, center: [1, 1, 1], size: [1, 1, 1], center: [2, 2, 1]}\n"),
                {"bad_world.yaml:8:", "duplicate key 'center'"});
    expectError(room("[[2, 2, 0.2]]",
                     "people:\n  - name: a\n    waypoints: [[0, 4], [1, 4]]\n    name: b\n"),
                {"bad_world.yaml:11:", "duplicate key 'name'", "first given on line 9"});
}

TEST(WorldValidation, BytesThatAreNotUtf8NameTheLine) {
    // libfyaml loops forever on a directive followed by 0xff (found by fuzz_world_file).
    expectError(room("[[2, 2, 0.2]]", "# caf\xe9\n"), {"bad_world.yaml:8:", "not UTF-8 text"});
    expectError("%pe\xff\xff\xff\n", {"bad_world.yaml:1:", "not UTF-8 text"});
    // ...and on a 4-byte form beyond U+10FFFF (lead 0xf6, found by a 1M-execution run); the
    // other forms RFC 3629 rules out are refused too: overlong, surrogate, past U+10FFFF.
    for (const char* bad :
         {"%\xf6\x9a\x9a\x85\n", "a: \xc0\xaf\n", "a: \xe0\x80\xaf\n", "a: \xed\xa0\x80\n",
          "a: \xf0\x80\x80\xaf\n", "a: \xf4\x90\x80\x80\n", "a: \xe2\x82\n"})
        expectError(std::string("# ok\n") + bad, {"bad_world.yaml:2:", "not UTF-8 text"});
    const std::string utf8 = loadError(
        room("[[2, 2, 0.2]]", "# caf\xc3\xa9, \xe2\x82\xac \xf0\x9f\x9a\x81 \xf4\x8f\xbf\xbf\n"));
    EXPECT_EQ(utf8.find("not UTF-8"), std::string::npos) << utf8;
}

TEST(YamlDuplicateKeys, SameKeysInSiblingMappingsAreNotDuplicates) {
    const std::string ok =
        "a: 1\nlist:\n  - {name: x, v: 1}\n  - {name: y, v: 2}\n"
        "  - name: z\n    v: 3\n  - name: w\n    v: 4\n"
        "nested:\n  a: 1\n  b: {a: 1, b: [1, {a: 2}]}\n"
        "text: |\n  a: 1\n  a: 2\n"
        "quoted: \"a: 1, a: 2\"  # a: 1\n";
    EXPECT_FALSE(findDuplicateKey(ok).has_value());
    const auto dup = findDuplicateKey("a: 1\nb:\n  c: 1\n  d: [1,\n    2]\n  c: 2\n");
    ASSERT_TRUE(dup.has_value());
    EXPECT_EQ(dup->key, "c");
    EXPECT_EQ(dup->line, 6);
    EXPECT_EQ(dup->firstLine, 3);
}

TEST(WorldValidation, EveryBuiltinWorldLoads) {
    for (const std::string& name : builtinWorldNames()) {
        SCOPED_TRACE(name);
        EXPECT_NO_THROW(loadWorldFile(resolveWorldPath(name)));
    }
}

}  // namespace
}  // namespace daep::world
