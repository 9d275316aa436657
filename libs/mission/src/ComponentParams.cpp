#include "ComponentParams.h"

#include "daep/common/ConfigChecks.h"
#include "daep/common/Error.h"

namespace daep::mission {

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
    p.noReturnIsFree = r.requireBool("no_return_free");
    if (p.probHit <= 0.5 || p.probHit >= 1)
        throw InputError("[map] prob_hit: must be in (0.5, 1)");
    if (p.probMiss <= 0 || p.probMiss >= 0.5)
        throw InputError("[map] prob_miss: must be in (0, 0.5)");
    return p;
}

perception::DetectorParams loadDetectorParams(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "detector");
    perception::DetectorParams p;
    p.maxRange = requirePositive(r, "max_range");
    p.floorHeight = r.requireDouble("floor_height");
    p.ceilingHeight = r.requireDouble("ceiling_height");
    if (!(p.ceilingHeight > p.floorHeight))
        throw InputError("[detector] ceiling_height: must be above floor_height");
    p.maxPersonTop = requirePositive(r, "max_person_top");
    p.minVerticalExtent = requireNonNegative(r, "min_vertical_extent");
    p.maxWidth = requirePositive(r, "max_width");
    p.maxDepthSpread = requirePositive(r, "max_depth_spread");
    p.minArea = requireNonNegative(r, "min_area");
    p.minEvidenceFraction = requireNonNegative(r, "min_evidence_fraction");
    if (p.minEvidenceFraction > 1)
        throw InputError("[detector] min_evidence_fraction: must be in [0, 1]");
    p.depthJump = requirePositive(r, "depth_jump");
    p.maxGrazingAngle = r.requireAngleDeg("max_grazing_deg");
    if (!(p.maxGrazingAngle > 0 && p.maxGrazingAngle < M_PI / 2))
        throw InputError("[detector] max_grazing_deg: must be in (0, 90)");
    p.morphKernel = requireIntAtLeast(r, "morph_kernel_px", 1);
    p.surfaceMargin = requireNonNegative(r, "surface_margin");
    p.centreOffset = requireNonNegative(r, "centre_offset");
    p.mergeDistance = requireNonNegative(r, "merge_distance");
    p.sigmaAlong = requirePositive(r, "sigma_along");
    p.sigmaAcross = requirePositive(r, "sigma_across");
    p.imprintKeep = requireNonNegative(r, "imprint_keep_s");
    p.minFreshFraction = requireNonNegative(r, "min_fresh_fraction");
    p.seeThroughDepth = requireNonNegative(r, "see_through_depth");
    p.bodyHalfWidth = requirePositive(r, "body_half_width");
    p.bodyHeight = requirePositive(r, "body_height");
    p.pixelStride = requireIntAtLeast(r, "pixel_stride", 1);
    return p;
}

perception::TrackerParams loadTrackerParams(const mrpt::config::CConfigFileBase& cfg) {
    const ConfigReader r(cfg, "tracker");
    perception::TrackerParams p;
    p.predictor.accelNoise = requireNonNegative(r, "accel_noise");
    p.predictor.measurementSigma = requirePositive(r, "measurement_sigma");
    p.predictor.initialSpeedSigma = requirePositive(r, "initial_speed_sigma");
    p.dropAfter = requirePositive(r, "drop_after_s");
    p.dropAfterMissesInView = requireIntAtLeast(r, "drop_after_misses_in_view", 1);
    p.gateChi2 = requirePositive(r, "gate_chi2");
    p.confirmHits = requireIntAtLeast(r, "confirm_hits", 1);
    p.tentativeDropAfter = requirePositive(r, "tentative_drop_after_s");
    p.staticAfter = requireNonNegative(r, "static_after_s");
    p.staticRadius = requirePositive(r, "static_radius");
    p.staticMemory = requireNonNegative(r, "static_memory_s");
    return p;
}

}  // namespace daep::mission
