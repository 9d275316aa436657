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
    /**
     * Robot poses from a file instead of the rawlog's pose observations: a trajectory in the
     * TUM format, as RGB-D datasets ship their ground truth (TumPoses).
     */
    struct PosesFile {
        std::string path;
        /**
         * Whose poses they are: the robot body's (x forward, z up; trajectory_tum.txt of a run),
         * or the camera's optical centre (z forward, y down; the TUM RGB-D benchmark's
         * groundtruth.txt), which then replaces the frame's sensorPose.
         */
        bool optical = false;
        /** Timestamps in seconds since the first depth frame, not since 1970. */
        bool relativeTime = false;
    };

    /** Opens the rawlog; `sensorLabel` empty takes every depth camera. */
    RawlogSource(const std::string& path, std::string sensorLabel, std::string poseLabel,
                 const PosesFile* poses = nullptr);
    ~RawlogSource() override;

    bool next(Frame& frame) override;
    std::string name() const override;

    /** The rawlog timestamp (s since the Unix epoch) of the first depth frame; 0 before it. */
    double firstStamp() const;
    /** Whether the last frame's pose came from the rawlog or the poses file (else identity). */
    bool lastFrameHadPose() const;
    /** Depth frames skipped so far because they lie outside the poses file's time span. */
    std::size_t framesOutsidePoses() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace daep::mission
