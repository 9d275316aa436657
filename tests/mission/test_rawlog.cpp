#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/serialization/CArchive.h>
#include <unistd.h>

#include <filesystem>
#include <map>

#include "daep/mapping/DepthUnprojection.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/Mission.h"

namespace {

namespace fs = std::filesystem;
using mrpt::obs::CObservation3DRangeScan;
using mrpt::obs::CObservationRobotPose;

const std::string kTinyRoom = std::string(DAEP_SOURCE_DIR) + "/tests/e2e/data/tiny_room.ini";

std::vector<mrpt::serialization::CSerializable::Ptr> readAll(const std::string& path) {
    mrpt::io::CFileGZInputStream in(path);
    auto arch = mrpt::serialization::archiveFrom(in);
    std::vector<mrpt::serialization::CSerializable::Ptr> objects;
    try {
        for (;;) {
            mrpt::serialization::CSerializable::Ptr o;
            arch >> o;
            objects.push_back(o);
        }
    } catch (const mrpt::serialization::CExceptionEOF&) {
    }
    return objects;
}

/** Tiny room: walls 2.5 m high just outside the [-4,4] x [-2.5,2.5] x [0,2] box. */
bool insideWorld(const Eigen::Vector3f& p) {
    return p.x() > -4.3f && p.x() < 4.3f && p.y() > -2.8f && p.y() < 2.8f && p.z() > -0.1f &&
           p.z() < 2.6f;
}

TEST(Rawlog, MissionStreamsDepthFramesDronePoseAndPeople) {
    const fs::path out =
        fs::temp_directory_path() / ("daep_test_rawlog_" + std::to_string(::getpid()));
    fs::remove_all(out);
    const auto config = daep::mission::ExperimentConfig::fromFile(
        kTinyRoom, {"experiment.max_time_s=10", "output.rawlog=true", "output.scene=false"});
    daep::mission::Mission(config, out.string(), nullptr).run();

    const auto objects = readAll((out / "run.rawlog").string());
    std::map<std::string, int> perLabel;
    std::map<std::string, mrpt::Clock::time_point> lastStamp;
    mrpt::Clock::time_point previous{};
    const CObservation3DRangeScan* pendingScan = nullptr;
    std::size_t checkedPoints = 0;
    for (const auto& o : objects) {
        const auto* obs = dynamic_cast<const mrpt::obs::CObservation*>(o.get());
        ASSERT_NE(obs, nullptr) << o->GetRuntimeClass()->className;
        EXPECT_GE(obs->timestamp, previous);
        previous = obs->timestamp;
        if (perLabel[obs->sensorLabel]++ > 0) {
            EXPECT_GT(obs->timestamp, lastStamp[obs->sensorLabel]) << obs->sensorLabel;
        }
        lastStamp[obs->sensorLabel] = obs->timestamp;
        if (const auto* scan = dynamic_cast<const CObservation3DRangeScan*>(obs)) {
            EXPECT_EQ(scan->sensorLabel, "DEPTH_CAM");
            EXPECT_TRUE(scan->hasRangeImage);
            EXPECT_TRUE(scan->hasIntensityImage);
            pendingScan = scan;
        } else if (const auto* pose = dynamic_cast<const CObservationRobotPose*>(obs);
                   pose && pose->sensorLabel == "DRONE_POSE") {
            ASSERT_NE(pendingScan, nullptr) << "a drone pose without its depth frame";
            daep::FlatPose drone;
            const auto& m = pose->pose.mean;
            drone.position = {m.x(), m.y(), m.z()};
            drone.yaw = m.yaw();
            EXPECT_TRUE(insideWorld(drone.position.cast<float>()));
            for (const auto& p : daep::mapping::unprojectDepthImage(*pendingScan, drone)) {
                ASSERT_TRUE(insideWorld(p)) << p.transpose();
                ++checkedPoints;
            }
            pendingScan = nullptr;
        }
    }
    // 10 s of exploration after take-off at 5 Hz: well over 50 frames.
    EXPECT_GT(perLabel["DEPTH_CAM"], 50);
    EXPECT_EQ(perLabel["DRONE_POSE"], perLabel["DEPTH_CAM"]);
    EXPECT_EQ(perLabel["PERSON_0"], perLabel["DEPTH_CAM"]);
    EXPECT_EQ(perLabel.size(), 3u);
    EXPECT_GT(checkedPoints, 1000u);
    fs::remove_all(out);
}

}  // namespace
