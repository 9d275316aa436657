// RawlogObjects: the classes a rawlog may hold are checked before MRPT deserializes them, and
// CSensoryFrame / CActionCollection are unpacked here, element by element.
#include <gtest/gtest.h>
#include <mrpt/img/CImage.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <cstring>
#include <string>
#include <vector>

#include "RawlogObjects.h"

namespace {

using daep::mission::MalformedObject;
using daep::mission::RawlogObjects;
using daep::mission::TruncatedObject;
using Observations = std::vector<std::shared_ptr<mrpt::obs::CObservation>>;

std::string serialized(const mrpt::serialization::CSerializable& object) {
    mrpt::io::CMemoryStream m;
    mrpt::serialization::archiveFrom(m) << object;
    return {static_cast<const char*>(m.getRawBufferData()),
            static_cast<std::size_t>(m.getTotalBytesCount())};
}

/** A header in MRPT's current format: lead byte, class name, one version byte. */
std::string header(const std::string& className, unsigned char version) {
    return std::string(1, static_cast<char>(0x80 | className.size())) + className +
           static_cast<char>(version);
}

template <typename T>
std::string bytesOf(T value) {
    std::string b(sizeof(T), '\0');
    std::memcpy(b.data(), &value, sizeof(T));
    return b;
}

const std::string kEnd(1, static_cast<char>(0x88));

std::shared_ptr<mrpt::obs::CObservationOdometry> odometry(double stamp, const std::string& label) {
    auto o = mrpt::obs::CObservationOdometry::Create();
    o->timestamp = mrpt::Clock::fromDouble(stamp);
    o->sensorLabel = label;
    return o;
}

/** Every observation of a file, read to its end. */
Observations readAll(const std::string& file) {
    mrpt::io::CMemoryStream in(file.data(), file.size());
    RawlogObjects objects(in);
    Observations out;
    while (objects.readNext(out)) {
    }
    return out;
}

/** What reading a file to its end throws as MalformedObject ("" for none). */
std::string malformedReason(const std::string& file) {
    try {
        readAll(file);
    } catch (const MalformedObject& e) {
        return e.what();
    }
    return "";
}

TEST(RawlogObjects, ReadsObservationsSensoryFramesAndSkipsActions) {
    mrpt::obs::CActionCollection actions;
    mrpt::obs::CActionRobotMovement2D move;
    actions.insert(move);
    mrpt::obs::CSensoryFrame frame;
    frame.insert(odometry(10.0, "A"));
    frame.insert(odometry(10.5, "B"));
    const std::string file = serialized(*odometry(9.0, "FIRST")) + serialized(actions) +
                             serialized(frame) + serialized(mrpt::obs::CActionCollection());

    mrpt::io::CMemoryStream in(file.data(), file.size());
    RawlogObjects objects(in);
    Observations out;
    ASSERT_TRUE(objects.readNext(out));
    ASSERT_EQ(out.size(), 1u);
    ASSERT_TRUE(objects.readNext(out));
    EXPECT_EQ(out.size(), 1u);  // the actions carry no observation
    ASSERT_TRUE(objects.readNext(out));
    ASSERT_EQ(out.size(), 3u);
    ASSERT_TRUE(objects.readNext(out));
    EXPECT_FALSE(objects.readNext(out));
    EXPECT_EQ(out[0]->sensorLabel, "FIRST");
    EXPECT_EQ(out[1]->sensorLabel, "A");
    EXPECT_EQ(out[2]->sensorLabel, "B");
    EXPECT_DOUBLE_EQ(mrpt::Clock::toDouble(out[2]->timestamp), 10.5);
}

/** Versions 0 and 1 of CSensoryFrame carry an ID; version 0 one timestamp for all. */
TEST(RawlogObjects, OlderSensoryFrameVersionsAreRead) {
    const auto frameStamp = mrpt::Clock::fromDouble(20.0);
    const std::string elements = bytesOf<std::uint32_t>(2) + serialized(*odometry(1.0, "A")) +
                                 serialized(*odometry(2.0, "B"));
    const std::string v0 = header("CSensoryFrame", 0) + bytesOf<std::uint32_t>(7) +
                           bytesOf<std::int64_t>(frameStamp.time_since_epoch().count()) + elements +
                           kEnd;
    const std::string v1 = header("CSensoryFrame", 1) + bytesOf<std::uint32_t>(7) + elements + kEnd;
    const auto a = readAll(v0), b = readAll(v1);
    ASSERT_EQ(a.size(), 2u);
    ASSERT_EQ(b.size(), 2u);
    EXPECT_EQ(a[0]->timestamp, frameStamp);
    EXPECT_EQ(a[1]->timestamp, frameStamp);
    EXPECT_DOUBLE_EQ(mrpt::Clock::toDouble(b[1]->timestamp), 2.0);
    EXPECT_EQ(b[1]->sensorLabel, "B");
}

/** The format before MRPT 0.5.5: no flag bit, three zero bytes, a 4-byte version, no end flag. */
TEST(RawlogObjects, ObjectsInTheOldHeaderFormatAreRead) {
    const auto o = odometry(3.0, "OLD");
    const std::string current = serialized(*o);
    const std::string name = current.substr(1, current[0] & 0x7f);
    const std::size_t bodyAt = 1 + name.size() + 1;
    const std::string body = current.substr(bodyAt, current.size() - bodyAt - 1);
    const std::string old = std::string(1, static_cast<char>(name.size())) + std::string(3, '\0') +
                            name + bytesOf<std::int32_t>(current[bodyAt - 1]) + body;
    const auto read = readAll(old);
    ASSERT_EQ(read.size(), 1u);
    EXPECT_EQ(read[0]->sensorLabel, "OLD");
}

/**
 * fuzz_rawlog's finding: MRPT 2.5 reads an element of another class as a null action and
 * reads through it (a crash). Here it is an error naming both classes.
 */
TEST(RawlogObjects, AContainerElementOfAnotherClassIsMalformed) {
    const std::string nested = header("CActionCollection", 0) + bytesOf<std::uint32_t>(1) +
                               serialized(mrpt::obs::CActionCollection()) + kEnd;
    EXPECT_EQ(
        malformedReason(nested),
        "is a CActionCollection holding a mrpt::obs::CActionCollection where an action must be");

    const std::string actionInFrame = header("CSensoryFrame", 0) + bytesOf<std::uint32_t>(0) +
                                      bytesOf<std::int64_t>(0) + bytesOf<std::uint32_t>(1) +
                                      serialized(mrpt::obs::CActionRobotMovement2D()) + kEnd;
    EXPECT_EQ(malformedReason(actionInFrame),
              "is a CSensoryFrame holding a mrpt::obs::CActionRobotMovement2D where an observation "
              "must be");

    // An abstract class is known to MRPT but cannot be created: MRPT would give a null.
    const std::string abstract = header("CSensoryFrame", 2) + bytesOf<std::uint32_t>(1) +
                                 header("CObservation", 0) + kEnd + kEnd;
    EXPECT_NE(malformedReason(abstract).find("holding a CObservation where"), std::string::npos);

    const std::string null = header("CSensoryFrame", 2) + bytesOf<std::uint32_t>(1) +
                             std::string(1, static_cast<char>(0x80 | 7)) + "nullptr" + kEnd + kEnd;
    EXPECT_NE(malformedReason(null).find("holding a nullptr"), std::string::npos);
}

TEST(RawlogObjects, TopLevelObjectsARawlogDoesNotHoldAreMalformed) {
    EXPECT_EQ(
        malformedReason(serialized(mrpt::img::CImage(4, 3))),
        "is a mrpt::img::CImage, which a rawlog does not hold (observations, CSensoryFrame and "
        "CActionCollection)");
    EXPECT_EQ(malformedReason(header("CNoSuchClass\x01", 0) + kEnd),
              "is of class 'CNoSuchClass?', which MRPT does not know");
    EXPECT_EQ(malformedReason(std::string(1, static_cast<char>(0x80 | 7)) + "nullptr" + kEnd),
              "is a null object");
    EXPECT_NE(malformedReason("this is text, not a rawlog").find("is no MRPT object"),
              std::string::npos);
    EXPECT_NE(malformedReason(header("CSensoryFrame", 3)).find("version 3"), std::string::npos);
    EXPECT_NE(malformedReason(header("CActionCollection", 1)).find("version 1"), std::string::npos);
    mrpt::obs::CSensoryFrame frame;
    frame.insert(odometry(1.0, "A"));
    std::string noEndFlag = serialized(frame);
    noEndFlag.back() = '\x77';
    EXPECT_EQ(malformedReason(noEndFlag),
              "is a CSensoryFrame without an end flag after its elements");
}

/** Cut anywhere inside an object, a rawlog is an error (never a crash); cut at its end, not. */
TEST(RawlogObjects, EveryCutInsideAnObjectThrows) {
    mrpt::obs::CSensoryFrame frame;
    frame.insert(odometry(1.0, "A"));
    frame.insert(odometry(2.0, "B"));
    const std::string file = serialized(frame);
    for (std::size_t cut = 1; cut < file.size(); ++cut)
        EXPECT_THROW(readAll(file.substr(0, cut)), std::exception) << "cut at " << cut;
    EXPECT_EQ(readAll(file).size(), 2u);
    EXPECT_TRUE(readAll("").empty());

    // A count of 4 billion elements allocates nothing before the file ends.
    const std::string huge = header("CSensoryFrame", 2) + bytesOf<std::uint32_t>(0xffffffffu);
    EXPECT_THROW(readAll(huge), TruncatedObject);
}

}  // namespace
