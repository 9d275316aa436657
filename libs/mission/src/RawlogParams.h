#pragma once

#include <Eigen/Core>
#include <string>

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
    bool realtime = false;  ///< play at the rawlog's own pace
    Eigen::Vector3d boxMin, boxMax;
};

/** Throws InputError naming the file and key; rawlog_file is required only if `needFile`. */
RawlogParams loadRawlogParams(const ExperimentConfig& experiment, bool needFile);

/** A key whose empty value means "not set": its value, trimmed, or "". */
std::string optionalString(const ConfigReader& r, const std::string& key);

}  // namespace daep::mission
