#include <gtest/gtest.h>

#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <Eigen/Geometry>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "daep/common/Error.h"
#include "daep/mission/PeopleInput.h"
#include "daep/sim/DepthCamera.h"
#include "daep/world/RayCaster.h"

namespace daep::mission {
namespace {

world::BoxShape wall(const Eigen::Vector3d& center, const Eigen::Vector3d& size) {
    world::BoxShape b;
    b.name = "wall";
    b.pose = Eigen::Translation3d(center) * Eigen::AngleAxisd(0.0, Eigen::Vector3d::UnitZ());
    b.size = size;
    return b;
}

world::PersonState standing(double x, double y) {
    world::PersonState p;
    p.position = {x, y};
    return p;
}

/** A camera at (0, 0, 1) facing +x; a wall across y in [2, 6] at x = 3. */
struct SensedPeople : ::testing::Test {
    SensedPeople() : caster(worldWithWall()) {}
    static world::WorldSpec worldWithWall() {
        world::WorldSpec w;
        w.boxes.push_back(wall({3.0, 4.0, 1.25}, {0.2, 4.0, 2.5}));
        return w;
    }
    bool sees(const std::vector<world::PersonState>& people, int index) {
        caster.setPeople(people, body);
        return PeopleInput::visible(caster, camera, cameraParams, 5.0, people[index], body, index);
    }
    world::RayCaster caster;
    FlatPose camera{{0, 0, 1}, 0.0};
    sim::CameraParams cameraParams;
    Eigen::Vector3d body{1.0, 1.0, 1.8};
};

TEST_F(SensedPeople, SeesAPersonInFrontWithinRange) {
    EXPECT_TRUE(sees({standing(3.0, 0.0)}, 0));
    EXPECT_TRUE(sees({standing(3.0, -2.0)}, 0));  // 34 deg off axis, inside the 103 deg FoV
}

TEST_F(SensedPeople, DoesNotSeeBehindTheCameraOrBeyondRange) {
    EXPECT_FALSE(sees({standing(-3.0, 0.0)}, 0));
    EXPECT_FALSE(sees({standing(0.3, 4.0)}, 0));  // 85 deg to the left
    EXPECT_FALSE(sees({standing(7.0, 0.0)}, 0));
}

TEST_F(SensedPeople, WallsAndOtherPeopleHideAPerson) {
    EXPECT_FALSE(sees({standing(4.5, 4.0)}, 0));  // behind the wall
    EXPECT_TRUE(sees({standing(2.0, 3.0)}, 0));   // in front of it
    // One person right behind another, seen along the same line: only the front one.
    const std::vector<world::PersonState> queue{standing(1.8, 0.0), standing(3.6, 0.0)};
    EXPECT_TRUE(sees(queue, 0));
    EXPECT_FALSE(sees(queue, 1));
}

/** The [name] section of the defaults file, as it is. */
std::string defaultsSection(const std::string& name) {
    std::ifstream in(std::string(DAEP_SOURCE_DIR) + "/share/daep/config/defaults.ini");
    std::stringstream all;
    all << in.rdbuf();
    const std::string text = all.str();
    const std::size_t from = text.find("\n[" + name + "]") + 1;
    return text.substr(from, text.find("\n[", from + 1) - from + 1);
}

/** The defaults' tracker, but a track unseen for 2 s is dropped. */
std::string trackerSection() {
    std::string tracker = defaultsSection("tracker");
    const std::string timeout = "\ndrop_after_s = 20.0\n";
    const std::size_t at = tracker.find(timeout);
    if (at == std::string::npos)
        throw std::runtime_error("defaults.ini: [tracker] drop_after_s is no longer 20.0");
    return tracker.replace(at, timeout.size(), "\ndrop_after_s = 2\n");
}

std::string trackingSection(const std::string& source) {
    return "[tracking]\npeople_source = " + source +
           "\nsensed_range = 5\nsensed_noise_sigma = 0.05\nexclude_from_map = true\n" +
           trackerSection() + defaultsSection("detector");
}

TEST_F(SensedPeople, SensedTracksOnlyWhoIsSeenAndForgetsThemAfterTheTimeout) {
    const mrpt::config::CConfigFileMemory cfg(trackingSection("sensed"));
    PeopleInput input(PeopleInputParams::fromConfig(cfg), 1);
    // Person 0 walks in front of the camera, person 1 stands behind the wall.
    for (int k = 0; k <= 10; ++k) {
        const std::vector<world::PersonState> people{standing(3.0, -1.0 + 0.07 * k),
                                                     standing(4.5, 4.0)};
        caster.setPeople(people, body);
        input.observe(0.2 * k, people, caster, camera, cameraParams, body);
    }
    ASSERT_EQ(input.forecasts().size(), 1u);
    EXPECT_EQ(input.forecasts()[0].id, 0);
    EXPECT_NEAR(input.forecasts()[0].velocity().y(), 0.35, 0.15);
    // Person 0 walks out of view (behind the camera): predicted on, then dropped after 2 s.
    const std::vector<world::PersonState> gone{standing(-3.0, 0.0), standing(4.5, 4.0)};
    caster.setPeople(gone, body);
    input.observe(3.0, gone, caster, camera, cameraParams, body);
    EXPECT_EQ(input.forecasts().size(), 1u);
    input.observe(4.1, gone, caster, camera, cameraParams, body);
    EXPECT_EQ(input.forecasts().size(), 0u);
}

TEST_F(SensedPeople, ATrackWhosePlaceTheDepthFrameSeesEmptyIsDroppedAfterThreeFrames) {
    const mrpt::config::CConfigFileMemory cfg(trackingSection("sensed"));
    PeopleInput withView(PeopleInputParams::fromConfig(cfg), 1);
    PeopleInput withoutView(PeopleInputParams::fromConfig(cfg), 1);
    const sim::DepthCamera depthCamera(cameraParams);
    std::mt19937_64 rng(1);
    mrpt::obs::CObservation3DRangeScan frame;
    auto observe = [&](double t, const std::vector<world::PersonState>& people) {
        caster.setPeople(people, body);
        depthCamera.render(caster, camera, t, rng, frame);
        withView.observe(t, people, caster, camera, cameraParams, body, {&frame, camera});
        withoutView.observe(t, people, caster, camera, cameraParams, body);
    };
    // Person 0 stands in view, 3 m ahead, then is gone (behind the camera) all of a sudden.
    for (int k = 0; k <= 5; ++k)
        observe(0.2 * k, {standing(3.0, 0.0)});
    ASSERT_EQ(withView.forecasts().size(), 1u);
    const std::vector<world::PersonState> gone{standing(-3.0, 0.0)};
    observe(1.2, gone);
    observe(1.4, gone);
    EXPECT_EQ(withView.forecasts().size(), 1u);  // two frames saw the place empty
    observe(1.6, gone);
    EXPECT_EQ(withView.forecasts().size(), 0u);     // the third drops the track
    EXPECT_EQ(withoutView.forecasts().size(), 1u);  // without depth it waits for drop_after_s
}

TEST_F(SensedPeople, AWallInFrontOfThePredictionIsNoEvidenceTheyLeft) {
    // Behind the wall at x = 3 the camera cannot tell whether anyone still stands there.
    const mrpt::config::CConfigFileMemory cfg(trackingSection("ground_truth"));
    PeopleInput input(PeopleInputParams::fromConfig(cfg), 1);
    const sim::DepthCamera depthCamera(cameraParams);
    std::mt19937_64 rng(1);
    mrpt::obs::CObservation3DRangeScan frame;
    const std::vector<world::PersonState> behindWall{standing(4.5, 3.0)};
    caster.setPeople(behindWall, body);
    input.observe(0.0, behindWall, caster, camera, cameraParams, body);
    const std::vector<world::PersonState> nobody;
    caster.setPeople(nobody, body);
    for (int k = 1; k <= 5; ++k) {
        depthCamera.render(caster, camera, 0.2 * k, rng, frame);
        // Ground truth measures nobody now; the track lives on behind the wall.
        input.observe(0.2 * k, nobody, caster, camera, cameraParams, body, {&frame, camera});
    }
    EXPECT_EQ(input.forecasts().size(), 1u);
}

TEST_F(SensedPeople, GroundTruthTracksEveryoneWherever) {
    const mrpt::config::CConfigFileMemory cfg(trackingSection("ground_truth"));
    PeopleInput input(PeopleInputParams::fromConfig(cfg), 1);
    const std::vector<world::PersonState> people{standing(-3.0, 0.0), standing(4.5, 4.0)};
    caster.setPeople(people, body);
    input.observe(0.0, people, caster, camera, cameraParams, body);
    EXPECT_EQ(input.forecasts().size(), 2u);
    EXPECT_TRUE(input.forecasts()[1].state.head<2>().isApprox(Eigen::Vector2d(4.5, 4.0)));
}

TEST(PeopleInputParams, TheCameraFindsPeopleAsFarAsItsSourceReaches) {
    const auto range = [](const std::string& source) {
        const mrpt::config::CConfigFileMemory cfg(trackingSection(source));
        PeopleInputParams params = PeopleInputParams::fromConfig(cfg);
        params.sensedRange = 7.0;
        params.detector.maxRange = 4.0;
        return PeopleInput(params, 1).seeingRange();
    };
    EXPECT_EQ(range("sensed"), 7.0);
    EXPECT_EQ(range("detected"), 4.0);
    EXPECT_EQ(range("ground_truth"), std::numeric_limits<double>::infinity());
}

TEST(PeopleInputParams, RejectsAnUnknownSourceNamingTheKey) {
    const mrpt::config::CConfigFileMemory cfg(trackingSection("telepathy"));
    try {
        PeopleInputParams::fromConfig(cfg);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("[tracking] people_source"), std::string::npos);
    }
}

}  // namespace
}  // namespace daep::mission
