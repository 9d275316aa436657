// PeopleDetector on frames rendered by the simulator (people walking in a mapped room, a static
// person-sized box) and on MRPT's real Kinect frame.
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <random>

#include "daep/mapping/ExplorationMap.h"
#include "daep/perception/PeopleDetector.h"
#include "daep/perception/PeopleTracker.h"
#include "daep/sim/DepthCamera.h"
#include "daep/world/People.h"
#include "daep/world/RayCaster.h"

using namespace daep;
using perception::PeopleDetector;
using perception::PersonMeasurement;

namespace {

world::BoxShape box(const std::string& name, const Eigen::Vector3d& centre,
                    const Eigen::Vector3d& size) {
    world::BoxShape b;
    b.name = name;
    b.pose = Eigen::Isometry3d(Eigen::Translation3d(centre));
    b.size = size;
    return b;
}

/** A 12 x 12 m walled room with a floor and a static box the size of a person. */
world::WorldSpec room() {
    world::WorldSpec w;
    w.name = "detector_room";
    w.explorationBox.min = Eigen::Vector3d(-6, -6, 0);
    w.explorationBox.max = Eigen::Vector3d(6, 6, 2.5);
    w.boxes = {box("floor", {0, 0, -0.05}, {12.4, 12.4, 0.1}),
               box("north", {0, 6.1, 1.25}, {12.4, 0.2, 2.5}),
               box("south", {0, -6.1, 1.25}, {12.4, 0.2, 2.5}),
               box("east", {6.1, 0, 1.25}, {0.2, 12.4, 2.5}),
               box("west", {-6.1, 0, 1.25}, {0.2, 12.4, 2.5}),
               box("statue", {2.5, -2.0, 0.9}, {1.0, 1.0, 1.8})};
    return w;
}

const Eigen::Vector3d kBody(1.0, 1.0, 1.8);

struct Scene {
    world::WorldSpec spec = room();
    world::RayCaster caster{spec};
    sim::DepthCamera camera{[] {
        sim::CameraParams p;
        p.width = 320;
        p.height = 240;
        return p;
    }()};
    mapping::ExplorationMap map{mapping::MapParams{}, spec.explorationBox};
    std::mt19937_64 rng{3};
    mrpt::obs::CObservation3DRangeScan obs;

    void render(const FlatPose& drone, double t, const std::vector<world::PersonState>& people) {
        caster.setPeople(people, kBody);
        camera.render(caster, drone, t, rng, obs);
    }

    /** Share of person i's pixels (were it alone) that show it among all the people. */
    double visibleFraction(const FlatPose& drone, const std::vector<world::PersonState>& people,
                           std::size_t i) {
        std::vector<float> all, alone, none;
        caster.setPeople(people, kBody);
        camera.renderDepth(caster, drone, nullptr, all);
        caster.setPeople({people[i]}, kBody);
        camera.renderDepth(caster, drone, nullptr, alone);
        caster.setPeople({}, kBody);
        camera.renderDepth(caster, drone, nullptr, none);
        std::size_t body = 0, shown = 0;
        for (std::size_t k = 0; k < all.size(); ++k) {
            if (std::abs(alone[k] - none[k]) < 1e-4f)
                continue;
            ++body;
            shown += std::abs(all[k] - alone[k]) < 1e-4f;
        }
        return body ? double(shown) / double(body) : 0.0;
    }

    /** The drone turns a full circle in the empty room: the map knows the room. */
    void mapEmptyRoom(const Eigen::Vector3d& at) {
        for (int k = 0; k < 36; ++k) {
            FlatPose pose{at, k * M_PI / 18};
            render(pose, 0.1 * k, {});
            map.insertObservation(obs, pose);
        }
    }
};

world::PersonState standingAt(double x, double y) {
    world::PersonState s;
    s.position = {x, y};
    return s;
}

/** True when the person's centre lies within range and well inside the horizontal FoV. */
bool inView(const FlatPose& drone, const sim::CameraParams& cam, const Eigen::Vector2d& p,
            double range) {
    const Eigen::Vector2d rel = p - drone.position.head<2>();
    const double bearing = wrapAngle(std::atan2(rel.y(), rel.x()) - drone.yaw);
    return rel.norm() <= range && std::abs(bearing) < 0.5 * cam.hfovRad - 0.15;
}

}  // namespace

TEST(PeopleDetector, FindsAPersonInKnownFreeSpaceAndNotTheStaticBox) {
    Scene s;
    const Eigen::Vector3d at(-3, 0, 1.2);
    s.mapEmptyRoom(at);
    PeopleDetector detector{perception::DetectorParams{}};
    const FlatPose pose{at, -0.3};
    s.render(pose, 10.0, {standingAt(0.5, -0.5)});
    const auto found = detector.detect(s.obs, pose, s.map);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_LT((found[0].position - Eigen::Vector2d(0.5, -0.5)).norm(), 0.2)
        << found[0].position.transpose();
    EXPECT_EQ(found[0].id, -1);
    // The covariance is elongated along the viewing direction (the depth of the body is guessed).
    const Eigen::Vector2d view = (Eigen::Vector2d(0.5, -0.5) - at.head<2>()).normalized();
    const Eigen::Vector2d across(-view.y(), view.x());
    EXPECT_GT(view.dot(found[0].covariance * view), across.dot(found[0].covariance * across));
    EXPECT_FALSE(detector.lastDetections()[0].cutBySide);
    EXPECT_NEAR(across.dot(found[0].covariance * across), 0.1 * 0.1, 1e-3);
}

TEST(PeopleDetector, APersonTheImageSideCutsIsPlacedBeyondThePartSeen) {
    Scene s;
    const Eigen::Vector3d at(-3, 0, 1.2);
    s.mapEmptyRoom(at);
    perception::DetectorParams params;
    PeopleDetector detector{params};
    const Eigen::Vector2d person(0.5, -0.5);
    const Eigen::Vector2d view = (person - at.head<2>()).normalized();
    const double bearing = std::atan2(view.y(), view.x());
    const double halfFov = 0.5 * s.camera.params().hfovRad;
    // The right edge of the image runs through the body, then the left one: a third of it seen.
    for (const double yaw : {bearing + halfFov + 0.05, bearing - halfFov - 0.05}) {
        const FlatPose pose{at, yaw};
        s.render(pose, 10.0, {standingAt(person.x(), person.y())});
        const auto found = detector.detect(s.obs, pose, s.map);
        ASSERT_EQ(found.size(), 1u) << "yaw " << yaw;
        const perception::PersonDetection& d = detector.lastDetections()[0];
        EXPECT_TRUE(d.cutBySide);
        const Eigen::Vector2d viewed = (d.surfaceCentroid.head<2>() - at.head<2>()).normalized();
        const Eigen::Vector2d side(-viewed.y(), viewed.x());
        // The part seen alone would put the person inside it, off by a good part of a body.
        const Eigen::Vector2d seenOnly = d.surfaceCentroid.head<2>() + params.centreOffset * viewed;
        EXPECT_GT((seenOnly - person).norm(), 0.25) << "yaw " << yaw;
        EXPECT_LT((found[0].position - person).norm(), 0.15) << "yaw " << yaw;
        EXPECT_NEAR(side.dot(found[0].covariance * side),
                    params.sideSigmaAcross * params.sideSigmaAcross, 1e-3);
        EXPECT_NEAR(viewed.dot(found[0].covariance * viewed), params.sigmaAlong * params.sigmaAlong,
                    1e-3);
    }
    // Seen whole again, the person is placed as before: at the part seen, tightly across.
    const FlatPose ahead{at, bearing};
    s.render(ahead, 11.0, {standingAt(person.x(), person.y())});
    const auto found = detector.detect(s.obs, ahead, s.map);
    ASSERT_EQ(found.size(), 1u);
    const perception::PersonDetection& d = detector.lastDetections()[0];
    EXPECT_FALSE(d.cutBySide);
    EXPECT_LT((found[0].position - person).norm(), 0.2);
    const Eigen::Vector2d across(-view.y(), view.x());
    EXPECT_NEAR(across.dot(found[0].covariance * across), params.sigmaAcross * params.sigmaAcross,
                1e-3);
}

TEST(PeopleDetector, FindsNothingInAStaticSceneTheMapExplains) {
    Scene s;
    const Eigen::Vector3d at(-3, 0, 1.2);
    s.mapEmptyRoom(at);
    PeopleDetector detector{perception::DetectorParams{}};
    for (int k = 0; k < 12; ++k) {
        const FlatPose pose{at, k * M_PI / 6};
        s.render(pose, 10.0 + 0.2 * k, {});
        EXPECT_TRUE(detector.detect(s.obs, pose, s.map).empty()) << "yaw step " << k;
        s.map.insertObservation(s.obs, pose);
    }
}

TEST(PeopleDetector, RecallAndPrecisionOnPeopleWalkingThroughAMappedRoom) {
    Scene s;
    const Eigen::Vector3d at(-4, 0, 1.2);
    s.mapEmptyRoom(at);
    std::vector<world::PersonRoute> routes(3);
    routes[0].waypoints = {{0.5, -3.0}, {0.5, 3.0}};     // across the view
    routes[1].waypoints = {{0.5, 2.5}, {-2.5, -0.5}};    // towards the drone
    routes[2].waypoints = {{-2.5, -2.0}, {-0.8, -2.0}};  // away from the drone
    world::PeopleSimulator people(routes, world::PeopleParams{});
    PeopleDetector detector{perception::DetectorParams{}};
    std::size_t eligible = 0, found = 0, detections = 0, falsePositives = 0;
    const FlatPose pose{at, 0.0};
    for (int k = 0; k < 40; ++k) {
        const double t = 10.0 + 0.2 * k;
        s.render(pose, t, people.states());
        const auto measured = detector.detect(s.obs, pose, s.map);
        s.map.insertObservation(s.obs, pose);
        for (const world::PersonState& p : people.states()) {
            if (!inView(pose, s.camera.params(), p.position, 5.0) ||
                s.visibleFraction(pose, people.states(), std::size_t(&p - people.states().data())) <
                    0.5)
                continue;
            ++eligible;
            for (const PersonMeasurement& m : measured)
                if ((m.position - p.position).norm() < 0.5) {
                    ++found;
                    break;
                }
        }
        for (const PersonMeasurement& m : measured) {
            ++detections;
            bool near = false;
            for (const world::PersonState& p : people.states())
                near |= (m.position - p.position).norm() < 0.75;
            falsePositives += !near;
        }
        people.advance(0.2);
    }
    ASSERT_GT(eligible, 60u);
    EXPECT_GE(double(found) / double(eligible), 0.9) << found << " of " << eligible;
    EXPECT_GE(1.0 - double(falsePositives) / double(detections), 0.95)
        << falsePositives << " of " << detections;
}

namespace {

std::shared_ptr<mrpt::obs::CObservation3DRangeScan> kinectFrame() {
    mrpt::io::CFileGZInputStream in("/usr/share/mrpt/datasets/tests_rgbd.rawlog");
    auto arch = mrpt::serialization::archiveFrom(in);
    for (;;) {
        mrpt::serialization::CSerializable::Ptr obj;
        arch >> obj;
        if (auto o = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obj))
            return o;
        if (auto sf = std::dynamic_pointer_cast<mrpt::obs::CSensoryFrame>(obj))
            for (const auto& o : *sf)
                if (auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(o))
                    return scan;
    }
}

}  // namespace

TEST(PeopleDetector, RealKinectFrameOfAStaticSceneHasNoPerson) {
    const auto frame = kinectFrame();
    frame->load();
    ASSERT_TRUE(frame->hasRangeImage);
    ASSERT_EQ(frame->rangeImage.cols(), 640);
    // Lift the sensor to drone height so the scene spans the detector's height band.
    const FlatPose robot{{0, 0, 1.0}, 0.0};
    Aabb box;
    box.min = {-6, -6, -2};
    box.max = {6, 6, 4};
    mapping::ExplorationMap map(mapping::MapParams{}, box);
    PeopleDetector detector{perception::DetectorParams{}};
    // Nothing is known yet: nothing contradicts the map.
    EXPECT_TRUE(detector.detect(*frame, robot, map).empty());
    // Mapped, the same static scene is all explained by the map.
    map.insertObservation(*frame, robot);
    EXPECT_TRUE(detector.detect(*frame, robot, map).empty());
}

TEST(SeenEmptyIn, APlaceTheFrameSeesPastIsEmptyAPersonOrAPlaceOutOfViewIsNot) {
    Scene s;
    const FlatPose pose{{-3, 0, 1.2}, 0.0};
    s.render(pose, 1.0, {standingAt(0.0, 1.0)});
    const auto seenEmpty = perception::seenEmptyIn(&s.obs, pose, kBody);
    EXPECT_TRUE(seenEmpty({0.0, -1.0}));   // in view, the floor and the east wall behind it
    EXPECT_FALSE(seenEmpty({0.0, 1.0}));   // the person stands there
    EXPECT_FALSE(seenEmpty({-5.0, 0.0}));  // behind the camera
    EXPECT_FALSE(seenEmpty({2.5, -2.0}));  // the statue: the frame does not see past it
    EXPECT_FALSE(perception::seenEmptyIn(nullptr, pose, kBody));  // no frame, no test
}
