#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "daep/common/Types.h"
#include "daep/world/People.h"

namespace mrpt::obs {
class CObservation3DRangeScan;
}

namespace daep::mission {

/**
 * Streams a run to an MRPT rawlog in the observations format (a gzip'ed sequence of
 * serialized CObservation objects), frame by frame, for rawlog-edit and RawLogViewer:
 * the depth frame (label DEPTH_CAM, with a grey intensity image made from depth), the drone's
 * true pose (CObservationRobotPose "DRONE_POSE") and every person's true pose
 * (CObservationRobotPose "PERSON_<i>"). Timestamps are kRawlogEpoch + simulated time.
 */
class RawlogRecorder {
public:
    /** 2000-01-01T00:00:00Z: simulated t = 0 must not become MRPT's invalid timestamp (0). */
    static constexpr double kRawlogEpoch = 946684800.0;

    /** Creates the file; throws std::runtime_error naming the path on failure. */
    explicit RawlogRecorder(const std::string& path);
    ~RawlogRecorder();
    RawlogRecorder(const RawlogRecorder&) = delete;
    RawlogRecorder& operator=(const RawlogRecorder&) = delete;

    void addFrame(const mrpt::obs::CObservation3DRangeScan& depth, double simTime,
                  const FlatPose& drone, const std::vector<world::PersonState>& people,
                  const Eigen::Vector3d& bodySize);

    /** Finishes the gzip stream; further frames are ignored. Also done by the destructor. */
    void close();

    std::size_t observationsWritten() const { return written_; }

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::size_t written_ = 0;
};

}  // namespace daep::mission
