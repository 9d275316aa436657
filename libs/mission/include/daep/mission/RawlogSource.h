#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "daep/mission/FrameSource.h"

namespace daep::mission {

/**
 * The depth frames of an MRPT rawlog, streamed one object at a time (never loaded whole), open
 * loop: time runs from the first depth frame, the robot pose is the one the rawlog gives with
 * the frame (see RawlogReader), and a rawlog recorded from the simulator also gives the true
 * people. Errors are InputError naming the file.
 */
class RawlogSource : public FrameSource {
public:
    /** Opens the rawlog; `sensorLabel` empty takes every depth camera. */
    RawlogSource(const std::string& path, std::string sensorLabel, std::string poseLabel);
    ~RawlogSource() override;

    bool next(Frame& frame) override;
    std::string name() const override;

    /** The rawlog timestamp (s since the Unix epoch) of the first depth frame; 0 before it. */
    double firstStamp() const;
    /** Whether the last frame's pose came from the rawlog (else it is the identity). */
    bool lastFrameHadPose() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace daep::mission
