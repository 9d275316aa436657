#include "ComponentParams.h"

#include "daep/common/Error.h"

namespace daep::mission {
namespace {

double requirePositive(const ConfigReader& r, const std::string& key) {
    const double v = r.requireDouble(key);
    if (!(v > 0))
        throw InputError("[" + r.section() + "] " + key + ": must be > 0");
    return v;
}

}  // namespace

sim::CameraParams loadCameraParams(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "camera");
    sim::CameraParams p;
    p.width = r.requireInt("width");
    p.height = r.requireInt("height");
    if (p.width < 2 || p.height < 2)
        throw InputError("[camera] width/height: must be >= 2");
    p.hfovRad = r.requireAngleDeg("hfov_deg");
    if (p.hfovRad <= 0 || p.hfovRad >= M_PI)
        throw InputError("[camera] hfov_deg: must be in (0, 180)");
    p.maxRange = requirePositive(r, "max_range");
    p.rateHz = requirePositive(r, "rate_hz");
    p.noiseSigma = r.requireDouble("noise_sigma");
    if (p.noiseSigma < 0)
        throw InputError("[camera] noise_sigma: must be >= 0");
    return p;
}

sim::DroneParams loadDroneParams(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "drone");
    sim::DroneParams p;
    p.speed = requirePositive(r, "speed");
    p.yawRate = requirePositive(r, "yaw_rate_deg_s") * M_PI / 180.0;
    p.boxSize = {requirePositive(r, "box_x"), requirePositive(r, "box_y"),
                 requirePositive(r, "box_z")};
    return p;
}

world::PeopleParams loadPeopleParams(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "people");
    world::PeopleParams p;
    p.speed = requirePositive(r, "speed");
    p.turnRate = requirePositive(r, "turn_rate_deg_s") * M_PI / 180.0;
    p.bodySize = {requirePositive(r, "body_x"), requirePositive(r, "body_y"),
                  requirePositive(r, "body_z")};
    return p;
}

mapping::MapParams loadMapParams(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "map");
    mapping::MapParams p;
    p.resolution = requirePositive(r, "resolution");
    p.maxRange = requirePositive(r, "max_range");
    p.probHit = r.requireDouble("prob_hit");
    p.probMiss = r.requireDouble("prob_miss");
    p.clampMin = r.requireDouble("clamp_min");
    p.clampMax = r.requireDouble("clamp_max");
    if (p.probHit <= 0.5 || p.probHit >= 1)
        throw InputError("[map] prob_hit: must be in (0.5, 1)");
    if (p.probMiss <= 0 || p.probMiss >= 0.5)
        throw InputError("[map] prob_miss: must be in (0, 0.5)");
    return p;
}

}  // namespace daep::mission
