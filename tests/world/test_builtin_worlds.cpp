#include <gtest/gtest.h>

#include "daep/world/RayCaster.h"
#include "daep/world/WorldSpec.h"

namespace daep::world {
namespace {

struct Expected {
    const char* name;
    double volume;  ///< paper Table III
    std::size_t people;
};

class BuiltinWorld : public ::testing::TestWithParam<Expected> {};

TEST_P(BuiltinWorld, MatchesThePaper) {
    const Expected& e = GetParam();
    const WorldSpec w = loadWorldFile(resolveWorldPath(e.name));
    EXPECT_EQ(w.name, e.name);
    EXPECT_DOUBLE_EQ(w.explorationVolume(), e.volume);
    EXPECT_EQ(w.people.size(), e.people);
    EXPECT_EQ(w.starts.size(), 5u);
    for (const auto& s : w.starts)
        EXPECT_TRUE(w.explorationBox.contains(s)) << s.transpose();
    for (const auto& p : w.people)
        EXPECT_GE(p.waypoints.size(), 2u) << p.name;
}

TEST_P(BuiltinWorld, DroneFitsAtEveryStartAndAfterItsClimb) {
    const WorldSpec w = loadWorldFile(resolveWorldPath(GetParam().name));
    const StaticCollisionChecker checker(w);
    const Eigen::Vector3d drone(0.4, 0.4, 0.1);
    for (const auto& s : w.starts) {
        // Resting on the start point, halfway up and after the 1 m climb.
        for (const double up : {0.5 * drone.z(), 0.5, 1.0}) {
            const Eigen::Vector3d c = s + Eigen::Vector3d(0, 0, up);
            for (const double yaw : {0.0, 0.4, M_PI / 4})
                EXPECT_FALSE(checker.overlaps(c, drone, yaw))
                    << GetParam().name << " start " << s.transpose() << " +" << up;
        }
    }
}

TEST_P(BuiltinWorld, HasAFloorUnderEveryStart) {
    const WorldSpec w = loadWorldFile(resolveWorldPath(GetParam().name));
    const RayCaster caster(w);
    for (const auto& s : w.starts) {
        const Eigen::Vector3f o = (s + Eigen::Vector3d(0, 0, 1.0)).cast<float>();
        // The floor is at or above z = 0 and not above the start point.
        const float d = caster.castRay(o, Eigen::Vector3f(0, 0, -1), 100.0f);
        EXPECT_LE(d, s.z() + 1.0 + 1e-4) << s.transpose();
        EXPECT_GE(d, 1.0 - 1e-4) << s.transpose();
    }
}

INSTANTIATE_TEST_SUITE_P(Paper, BuiltinWorld,
                         ::testing::Values(Expected{"exhibition", 450, 22},
                                           Expected{"crosswalks", 450, 4},
                                           Expected{"patrol", 800, 8}, Expected{"cafe", 510, 2}),
                         [](const auto& p) { return std::string(p.param.name); });

TEST(BuiltinWorlds, CafeBoxIsTheConfiguredOne) {
    const WorldSpec w = loadWorldFile(resolveWorldPath("cafe"));
    EXPECT_TRUE(w.explorationBox.min.isApprox(Eigen::Vector3d(-5, -11, 0)));
    EXPECT_TRUE(w.explorationBox.max.isApprox(Eigen::Vector3d(4, 12, 2.5)));
    EXPECT_DOUBLE_EQ(w.explorationBox.volume(), 517.5);
}

TEST(BuiltinWorlds, HallsAreWalledAllAround) {
    for (const char* name : {"exhibition", "crosswalks", "patrol"}) {
        const WorldSpec w = loadWorldFile(resolveWorldPath(name));
        const RayCaster caster(w);
        const double halfWidth = w.explorationBox.max.x();
        for (const auto& s : w.starts) {
            const Eigen::Vector3f o = (s + Eigen::Vector3d(0, 0, 1.0)).cast<float>();
            for (int i = 0; i < 16; ++i) {
                const double a = 2 * M_PI * i / 16;
                const Eigen::Vector3f dir(std::cos(a), std::sin(a), 0.0f);
                // The walls' inner faces are 7.5 cm inside the box's sides.
                EXPECT_LT(caster.castRay(o, dir, 100.0f), 2 * std::sqrt(2.0) * halfWidth)
                    << name << " from " << s.transpose();
            }
        }
    }
}

}  // namespace
}  // namespace daep::world
