#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <string>

#include "daep/common/Types.h"

namespace mrpt::obs {
class CObservation3DRangeScan;
}

namespace daep::mission {

/** One depth frame of a rawlog with the robot pose it was taken from. */
struct RawlogFrame {
    double stamp = 0.0;  ///< the observation's timestamp, seconds since the Unix epoch
    /** The same timestamp exactly, in mrpt::Clock ticks: differences of these lose nothing. */
    std::int64_t ticks = 0;
    std::shared_ptr<mrpt::obs::CObservation3DRangeScan> depth;
    FlatPose robot;        ///< identity when the rawlog gave no pose at or before `stamp`
    bool hasPose = false;  ///< a pose observation gave `robot`
    /**
     * Ground truth of a simulated run: the latest pose of each CObservationRobotPose labelled
     * PERSON_<i> at or before `stamp`, keyed by i (position = body centre, yaw = heading).
     */
    std::map<int, FlatPose> people;
};

/**
 * Streams the depth frames of an MRPT rawlog (observations format, or actions / sensory-frames
 * format: observations inside CSensoryFrame are taken in order, CActionCollection is skipped),
 * one serialized object at a time; an object of any other class, or a container element of the
 * wrong class, is a corrupt rawlog (see RawlogObjects). A depth frame is a CObservation3DRangeScan
 * with a range image (and the given sensor label, if one is given). Its robot pose is the latest
 * CObservationRobotPose labelled poseLabel whose timestamp is at or before the frame's: pose
 * observations recorded just after the frame with the same timestamp (our simulator writes
 * the frame, then the pose) still pair with it; so do the people's PERSON_<i> poses. Errors are
 * daep::InputError naming the file.
 */
class RawlogReader {
public:
    RawlogReader(const std::string& path, std::string sensorLabel, std::string poseLabel);
    ~RawlogReader();
    RawlogReader(const RawlogReader&) = delete;
    RawlogReader& operator=(const RawlogReader&) = delete;

    /** The next depth frame; false at the end of the file. */
    bool next(RawlogFrame& frame);

    const std::string& path() const;
    /** Serialized objects read so far. */
    std::size_t objectsRead() const;

    /**
     * The largest block MRPT's deserializer may allocate at once while one object is read: a
     * corrupt size field asks for gigabytes or terabytes, and more than this is a "corrupt
     * rawlog" error before anything is allocated. Default: the largest range image accepted,
     * 16384 x 16384 floats (1 GiB).
     */
    static void setLargestReadBlock(std::size_t bytes);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace daep::mission
