#include <gtest/gtest.h>

#include "TestFiles.h"
#include "daep/common/Error.h"
#include "daep/world/ReachableVolume.h"

namespace daep::world {
namespace {

constexpr double kCell = 0.2 * 0.2 * 0.2;

BoxShape solid(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
    BoxShape b;
    b.pose.translation() = 0.5 * (min + max);
    b.size = max - min;
    return b;
}

/**
 * An 8 x 4 x 2.4 m box (40 x 20 x 12 cells of 0.2 m) closed by floor, ceiling and walls just
 * outside it, split at x = 4 by a 0.2 m wall (one cell layer). `opening` (y from, y to, top)
 * cuts a gap into the wall from the floor up; a zero width leaves it closed.
 */
WorldSpec twoRooms(double openFrom = 0.0, double openTo = 0.0, double openTop = 0.0) {
    WorldSpec w;
    w.name = "two_rooms";
    w.explorationBox.min = {0, 0, 0};
    w.explorationBox.max = {8, 4, 2.4};
    w.starts = {{1, 2, 0}, {7, 2, 0}};
    const double t = 0.2;
    w.boxes.push_back(solid({-t, -t, -t}, {8 + t, 4 + t, 0}));         // floor
    w.boxes.push_back(solid({-t, -t, 2.4}, {8 + t, 4 + t, 2.4 + t}));  // ceiling
    w.boxes.push_back(solid({-t, -t, -t}, {0, 4 + t, 2.4 + t}));
    w.boxes.push_back(solid({8, -t, -t}, {8 + t, 4 + t, 2.4 + t}));
    w.boxes.push_back(solid({-t, -t, -t}, {8 + t, 0, 2.4 + t}));
    w.boxes.push_back(solid({-t, 4, -t}, {8 + t, 4 + t, 2.4 + t}));
    if (openTo <= openFrom) {
        w.boxes.push_back(solid({4, 0, 0}, {4.2, 4, 2.4}));
    } else {
        w.boxes.push_back(solid({4, 0, 0}, {4.2, openFrom, 2.4}));
        w.boxes.push_back(solid({4, openTo, 0}, {4.2, 4, 2.4}));
        w.boxes.push_back(solid({4, openFrom, openTop}, {4.2, openTo, 2.4}));
    }
    return w;
}

double percentOf(std::size_t cells) {
    return 100.0 * double(cells) * kCell / (8.0 * 4.0 * 2.4);
}

// The drone's centre keeps 0.3 m from solid cells and from the box: in a room of x 0..4 the
// centres 0.3 .. 3.7 (18 cells), y the same (18), z 0.3 .. 2.1 (10).
constexpr std::size_t kRoomDroneCells = 18 * 18 * 10;

TEST(ReachableVolume, ClosedWallKeepsTheFarRoomOut) {
    const WorldSpec w = twoRooms();
    const ReachableVolume r = computeReachableVolume(w, w.starts[0]);
    // The near room's 20 x 20 x 12 free cells and the wall's 20 x 12 cells it faces.
    EXPECT_EQ(r.observableCells, 20u * 20 * 12 + 20 * 12);
    EXPECT_NEAR(r.reachablePercent, 52.5, 1e-9);
    EXPECT_NEAR(r.observableVolume, 5040 * kCell, 1e-9);
    EXPECT_EQ(r.droneCells, kRoomDroneCells);
    EXPECT_DOUBLE_EQ(r.dronePercent, percentOf(kRoomDroneCells));
    EXPECT_TRUE(r.seedClear);
    EXPECT_FALSE(r.seedMoved);
    EXPECT_TRUE(r.seed.isApprox(Eigen::Vector3d(1.1, 2.1, 1.1)));

    // From the far room: its 19 free layers of x and the same wall.
    const ReachableVolume far = computeReachableVolume(w, w.starts[1]);
    EXPECT_EQ(far.observableCells, 19u * 20 * 12 + 20 * 12);
    EXPECT_EQ(far.droneCells, 17u * 18 * 10);  // x centres 4.5 .. 7.7
}

TEST(ReachableVolume, DoorWiderThanTheDroneOpensBothRooms) {
    // A door 0.8 m wide (y 1.6 .. 2.4), 2 m high.
    const WorldSpec w = twoRooms(1.6, 2.4, 2.0);
    const ReachableVolume r = computeReachableVolume(w, w.starts[0]);
    EXPECT_EQ(r.observableCells, 40u * 20 * 12);
    EXPECT_DOUBLE_EQ(r.reachablePercent, 100.0);
    // Both rooms, and through the door at y 1.9 and 2.1, z 0.3 .. 1.7 the cells at x 3.9, 4.1
    // and 4.3 (3 x 2 x 8), which the rooms' clearance from the wall leaves out.
    EXPECT_EQ(r.droneCells, kRoomDroneCells + 17 * 18 * 10 + 3 * 2 * 8);
}

TEST(ReachableVolume, SlotNarrowerThanTheDroneIsSeenThroughNotFlownThrough) {
    // A slot 0.4 m wide (y 1.8 .. 2.2): the drone (0.6 m) stays in the near room.
    const WorldSpec w = twoRooms(1.8, 2.2, 2.0);
    const ReachableVolume r = computeReachableVolume(w, w.starts[0]);
    EXPECT_DOUBLE_EQ(r.reachablePercent, 100.0);
    EXPECT_EQ(r.droneCells, kRoomDroneCells);
    EXPECT_DOUBLE_EQ(r.dronePercent, percentOf(kRoomDroneCells));
}

TEST(ReachableVolume, SolidDeepInsideGeometryIsNotObservable) {
    // A 1 m cube (5 x 5 x 5 cells) on the floor of the near room: the 3 x 3 cells inside it
    // are unseen in its 4 lower layers (the floor closes the lowest).
    WorldSpec w = twoRooms();
    w.boxes.push_back(solid({2, 1, 0}, {3, 2, 1}));
    const ReachableVolume r = computeReachableVolume(w, w.starts[0]);
    EXPECT_EQ(r.observableCells, 20u * 20 * 12 + 20 * 12 - 3 * 3 * 4);
}

TEST(ReachableVolume, MeshSurfaceBoundsTheSameVolumeAsTheSolidBox) {
    // A cube off the cell bounds as 12 triangles: the cells only inside it are free but
    // enclosed, so unseen, as the solid box's core.
    WorldSpec w = twoRooms();
    TriangleMesh cube;
    for (int i = 0; i < 8; ++i)
        cube.vertices.emplace_back(2.1f + float(i & 1), 1.1f + float((i >> 1) & 1),
                                   1.1f * float((i >> 2) & 1));
    cube.triangles = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1},
                      {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
    w.meshes.push_back(cube);
    WorldSpec asBox = twoRooms();
    asBox.boxes.push_back(solid({2.1, 1.1, 0}, {3.1, 2.1, 1.1}));
    const ReachableVolume mesh = computeReachableVolume(w, w.starts[0]);
    const ReachableVolume box = computeReachableVolume(asBox, asBox.starts[0]);
    EXPECT_EQ(box.observableCells, 20u * 20 * 12 + 20 * 12 - 4 * 4 * 5);
    EXPECT_EQ(mesh.observableCells, box.observableCells);
    EXPECT_EQ(mesh.droneCells, box.droneCells);
}

TEST(ReachableVolume, YawedAndCylinderShapesTakeTheExactTest) {
    // A pillar as a cylinder and as a box turned 45 deg: fewer drone cells, every surface seen.
    WorldSpec w = twoRooms();
    CylinderShape c;
    c.pose.translation() = Eigen::Vector3d(2, 2, 1.2);
    c.radius = 0.25;
    c.length = 2.4;
    w.cylinders.push_back(c);
    BoxShape b = solid({0.8, 0.8, 0}, {1.2, 1.2, 2.4});
    b.pose.linear() = Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    w.boxes.push_back(b);
    const ReachableVolume r = computeReachableVolume(w, w.starts[0]);
    EXPECT_LT(r.droneCells, kRoomDroneCells);
    // Each covers 4 x 4 cells less the free corners, whose corner the 2 x 2 cells inside
    // touch: those are not full, the camera may see into them, and they count.
    EXPECT_EQ(r.observableCells, 20u * 20 * 12 + 20 * 12);
}

TEST(ReachableVolume, GroundSlabFromTheWorldFileBoundsTheBoxBelowZero) {
    // An open field, box z -0.6 .. 1.4: of the three layers under the ground only the top one
    // (the surface) counts, so 8 of 10 layers.
    const test::TempDir dir;
    const std::string path =
        dir.write("field.yaml",
                  "name: field\nexploration_box: {min: [0, 0, -0.6], max: [4, 4, 1.4]}\n"
                  "ground: true\nstarts: [[2, 2, 0.1]]\nboxes:\n"
                  "  - {name: post, center: [3.5, 3.5, 1.5], size: [0.2, 0.2, 3]}\n");
    const WorldSpec w = loadWorldFile(path);
    ReachParams p;
    p.climb = 0.5;
    const ReachableVolume r = computeReachableVolume(w, w.starts[0], p);
    // The post: one column of cells, all seen, and the ground cell under it, which touches
    // the free cells by its edges.
    EXPECT_EQ(r.observableCells, 20u * 20 * 8);
    EXPECT_NEAR(r.reachablePercent, 80.0, 1e-9);
}

TEST(ReachableVolume, SpawnInsideGeometryStartsFromTheNearestFreeCell) {
    WorldSpec w = twoRooms();
    w.boxes.push_back(solid({0.6, 1.6, 0.6}, {1.6, 2.6, 1.6}));  // around start + climb
    const ReachableVolume r = computeReachableVolume(w, w.starts[0]);
    EXPECT_TRUE(r.seedMoved);
    EXPECT_GT(r.reachablePercent, 50.0);
}

TEST(ReachableVolume, SpawnCellWithoutClearanceStillBeginsTheFill) {
    // Climbing 2.2 m puts the drone 0.1 m under the ceiling: it is there, so it counts.
    const WorldSpec w = twoRooms();
    ReachParams p;
    p.climb = 2.2;
    const ReachableVolume r = computeReachableVolume(w, w.starts[0], p);
    EXPECT_FALSE(r.seedClear);
    EXPECT_FALSE(r.seedMoved);
    EXPECT_NEAR(r.reachablePercent, 52.5, 1e-9);
    EXPECT_EQ(r.droneCells, kRoomDroneCells + 1);
}

TEST(ReachableVolume, RejectsBadParameters) {
    const WorldSpec w = twoRooms();
    ReachParams p;
    p.resolution = 0;
    EXPECT_THROW(computeReachableVolume(w, w.starts[0], p), InputError);
    p = {};
    p.robotRadius = -1;
    EXPECT_THROW(computeReachableVolume(w, w.starts[0], p), InputError);
}

}  // namespace
}  // namespace daep::world
