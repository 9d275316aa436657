// [experiment] source = rawlog: RawlogMission replays recorded depth frames into the map and
// runs the planner on them.
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CActionRobotMovement3D.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CArchive.h>
#include <unistd.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "TestFiles.h"
#include "daep/common/Error.h"
#include "daep/mapping/DepthUnprojection.h"
#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/DetectionEval.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/Mission.h"
#include "daep/mission/RawlogMission.h"
#include "daep/mission/RawlogSource.h"

namespace {

namespace fs = std::filesystem;
using daep::mission::ExperimentConfig;
using daep::mission::RawlogMission;
using mrpt::serialization::CSerializable;

const std::string kTinyRoom = std::string(DAEP_SOURCE_DIR) + "/tests/e2e/data/tiny_room.ini";
const std::string kDataset = std::string(DAEP_SOURCE_DIR) + "/datasets/tiny_room_dynamic.rawlog";
const std::string kKinect = "/usr/share/mrpt/datasets/tests_rgbd.rawlog";

fs::path freshDir(const std::string& name) {
    return daep::test::freshDir("daep_test_rawsrc_", name);
}

std::string readBytes(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

using daep::test::lines;

fs::path out(const std::ostringstream& text) {
    static int n = 0;
    const fs::path p = freshDir("csv" + std::to_string(n++)) / "frames.csv";
    std::ofstream(p) << text.str();
    return p;
}

std::vector<std::string> fields(const std::string& line) {
    std::vector<std::string> out;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');)
        out.push_back(f);
    if (!line.empty() && line.back() == ',')
        out.emplace_back();
    return out;
}

ExperimentConfig replayConfig(const std::string& rawlog, std::vector<std::string> more = {}) {
    std::vector<std::string> o = {"experiment.source=rawlog", "experiment.rawlog_file=" + rawlog,
                                  "output.scene=false"};
    o.insert(o.end(), more.begin(), more.end());
    return ExperimentConfig::fromFile(kTinyRoom, o);
}

std::vector<CSerializable::Ptr> readObjects(const std::string& path, std::size_t max) {
    mrpt::io::CFileGZInputStream in(path);
    auto arch = mrpt::serialization::archiveFrom(in);
    std::vector<CSerializable::Ptr> objects;
    try {
        while (objects.size() < max) {
            CSerializable::Ptr o;
            arch >> o;
            objects.push_back(o);
        }
    } catch (const mrpt::serialization::CExceptionEOF&) {
    }
    return objects;
}

void writeObjects(const std::string& path, const std::vector<CSerializable::Ptr>& objects) {
    mrpt::io::CFileGZOutputStream out(path);
    auto arch = mrpt::serialization::archiveFrom(out);
    for (const auto& o : objects)
        arch << *o;
}

/** The same observations in the actions / sensory-frames format, one frame per timestamp. */
std::vector<CSerializable::Ptr> asSensoryFrames(const std::vector<CSerializable::Ptr>& objects) {
    std::vector<CSerializable::Ptr> out;
    mrpt::obs::CSensoryFrame::Ptr sf;
    mrpt::Clock::time_point stamp{};
    for (const auto& o : objects) {
        auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(o);
        if (!sf || obs->timestamp != stamp) {
            auto acts = mrpt::obs::CActionCollection::Create();
            out.push_back(acts);
            sf = mrpt::obs::CSensoryFrame::Create();
            out.push_back(sf);
            stamp = obs->timestamp;
        }
        sf->insert(obs);
    }
    return out;
}

/** The dataset's first `count` objects in the sensory-frames format, as a file. */
std::string asSensoryFramesFile(const std::string& name, std::size_t count) {
    const std::string path = (freshDir(name) / "sf.rawlog").string();
    writeObjects(path, asSensoryFrames(readObjects(kDataset, count)));
    return path;
}

/** Recording a simulated run and replaying it with the same settings gives the same map. */
TEST(RawlogSource, ReplayOfARecordedRunGivesTheSameMap) {
    const fs::path sim = freshDir("sim"), replay = freshDir("replay");
    const auto simConfig = ExperimentConfig::fromFile(
        kTinyRoom, {"experiment.max_time_s=6", "output.rawlog=true", "output.scene=false"});
    const auto simSummary = daep::mission::Mission(simConfig, sim.string(), nullptr).run();

    RawlogMission mission(
        replayConfig((sim / "run.rawlog").string(), {"rawlog.world=tiny_room.yaml"}), replay,
        nullptr);
    const auto summary = mission.run();

    const std::size_t simFrames = lines(sim / "trajectory.csv").size() - 1;
    std::cout << "round trip: " << simFrames << " frames, sim known " << simSummary.knownVolume
              << " m^3, replay known " << summary.knownVolume << " m^3 ("
              << mission.map().knownCellsInBox() << " cells), map.bt "
              << readBytes(sim / "map.bt").size() << " bytes\n";
    EXPECT_EQ(mission.frames(), simFrames);
    EXPECT_GT(mission.map().knownCellsInBox(), 1000u);
    EXPECT_DOUBLE_EQ(summary.knownVolume, simSummary.knownVolume);
    EXPECT_DOUBLE_EQ(summary.coveragePercent, simSummary.coveragePercent);
    EXPECT_EQ(readBytes(replay / "map.bt"), readBytes(sim / "map.bt"));
    // The replay's trajectory is the recorded one, on the rawlog clock (t = 0 at spawn).
    EXPECT_EQ(readBytes(replay / "trajectory.csv"), readBytes(sim / "trajectory.csv"));
    EXPECT_EQ(summary.endReason.kind, daep::eval::EndReason::Kind::EndOfRawlog);
}

/** The shipped dynamic-world rawlog replays with RH-NBVP and writes one plan per second. */
TEST(RawlogSource, ShippedDatasetReplaysWithAPlanner) {
    const fs::path out = freshDir("dataset");
    RawlogMission mission(
        replayConfig(kDataset, {"rawlog.world=tiny_room.yaml", "experiment.planner=rhnbvp",
                                "rawlog.plan_every_s=1.0"}),
        out, nullptr);
    const auto s = mission.run();
    EXPECT_EQ(mission.frames(), 102u);
    EXPECT_NEAR(s.explorationTime, 20.2, 1e-6);
    EXPECT_EQ(s.iterations, 21);  // t = 0, 1, ..., 20
    EXPECT_GT(s.coveragePercent, 30.0);
    EXPECT_LE(s.coveragePercent, 100.0);
    EXPECT_EQ(s.collisions, 0);
    EXPECT_FALSE(s.finished);
    EXPECT_EQ(s.endReason.text(), "end of rawlog");

    const auto plans = lines(out / "plans.csv");
    ASSERT_EQ(plans.size(), 22u);
    EXPECT_EQ(plans[0], "t,x,y,z,yaw,status,gain,waypoints,wp_x,wp_y,wp_z,wp_yaw,safe,plan_ms");
    int withPath = 0, withGain = 0;
    for (std::size_t i = 1; i < plans.size(); ++i) {
        const auto f = fields(plans[i]);
        ASSERT_EQ(f.size(), 14u) << plans[i];
        EXPECT_NEAR(std::stod(f[0]), double(i - 1), 0.21) << plans[i];
        if (std::stoi(f[7]) > 0) {
            ++withPath;
            EXPECT_TRUE(f[12] == "0" || f[12] == "1") << plans[i];
            withGain += std::stod(f[6]) > 0.0 ? 1 : 0;
        } else {
            EXPECT_EQ(f[12], "") << plans[i];
        }
    }
    EXPECT_GE(withPath, 5);
    EXPECT_GE(withGain, 3);
    for (const char* file : {"summary.json", "timeseries.csv", "trajectory.csv", "map.bt",
                             "timing.json", "collisions.csv"})
        EXPECT_TRUE(fs::exists(out / file)) << file;
    EXPECT_EQ(lines(out / "trajectory.csv").size(), 103u);
    EXPECT_EQ(lines(out / "timeseries.csv").size(), 22u);  // header + t = 0..20
}

TEST(RawlogSource, ReplayTracksThePersonOfTheShippedDataset) {
    const fs::path out = freshDir("people");
    RawlogMission mission(replayConfig(kDataset, {"rawlog.world=tiny_room.yaml"}), out, nullptr);
    mission.run();
    const auto rows = lines(out / "people.csv");
    ASSERT_GE(rows.size(), 6u);
    EXPECT_EQ(rows[0], "t,track,x,y,vx,vy,sigma");
    for (std::size_t i = 1; i < rows.size(); ++i) {
        const auto f = fields(rows[i]);
        ASSERT_EQ(f.size(), 7u) << rows[i];
        EXPECT_GE(std::stoi(f[1]), 0);
        EXPECT_GT(std::stod(f[6]), 0.0);
        EXPECT_LT(std::hypot(std::stod(f[4]), std::stod(f[5])), 1.5) << rows[i];
    }
}

TEST(DetectionEval, ScoresTheShippedDatasetAgainstItsTruePeople) {
    const auto config = ExperimentConfig::fromFile(kTinyRoom);
    std::ostringstream csv;
    const auto s = daep::mission::evaluateDetection(config, kDataset, {}, &csv);
    EXPECT_EQ(s.frames, 102u);
    EXPECT_EQ(lines(out(csv)).size(), 103u);
    EXPECT_GE(s.truePositives, 5u);
    EXPECT_GE(s.found, 3u);
    EXPECT_LE(s.found, s.eligible);
    EXPECT_EQ(s.truePositives + s.falsePositives, s.detections);
    ASSERT_FALSE(s.errors.empty());
    // The walker is detected near where they are: within 0.34 m, a detection the image's left
    // edge cuts and that is placed beyond the part seen (a body is 1 m wide).
    EXPECT_LT(*std::min_element(s.errors.begin(), s.errors.end()), 0.4);
    EXPECT_GE(s.confirmedTrackMatches, 3u);
    // A rawlog without true people cannot be scored.
    EXPECT_THROW(daep::mission::evaluateDetection(config, kKinect, {}), daep::InputError);
}

/** The sensory-frames format (CActionCollection + CSensoryFrame) maps like observations. */
TEST(RawlogSource, SensoryFrameFormatGivesTheSameMapAsObservations) {
    const fs::path dir = freshDir("sf");
    const auto objects = readObjects(kDataset, 45);  // 15 frames: scan, drone, person
    writeObjects((dir / "obs.rawlog").string(), objects);
    writeObjects((dir / "sf.rawlog").string(), asSensoryFrames(objects));
    RawlogMission a(replayConfig((dir / "obs.rawlog").string(), {"rawlog.world=tiny_room.yaml"}),
                    dir / "a", nullptr);
    RawlogMission b(replayConfig((dir / "sf.rawlog").string(), {"rawlog.world=tiny_room.yaml"}),
                    dir / "b", nullptr);
    a.run();
    b.run();
    EXPECT_EQ(a.frames(), 15u);
    EXPECT_EQ(b.frames(), 15u);
    EXPECT_GT(a.map().knownCellsInBox(), 500u);
    EXPECT_EQ(a.map().knownCellsInBox(), b.map().knownCellsInBox());
    EXPECT_EQ(readBytes(dir / "a" / "map.bt"), readBytes(dir / "b" / "map.bt"));
}

/** MRPT's real Kinect frame (no robot poses): its surfaces land in front of the camera. */
TEST(RawlogSource, KinectFrameFromMrptDatasetsIsMapped) {
    if (!fs::exists(kKinect))
        GTEST_SKIP() << kKinect << " missing (Debian package mrpt-common)";
    const fs::path out = freshDir("kinect");
    // Recorded data without true people: the people come from the detector.
    RawlogMission mission(replayConfig(kKinect, {"tracking.people_source=detected"}), out, nullptr);
    const auto s = mission.run();
    EXPECT_EQ(mission.frames(), 1u);
    EXPECT_EQ(s.iterations, 1);
    const auto& map = mission.map();
    EXPECT_GT(map.knownCellsInBox(), 400u);  // a ~2 m deep frustum at 0.2 m cells

    const auto objects = readObjects(kKinect, 1);
    auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(objects.at(0));
    ASSERT_TRUE(scan);
    scan->load();
    const auto points = daep::mapping::unprojectDepthImage(*scan, daep::FlatPose{});
    ASSERT_GT(points.size(), 10000u);
    const auto& sp = scan->sensorPose;
    const Eigen::Vector3f origin(float(sp.x()), float(sp.y()), float(sp.z()));
    const auto& r = sp.getRotationMatrix();
    const Eigen::Vector3f forward(float(r(0, 0)), float(r(1, 0)), float(r(2, 0)));
    std::vector<float> depths;
    std::size_t occupied = 0, inReach = 0;
    for (std::size_t i = 0; i < points.size(); i += 7) {
        const Eigen::Vector3f d = points[i] - origin;
        depths.push_back(d.dot(forward));
        if (d.norm() < 4.5f && map.explorationBox().contains(points[i].cast<double>())) {
            ++inReach;
            occupied += map.isOccupied(points[i].cast<double>()) ? 1 : 0;
        }
    }
    std::sort(depths.begin(), depths.end());
    std::cout << "kinect: " << points.size() << " points, depth " << depths.front() << " .. "
              << depths.back() << " m (median " << depths[depths.size() / 2] << "), "
              << map.knownCellsInBox() << " known cells, " << occupied << "/" << inReach
              << " sampled points on occupied cells\n";
    EXPECT_GT(depths.front(), 0.3f);  // everything in front of the camera
    EXPECT_LT(depths.back(), 12.0f);
    EXPECT_GT(depths[depths.size() / 2], 0.5f);
    EXPECT_LT(depths[depths.size() / 2], 6.0f);
    ASSERT_GT(inReach, 1000u);
    EXPECT_GT(double(occupied), 0.9 * double(inReach));
    // Behind the camera nothing is known.
    const Eigen::Vector3f behind = origin - 1.5f * forward;
    EXPECT_TRUE(map.isUnknown(behind.cast<double>()));
}

template <typename F>
std::string inputErrorOf(F&& f) {
    try {
        f();
    } catch (const daep::InputError& e) {
        return e.what();
    }
    return "(no InputError)";
}

TEST(RawlogSource, BadInputsAreInputErrorsNamingTheFileOrKey) {
    const fs::path dir = freshDir("bad");
    const auto make = [&](const ExperimentConfig& c) { RawlogMission(c, dir / "out", nullptr); };

    EXPECT_NE(inputErrorOf([&] { make(replayConfig("")); }).find("rawlog_file"), std::string::npos);
    const std::string missing = (dir / "missing.rawlog").string();
    EXPECT_NE(inputErrorOf([&] { make(replayConfig(missing)); }).find(missing), std::string::npos);

    const std::string garbage = (dir / "garbage.rawlog").string();
    std::ofstream(garbage) << "this is not a rawlog, just some text that is long enough\n";
    EXPECT_NE(inputErrorOf([&] { make(replayConfig(garbage)); }).find(garbage), std::string::npos);

    const std::string noDepth = (dir / "odometry_only.rawlog").string();
    auto odo = mrpt::obs::CObservationOdometry::Create();
    odo->timestamp = mrpt::Clock::fromDouble(1e9);
    writeObjects(noDepth, {odo, odo});
    const std::string e = inputErrorOf([&] { make(replayConfig(noDepth)); });
    EXPECT_NE(e.find(noDepth), std::string::npos) << e;
    EXPECT_NE(e.find("no depth frames"), std::string::npos) << e;

    // A depth label that no frame has is the same as no depth frames.
    EXPECT_NE(inputErrorOf([&] {
                  make(replayConfig(kDataset, {"rawlog.sensor_label=NOPE"}));
              }).find("no depth frames"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([&] {
                  make(replayConfig(kDataset, {"rawlog.plan_every_s=0"}));
              }).find("plan_every_s"),
              std::string::npos);
    EXPECT_NE(inputErrorOf([&] {
                  RawlogMission::selectedBy(
                      ExperimentConfig::fromFile(kTinyRoom, {"experiment.source=camera"}));
              }).find("source"),
              std::string::npos);
    EXPECT_FALSE(RawlogMission::selectedBy(ExperimentConfig::fromFile(kTinyRoom)));

    // People from ground truth need PERSON_<i> poses; sensed people need the simulator.
    if (fs::exists(kKinect)) {
        const std::string noPeople = inputErrorOf([&] { make(replayConfig(kKinect)); });
        EXPECT_NE(noPeople.find(kKinect), std::string::npos) << noPeople;
        EXPECT_NE(noPeople.find("people_source = ground_truth"), std::string::npos) << noPeople;
    }
    const std::string sensed =
        inputErrorOf([&] { make(replayConfig(kDataset, {"tracking.people_source=sensed"})); });
    EXPECT_NE(sensed.find(kDataset), std::string::npos) << sensed;
    EXPECT_NE(sensed.find("people_source = sensed needs the simulator"), std::string::npos)
        << sensed;
}

/** A rawlog cut short fails while replaying, naming the file; the outputs so far are kept. */
TEST(RawlogSource, TruncatedRawlogIsAnErrorNamingTheFile) {
    const fs::path dir = freshDir("truncated");
    const std::string bytes = readBytes(kDataset);
    const std::string cut = (dir / "cut.rawlog").string();
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    RawlogMission mission(replayConfig(cut, {"rawlog.world=tiny_room.yaml"}), dir / "out", nullptr);
    const std::string e = inputErrorOf([&] { mission.run(); });
    EXPECT_NE(e.find(cut), std::string::npos) << e;
    EXPECT_GT(mission.frames(), 10u);
    EXPECT_TRUE(fs::exists(dir / "out" / "summary.json"));
}

}  // namespace

/**
 * One frame pipeline: a simulated DAEP run with people from its own camera, recorded and then
 * replayed with the same settings, tracks the same people and builds the same map, byte for
 * byte; the replayed plans are made with those tracks.
 */
TEST(RawlogSource, RecordedRunWithDetectedPeopleReplaysToTheSamePeopleAndMap) {
    const fs::path sim = freshDir("detsim"), replay = freshDir("detreplay");
    const std::vector<std::string> same = {"experiment.planner=daep",
                                           "tracking.people_source=detected"};
    std::vector<std::string> simSettings = {"experiment.max_time_s=14", "output.rawlog=true",
                                            "output.scene=false"};
    simSettings.insert(simSettings.end(), same.begin(), same.end());
    daep::mission::Mission(ExperimentConfig::fromFile(kTinyRoom, simSettings), sim.string(),
                           nullptr)
        .run();

    std::vector<std::string> replaySettings = {"rawlog.world=tiny_room.yaml"};
    replaySettings.insert(replaySettings.end(), same.begin(), same.end());
    RawlogMission mission(replayConfig((sim / "run.rawlog").string(), replaySettings), replay,
                          nullptr);
    mission.run();

    const auto tracks = lines(sim / "people.csv");
    std::size_t tracked = 0;
    for (std::size_t i = 1; i < tracks.size(); ++i)
        tracked += fields(tracks[i]).size() == 7u;
    std::cout << "detected run: " << tracked << " track rows in people.csv\n";
    EXPECT_GE(tracked, 5u);  // the walker was found and tracked
    EXPECT_EQ(readBytes(replay / "people.csv"), readBytes(sim / "people.csv"));
    EXPECT_EQ(readBytes(replay / "map.bt"), readBytes(sim / "map.bt"));
    EXPECT_EQ(readBytes(replay / "trajectory.csv"), readBytes(sim / "trajectory.csv"));
}

/** The dataset's first `objects` objects with each drone pose given by `replace`. */
template <typename F>
std::string withDronePoses(const std::string& name, std::size_t objects, F&& replace) {
    auto list = readObjects(kDataset, objects);
    for (auto& o : list) {
        auto pose = std::dynamic_pointer_cast<mrpt::obs::CObservationRobotPose>(o);
        if (pose && pose->sensorLabel == "DRONE_POSE")
            o = replace(*pose);
    }
    const std::string path = (freshDir(name) / "poses.rawlog").string();
    writeObjects(path, list);
    return path;
}

/** Poses the way MRPT logs them: CObservationOdometry (x, y, yaw) serves like a robot pose. */
TEST(RawlogSource, OdometryGivesTheRobotPoseLikeARobotPoseObservation) {
    const auto flat = [](const mrpt::obs::CObservationRobotPose& p) {
        auto q = mrpt::obs::CObservationRobotPose::Create(p);
        q->pose.mean = mrpt::poses::CPose3D(p.pose.mean.x(), p.pose.mean.y(), 0.0,
                                            p.pose.mean.yaw(), 0.0, 0.0);
        return CSerializable::Ptr(q);
    };
    const auto odometry = [](const mrpt::obs::CObservationRobotPose& p) {
        auto o = mrpt::obs::CObservationOdometry::Create();
        o->sensorLabel = p.sensorLabel;
        o->timestamp = p.timestamp;
        o->odometry = mrpt::poses::CPose2D(p.pose.mean.x(), p.pose.mean.y(), p.pose.mean.yaw());
        return CSerializable::Ptr(o);
    };
    const std::string a = withDronePoses("flat", 60, flat);
    const std::string b = withDronePoses("odometry", 60, odometry);
    const fs::path outA = freshDir("flatout"), outB = freshDir("odoout");
    RawlogMission(replayConfig(a, {"rawlog.world=tiny_room.yaml"}), outA, nullptr).run();
    RawlogMission(replayConfig(b, {"rawlog.world=tiny_room.yaml"}), outB, nullptr).run();
    EXPECT_EQ(lines(outB / "trajectory.csv").size(), 21u);  // 20 frames in 60 objects
    EXPECT_EQ(readBytes(outA / "trajectory.csv"), readBytes(outB / "trajectory.csv"));
    EXPECT_EQ(readBytes(outA / "map.bt"), readBytes(outB / "map.bt"));
}

/** Robot poses under another label than pose_label: exit 1 naming both, not a silent identity. */
TEST(RawlogSource, PosesUnderAnotherLabelAreAnErrorNamingTheLabels) {
    const std::string relabelled =
        withDronePoses("gps", 30, [](const mrpt::obs::CObservationRobotPose& p) {
            auto q = mrpt::obs::CObservationRobotPose::Create(p);
            q->sensorLabel = "GPS";
            return CSerializable::Ptr(q);
        });
    const std::string e = inputErrorOf(
        [&] { RawlogMission(replayConfig(relabelled), freshDir("gpsout"), nullptr).run(); });
    EXPECT_NE(e.find(relabelled), std::string::npos) << e;
    EXPECT_NE(e.find("no robot pose labelled 'DRONE_POSE'"), std::string::npos) << e;
    EXPECT_NE(e.find("labelled 'GPS'"), std::string::npos) << e;
}

/** A rawlog without any pose (MRPT's Kinect frame) maps at the identity pose, and says so. */
TEST(RawlogSource, NoPoseAtAllIsMappedAtTheIdentityWithANote) {
    if (!fs::exists(kKinect))
        GTEST_SKIP() << kKinect << " missing (Debian package mrpt-common)";
    std::ostringstream log;
    RawlogMission(replayConfig(kKinect, {"tracking.people_source=detected"}), freshDir("note"),
                  &log)
        .run();
    EXPECT_NE(log.str().find("note: " + kKinect + ": no robot pose"), std::string::npos)
        << log.str();
    EXPECT_NE(log.str().find("identity pose"), std::string::npos) << log.str();
}

/** [rawlog] realtime = true plays at the rawlog's pace: 1.8 s of frames take at least 1.8 s. */
TEST(RawlogSource, RealtimePlaybackKeepsTheRawlogsPace) {
    const std::string first =
        withDronePoses("pace", 30, [](const mrpt::obs::CObservationRobotPose& p) {
            return CSerializable::Ptr(mrpt::obs::CObservationRobotPose::Create(p));
        });  // 10 frames, 0 .. 1.8 s
    const auto t0 = std::chrono::steady_clock::now();
    RawlogMission mission(replayConfig(first, {"rawlog.realtime=true"}), freshDir("paceout"),
                          nullptr);
    mission.run();
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(mission.frames(), 10u);
    EXPECT_GE(wall, 1.8);
}

/** Known cells of the replay of `rawlog` with `settings`, and its summary's known volume. */
double replayedKnownVolume(const std::string& rawlog, const std::vector<std::string>& settings,
                           const std::string& name) {
    std::vector<std::string> all = {"rawlog.world=tiny_room.yaml"};
    all.insert(all.end(), settings.begin(), settings.end());
    return RawlogMission(replayConfig(rawlog, all), freshDir(name), nullptr).run().knownVolume;
}

/** A run's own trajectory_tum.txt gives its replay the poses the rawlog gave. */
TEST(RawlogSource, PosesFromARunsTumTrajectoryMapLikeTheRawlogsPoses) {
    const fs::path sim = freshDir("tumsim");
    daep::mission::Mission(
        ExperimentConfig::fromFile(
            kTinyRoom, {"experiment.max_time_s=6", "output.rawlog=true", "output.scene=false"}),
        sim.string(), nullptr)
        .run();
    const std::string rawlog = (sim / "run.rawlog").string();
    const double fromRawlog = replayedKnownVolume(rawlog, {}, "tumA");
    const double fromFile = replayedKnownVolume(
        rawlog,
        {"rawlog.poses_file=" + (sim / "trajectory_tum.txt").string(),
         "rawlog.poses_file_clock=relative", "rawlog.pose_label=NOT_IN_THE_FILE"},
        "tumB");
    std::cout << "TUM body poses: known " << fromFile << " m^3, rawlog poses " << fromRawlog
              << " m^3\n";
    EXPECT_GT(fromRawlog, 30.0);
    EXPECT_NEAR(fromFile, fromRawlog, 0.01 * fromRawlog);  // the file rounds to 0.1 mm

    // Read on the wrong clock (seconds since 1970), the file covers no frame: that is said.
    const std::string e = inputErrorOf([&] {
        replayedKnownVolume(rawlog, {"rawlog.poses_file=" + (sim / "trajectory_tum.txt").string()},
                            "tumC");
    });
    EXPECT_NE(e.find("trajectory_tum.txt: none of the 72 depth frames of"), std::string::npos) << e;
    EXPECT_NE(e.find("poses_file_clock = absolute"), std::string::npos) << e;
}

/**
 * The TUM benchmark's ground truth is the camera's optical centre (z forward, y down): the
 * dataset's camera poses written that way, with absolute timestamps, map like its own poses.
 */
TEST(RawlogSource, OpticalCameraPosesOfATumFileMapLikeTheRobotPoses) {
    daep::mission::RawlogSource source(kDataset, "", "DRONE_POSE");
    const fs::path dir = freshDir("optical");
    std::ofstream tum(dir / "groundtruth.txt");
    tum << "# timestamp tx ty tz qx qy qz qw\n" << std::fixed << std::setprecision(9);
    Eigen::Matrix3d sensorInOptical;  // MRPT sensor axes in optical axes
    sensorInOptical << 0, -1, 0, 0, 0, -1, 1, 0, 0;
    for (daep::mission::Frame f; source.next(f);) {
        const mrpt::poses::CPose3D robot(f.robot.position.x(), f.robot.position.y(),
                                         f.robot.position.z(), f.robot.yaw, 0, 0);
        const mrpt::poses::CPose3D sensor = robot + f.depth->sensorPose;
        Eigen::Matrix3d r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                r(i, j) = sensor.getRotationMatrix()(i, j);
        const Eigen::Quaterniond q(r * sensorInOptical.transpose());
        tum << source.firstStamp() + f.time << ' ' << sensor.x() << ' ' << sensor.y() << ' '
            << sensor.z() << ' ' << q.x() << ' ' << q.y() << ' ' << q.z() << ' ' << q.w() << '\n';
    }
    tum.close();
    const double fromRawlog = replayedKnownVolume(kDataset, {}, "opticalA");
    const double fromFile =
        replayedKnownVolume(kDataset,
                            {"rawlog.poses_file=" + (dir / "groundtruth.txt").string(),
                             "rawlog.poses_file_frame=optical"},
                            "opticalB");
    std::cout << "TUM optical poses: known " << fromFile << " m^3, rawlog poses " << fromRawlog
              << " m^3\n";
    EXPECT_GT(fromRawlog, 30.0);
    EXPECT_NEAR(fromFile, fromRawlog, 0.005 * fromRawlog);

    // A poses file that is not one names its line.
    std::ofstream(dir / "bad.txt") << "# header\n1.0 2 3\n";
    const std::string e = inputErrorOf([&] {
        replayedKnownVolume(kDataset, {"rawlog.poses_file=" + (dir / "bad.txt").string()}, "bad");
    });
    EXPECT_NE(e.find("bad.txt:2: expected 'timestamp tx ty tz qx qy qz qw'"), std::string::npos)
        << e;
}

/**
 * The dataset's first `count` objects in the actions / sensory-frames format, each frame's
 * drone pose given instead as a robot movement from the previous one (`movement` makes the
 * action from the increment), the way MRPT logs odometry there.
 */
template <typename Movement>
std::string asMovements(const std::string& name, std::size_t count, Movement&& movement) {
    std::vector<CSerializable::Ptr> out;
    mrpt::obs::CSensoryFrame::Ptr sf;
    mrpt::Clock::time_point stamp{};
    mrpt::poses::CPose3D previous;
    for (const auto& o : readObjects(kDataset, count)) {
        auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(o);
        if (!sf || obs->timestamp != stamp) {
            out.push_back(mrpt::obs::CActionCollection::Create());
            sf = mrpt::obs::CSensoryFrame::Create();
            out.push_back(sf);
            stamp = obs->timestamp;
        }
        auto pose = std::dynamic_pointer_cast<mrpt::obs::CObservationRobotPose>(o);
        if (pose && pose->sensorLabel == "DRONE_POSE") {
            // The action collection before this frame's sensory frame carries the movement.
            auto& actions =
                *std::dynamic_pointer_cast<mrpt::obs::CActionCollection>(out[out.size() - 2]);
            actions.insert(*movement(pose->pose.mean - previous));
            previous = pose->pose.mean;
            continue;
        }
        sf->insert(obs);
    }
    const std::string path = (freshDir(name) / "movements.rawlog").string();
    writeObjects(path, out);
    return path;
}

/** Robot movement actions (2D and 3D) give the poses: pose_label = ACTIONS integrates them. */
TEST(RawlogSource, RobotMovementActionsGiveThePoseIntegrated) {
    const auto move3d = [](const mrpt::poses::CPose3D& change) {
        auto a = mrpt::obs::CActionRobotMovement3D::Create();
        a->poseChange.mean = change;
        return a;
    };
    const std::string rawlog3d = asMovements("move3d", 60, move3d);
    const double fromPoses = replayedKnownVolume(asSensoryFramesFile("sf60", 60), {}, "mvA");
    const double fromActions = replayedKnownVolume(rawlog3d, {"rawlog.pose_label=ACTIONS"}, "mvB");
    std::cout << "3D movements: known " << fromActions << " m^3, poses " << fromPoses << "\n";
    EXPECT_GT(fromPoses, 20.0);
    EXPECT_NEAR(fromActions, fromPoses, 0.002 * fromPoses);

    // Without pose_label = ACTIONS the replay names what the file has.
    const std::string e = inputErrorOf([&] { replayedKnownVolume(rawlog3d, {}, "mvC"); });
    EXPECT_NE(e.find("labelled 'ACTIONS'"), std::string::npos) << e;

    // 2D odometry increments: x, y and heading, on the floor.
    const auto move2d = [](const mrpt::poses::CPose3D& change) {
        auto a = mrpt::obs::CActionRobotMovement2D::Create();
        a->computeFromOdometry(mrpt::poses::CPose2D(change.x(), change.y(), change.yaw()),
                               mrpt::obs::CActionRobotMovement2D::TMotionModelOptions());
        return a;
    };
    const double fromFloorPoses = replayedKnownVolume(
        withDronePoses("floor60", 60,
                       [](const mrpt::obs::CObservationRobotPose& p) {
                           auto q = mrpt::obs::CObservationRobotPose::Create(p);
                           q->pose.mean = mrpt::poses::CPose3D(p.pose.mean.x(), p.pose.mean.y(),
                                                               0.0, p.pose.mean.yaw(), 0, 0);
                           return CSerializable::Ptr(q);
                       }),
        {}, "mvD");
    const double from2d = replayedKnownVolume(asMovements("move2d", 60, move2d),
                                              {"rawlog.pose_label=ACTIONS"}, "mvE");
    std::cout << "2D movements: known " << from2d << " m^3, floor poses " << fromFloorPoses << "\n";
    EXPECT_NEAR(from2d, fromFloorPoses, 0.002 * fromFloorPoses);
}
