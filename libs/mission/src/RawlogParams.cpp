#include "RawlogParams.h"

#include <mrpt/config/CConfigFileBase.h>

#include <sstream>

#include "MissionSetup.h"
#include "daep/common/Config.h"
#include "daep/common/ConfigChecks.h"
#include "daep/common/Error.h"
#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/RawlogSource.h"

namespace daep::mission {

/** A key whose empty value means "not set". */
std::string optionalString(const ConfigReader& r, const std::string& key) {
    const std::string v = r.config().read_string(r.section(), key, "", false);
    const auto b = v.find_first_not_of(" \t");
    const auto e = v.find_last_not_of(" \t\r");
    return b == std::string::npos ? std::string() : v.substr(b, e - b + 1);
}

namespace {

Eigen::Vector3d readVector(const ConfigReader& r, const std::string& key,
                           const std::string& source) {
    std::istringstream is(r.requireString(key));
    Eigen::Vector3d v;
    if (!(is >> v.x() >> v.y() >> v.z()) || !(is >> std::ws).eof())
        throw InputError(source + ": [rawlog] " + key + ": expected three numbers \"x y z\"");
    return v;
}

}  // namespace

RawlogParams loadRawlogParams(const ExperimentConfig& experiment, bool needFile) {
    const std::string& source = experiment.source();
    const ConfigReader e(experiment.config(), "experiment", source);
    const ConfigReader r(experiment.config(), "rawlog", source);
    RawlogParams p;
    p.file = resolveDataPath(optionalString(e, "rawlog_file"));
    if (p.file.empty() && needFile)
        throw InputError(source + ": [experiment] rawlog_file: required when source = rawlog");
    p.planEvery = r.requireDouble("plan_every_s");
    if (p.planEvery <= 0)
        throw InputError(source + ": [rawlog] plan_every_s: must be > 0");
    p.world = optionalString(r, "world");
    p.boxMin = readVector(r, "box_min", source);
    p.boxMax = readVector(r, "box_max", source);
    if (p.world.empty() && !(p.boxMin.array() < p.boxMax.array()).all())
        throw InputError(source + ": [rawlog] box_min must be below box_max on every axis");
    p.sensorLabel = optionalString(r, "sensor_label");
    p.poseLabel = r.requireString("pose_label");
    p.realtime = r.requireBool("realtime");
    p.posesFile = resolveDataPath(optionalString(r, "poses_file"));
    p.posesOptical = requireOneOf(r, "poses_file_frame", {"body", "optical"}) == "optical";
    p.posesRelativeTime =
        requireOneOf(r, "poses_file_clock", {"absolute", "relative"}) == "relative";
    return p;
}

ReplayBox replayBox(const ExperimentConfig& config, const RawlogParams& params,
                    const FlatPose& firstPose) {
    ReplayBox r;
    if (params.world.empty()) {
        r.box.min = firstPose.position + params.boxMin;
        r.box.max = firstPose.position + params.boxMax;
        r.volume = r.box.volume();
        return r;
    }
    Settings s = loadSettings(config);  // loadWorld resolves the name like [experiment] world
    s.worldName = params.world;
    s.mode = "static";
    s.start = 0;
    const world::WorldSpec w = loadWorld(s, config.source());
    r.box = w.explorationBox;
    r.volume = w.explorationVolume();
    r.worldName = w.name;
    return r;
}

std::unique_ptr<FrameSource> openRawlog(const RawlogParams& params) {
    if (params.posesFile.empty())
        return std::make_unique<RawlogSource>(params.file, params.sensorLabel, params.poseLabel);
    const RawlogSource::PosesFile poses{params.posesFile, params.posesOptical,
                                        params.posesRelativeTime};
    return std::make_unique<RawlogSource>(params.file, params.sensorLabel, params.poseLabel,
                                          &poses);
}

Frame firstFrame(FrameSource& source, const RawlogParams& params) {
    Frame first;
    if (source.next(first))
        return first;
    const auto* rawlog = dynamic_cast<const RawlogSource*>(&source);
    if (rawlog && rawlog->framesOutsidePoses() > 0)
        throw InputError(params.posesFile + ": none of the " +
                         std::to_string(rawlog->framesOutsidePoses()) + " depth frames of " +
                         source.name() +
                         " lies within its time span ([rawlog] poses_file_clock = " +
                         (params.posesRelativeTime ? "relative" : "absolute") + ")");
    throw InputError(source.name() +
                     ": no depth frames (CObservation3DRangeScan with a range image" +
                     (params.sensorLabel.empty() ? "" : ", label " + params.sensorLabel) + ")");
}

}  // namespace daep::mission
