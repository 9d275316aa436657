// The built-in Cafe world is measured from the Gazebo model's visual mesh (what the reference
// depth camera saw and the reference drone flew through), not from its collision boxes: the
// kitchen wall at y = 7.43 has a doorway, a hatch and a pass-through.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "TestFiles.h"
#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace daep::world {
namespace {

const Eigen::Vector3d kDrone(0.4, 0.4, 0.1);  ///< the drone's collision box

WorldSpec cafe() {
    return loadWorldFile(resolveWorldPath("cafe"));
}

/** Distance along +y from (x, y0, z) to the first static hit. */
float northRange(const RayCaster& caster, double x, double y0, double z) {
    return caster.castRay(Eigen::Vector3f(float(x), float(y0), float(z)), Eigen::Vector3f(0, 1, 0),
                          100.0f);
}

/** A path from start 4 in the kitchen, up, through the doorway and into the dining room. */
std::vector<Eigen::Vector3d> kitchenToDiningPath(const WorldSpec& w) {
    const Eigen::Vector3d s = w.starts.at(4);
    return {s + Eigen::Vector3d(0, 0, 0.5 * kDrone.z()), Eigen::Vector3d(s.x(), s.y(), 1.2),
            Eigen::Vector3d(1.5, 9.3, 1.2), Eigen::Vector3d(1.5, 6.0, 1.2)};
}

/** True when the drone box (yaw 0) sweeps the polyline without touching static geometry. */
bool sweepIsClear(const StaticCollisionChecker& checker, const std::vector<Eigen::Vector3d>& path,
                  Eigen::Vector3d* firstHit) {
    for (std::size_t i = 0; i + 1 < path.size(); ++i) {
        const Eigen::Vector3d d = path[i + 1] - path[i];
        const int n = std::max(1, int(std::ceil(d.norm() / 0.02)));
        for (int k = 0; k <= n; ++k) {
            const Eigen::Vector3d c = path[i] + d * (double(k) / n);
            if (checker.overlaps(c, kDrone, 0.0)) {
                *firstHit = c;
                return false;
            }
        }
    }
    return true;
}

TEST(CafeWorld, KeepsTheBenchmarksBoxVolumeStartsAndPeople) {
    const WorldSpec w = cafe();
    EXPECT_EQ(w.explorationBox.min, Eigen::Vector3d(-5, -11, 0));
    EXPECT_EQ(w.explorationBox.max, Eigen::Vector3d(4, 12, 2.5));
    EXPECT_DOUBLE_EQ(w.explorationVolume(), 510.0);
    const std::vector<Eigen::Vector3d> starts = {
        {-3.5, -9.8, 0.2}, {-3, -5.3, 0.5}, {-3.2, 5.1, 0.5}, {3, 8.7, 0.2}, {-0.7, 9.6, 0.2}};
    ASSERT_EQ(w.starts.size(), starts.size());
    for (std::size_t i = 0; i < starts.size(); ++i)
        EXPECT_EQ(w.starts[i], starts[i]) << i;
    ASSERT_EQ(w.people.size(), 2u);
    EXPECT_EQ(w.people[0].waypoints.size(), 5u);
    EXPECT_EQ(w.people[1].waypoints.size(), 6u);
    // The meshes are measured into boxes: the tree ships no mesh.
    EXPECT_TRUE(w.meshes.empty());
}

TEST(CafeWorld, SaysGroundOnceAndHasOneGroundSlab) {
    // The YAML parser lets a repeated key pass, so the file itself is read.
    std::ifstream in(resolveWorldPath("cafe"));
    int keys = 0;
    for (std::string line; std::getline(in, line);)
        keys += line.rfind("ground:", 0) == 0;
    EXPECT_EQ(keys, 1);
    int grounds = 0;
    for (const auto& b : cafe().boxes)
        grounds += b.name == "ground";
    EXPECT_EQ(grounds, 1);
}

TEST(CafeWorld, TheKitchenDoorwayIsOpen) {
    const RayCaster caster(cafe());
    // From the dining room at door height through x = 1.5: the ray crosses y = 7.43 and runs
    // on to the kitchen's far side (north wall at y = 11.945), not to the wall at 7.383.
    for (const double z : {0.5, 1.2, 2.0, 2.5}) {
        const float d = northRange(caster, 1.5, 6.0, z);
        EXPECT_GT(6.0 + d, 10.0) << "z " << z;
    }
    // Above the doorway's lintel (2.619) the wall is closed.
    EXPECT_NEAR(6.0 + northRange(caster, 1.5, 6.0, 2.7), 7.383, 0.01);
    // The jambs: x = 0.8 (below the hatch) and x = 2.09 (wall_4's end) are wall at 1 m.
    EXPECT_NEAR(6.0 + northRange(caster, 0.8, 6.0, 1.0), 7.383, 0.01);
    EXPECT_NEAR(6.0 + northRange(caster, 2.09, 6.0, 1.0), 7.383, 0.01);
}

TEST(CafeWorld, TheHatchAndThePassThroughAreOpenAboveTheCounterOnly) {
    const RayCaster caster(cafe());
    for (const double x : {0.0, 0.3, -3.5}) {
        // Above the counter (1.335) the ray goes through to the kitchen (past its counters
        // at the wall, y 7.523-7.7; behind the pass-through the closet wall is at 8.983) ...
        EXPECT_GT(6.0 + northRange(caster, x, 6.0, 2.0), 8.5) << "x " << x;
        // ... below it the wall (y = 7.383) stops it.
        EXPECT_NEAR(6.0 + northRange(caster, x, 6.0, 0.8), 7.383, 0.01) << "x " << x;
    }
    // Between the hatch and the pass-through the wall is closed at every height.
    for (const double z : {0.8, 2.0})
        EXPECT_NEAR(6.0 + northRange(caster, -2.5, 6.0, z), 7.383, 0.01) << "z " << z;
}

TEST(CafeWorld, TheDroneCanFlyFromStartFourIntoTheDiningRoom) {
    const WorldSpec w = cafe();
    const StaticCollisionChecker checker(w);
    Eigen::Vector3d hit;
    EXPECT_TRUE(sweepIsClear(checker, kitchenToDiningPath(w), &hit)) << hit.transpose();
    // At 1.6 m (above the kitchen counters, 1.335) the camera sees from start 4 into the
    // dining room: the line crosses the wall at x = 0.6, through the hatch.
    const RayCaster caster(w);
    const Eigen::Vector3f from(-0.7f, 9.6f, 1.6f), to(1.5f, 6.0f, 1.6f);
    const float len = (to - from).norm();
    EXPECT_GE(caster.castRay(from, (to - from) / len, len), len);
}

TEST(CafeWorld, ThePathThroughTheDoorIsAlsoClearInTheVisualMesh) {
    const std::filesystem::path dae =
        std::filesystem::path(DAEP_SHARED_DIR) / "datasets/gazebo-models/cafe/meshes/cafe.dae";
    if (!std::filesystem::exists(dae))
        GTEST_SKIP() << "reference mesh not found: " << dae;
    test::TempDir dir;
    const WorldSpec mesh =
        loadWorldFile(dir.write("cafe_mesh.yaml",
                                "exploration_box: {min: [-5, -11, 0], max: [4, 12, 2.5]}\n"
                                "starts: [[-0.7, 9.6, 0.2]]\nground: true\n"
                                "meshes: [{file: " +
                                    dae.string() + "}]\n"));
    const StaticCollisionChecker checker(mesh);
    Eigen::Vector3d hit;
    EXPECT_TRUE(sweepIsClear(checker, kitchenToDiningPath(cafe()), &hit)) << hit.transpose();
    // The same rays as above, in the mesh: through the doorway and the hatch, not below it.
    const RayCaster caster(mesh);
    EXPECT_GT(6.0 + northRange(caster, 1.5, 6.0, 1.2), 10.0);
    EXPECT_GT(6.0 + northRange(caster, 0.3, 6.0, 2.0), 9.0);
    EXPECT_NEAR(6.0 + northRange(caster, 0.3, 6.0, 0.8), 7.383, 0.01);
}

}  // namespace
}  // namespace daep::world
