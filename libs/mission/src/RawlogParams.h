#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

#include "daep/common/Types.h"
#include "daep/mission/FrameSource.h"

namespace daep {
class ConfigReader;
}

namespace daep::mission {

class ExperimentConfig;

/** The [rawlog] section and the rawlog keys of [experiment], validated. */
struct RawlogParams {
    std::string file;  ///< [experiment] rawlog_file; empty when frames come from elsewhere
    std::string world, sensorLabel, poseLabel;
    double planEvery = 1.0;
    bool realtime = false;      ///< play at the rawlog's own pace
    std::string posesFile;      ///< robot poses from this TUM-format file; empty = from the rawlog
    bool posesOptical = false;  ///< [rawlog] poses_file_frame = optical (else body)
    bool posesRelativeTime = false;  ///< [rawlog] poses_file_clock = relative (else absolute)
    Eigen::Vector3d boxMin, boxMax;
};

/** The exploration box of a replay: [rawlog] world's, or box_min/box_max around `firstPose`. */
struct ReplayBox {
    Aabb box;
    double volume = 0.0;
    std::string worldName = "none";
};

ReplayBox replayBox(const ExperimentConfig& config, const RawlogParams& params,
                    const FlatPose& firstPose);

/** Throws InputError naming the file and key; rawlog_file is required only if `needFile`. */
RawlogParams loadRawlogParams(const ExperimentConfig& experiment, bool needFile);

/** [experiment] rawlog_file as a frame source, its poses from [rawlog] poses_file if set. */
std::unique_ptr<FrameSource> openRawlog(const RawlogParams& params);

/**
 * The source's first frame; InputError naming the file when it has none (naming the poses
 * file and its clock when every frame lay outside its span).
 */
Frame firstFrame(FrameSource& source, const RawlogParams& params);

/** A key whose empty value means "not set": its value, trimmed, or "". */
std::string optionalString(const ConfigReader& r, const std::string& key);

}  // namespace daep::mission
