// The component structs' defaults are those of share/daep/config/defaults.ini: code that builds
// a component without a config (tests, benchmarks, a library user) gets what a run gets.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>

#include <initializer_list>
#include <string>
#include <tuple>

#include "daep/mapping/ExplorationMap.h"
#include "daep/mission/PeopleInput.h"
#include "daep/perception/PeopleDetector.h"
#include "daep/perception/PeopleTracker.h"
#include "daep/sim/DepthCamera.h"
#include "daep/sim/Drone.h"
#include "daep/world/People.h"

namespace {

const std::string kDefaults = std::string(DAEP_SOURCE_DIR) + "/share/daep/config/defaults.ini";

class ComponentDefaults : public ::testing::Test {
protected:
    mrpt::config::CConfigFile ini{kDefaults};
};

using Field = std::tuple<const char*, double, double>;

/** Each field's struct default (second) equals its value from defaults.ini (third). */
void expectSame(std::initializer_list<Field> fields) {
    for (const auto& [name, byDefault, fromIni] : fields)
        EXPECT_DOUBLE_EQ(byDefault, fromIni) << name;
}

TEST_F(ComponentDefaults, Camera) {
    const auto d = daep::sim::CameraParams{}, i = daep::sim::CameraParams::fromConfig(ini);
    expectSame({{"width", d.width, i.width},
                {"height", d.height, i.height},
                {"hfov_deg", d.hfovRad, i.hfovRad},
                {"max_range", d.maxRange, i.maxRange},
                {"rate_hz", d.rateHz, i.rateHz},
                {"noise_sigma", d.noiseSigma, i.noiseSigma}});
}

TEST_F(ComponentDefaults, DroneAndPeople) {
    const auto d = daep::sim::DroneParams{}, i = daep::sim::DroneParams::fromConfig(ini);
    EXPECT_DOUBLE_EQ(d.speed, i.speed);
    EXPECT_NEAR(d.yawRate, i.yawRate, 1e-7);  // the ini gives 1 rad/s in degrees, to 7 digits
    EXPECT_EQ(d.boxSize, i.boxSize);
    const auto dp = daep::world::PeopleParams{}, ip = daep::world::PeopleParams::fromConfig(ini);
    EXPECT_DOUBLE_EQ(dp.speed, ip.speed);
    EXPECT_NEAR(dp.turnRate, ip.turnRate, 1e-7);
    EXPECT_EQ(dp.bodySize, ip.bodySize);
}

TEST_F(ComponentDefaults, Map) {
    const auto d = daep::mapping::MapParams{}, i = daep::mapping::MapParams::fromConfig(ini);
    expectSame({{"resolution", d.resolution, i.resolution},
                {"max_range", d.maxRange, i.maxRange},
                {"prob_hit", d.probHit, i.probHit},
                {"prob_miss", d.probMiss, i.probMiss},
                {"clamp_min", d.clampMin, i.clampMin},
                {"clamp_max", d.clampMax, i.clampMax},
                {"no_return_free", d.noReturnIsFree, i.noReturnIsFree}});
    for (int a = 0; a < 3; ++a)
        EXPECT_DOUBLE_EQ(d.bodyHalfExtents[a], i.bodyHalfExtents[a]) << "[drone] box, axis " << a;
}

TEST_F(ComponentDefaults, Detector) {
    const auto d = daep::perception::DetectorParams{},
               i = daep::perception::DetectorParams::fromConfig(ini);
    expectSame({{"max_range", d.maxRange, i.maxRange},
                {"floor_height", d.floorHeight, i.floorHeight},
                {"ceiling_height", d.ceilingHeight, i.ceilingHeight},
                {"max_person_top", d.maxPersonTop, i.maxPersonTop},
                {"min_vertical_extent", d.minVerticalExtent, i.minVerticalExtent},
                {"max_width", d.maxWidth, i.maxWidth},
                {"max_depth_spread", d.maxDepthSpread, i.maxDepthSpread},
                {"min_area", d.minArea, i.minArea},
                {"min_evidence_fraction", d.minEvidenceFraction, i.minEvidenceFraction},
                {"depth_jump", d.depthJump, i.depthJump},
                {"max_grazing_deg", d.maxGrazingAngle, i.maxGrazingAngle},
                {"surface_margin", d.surfaceMargin, i.surfaceMargin},
                {"centre_offset", d.centreOffset, i.centreOffset},
                {"merge_distance", d.mergeDistance, i.mergeDistance},
                {"sigma_along", d.sigmaAlong, i.sigmaAlong},
                {"sigma_across", d.sigmaAcross, i.sigmaAcross},
                {"side_sigma_across", d.sideSigmaAcross, i.sideSigmaAcross},
                {"imprint_keep_s", d.imprintKeep, i.imprintKeep},
                {"min_fresh_fraction", d.minFreshFraction, i.minFreshFraction},
                {"see_through_depth", d.seeThroughDepth, i.seeThroughDepth},
                {"body_half_width", d.bodyHalfWidth, i.bodyHalfWidth},
                {"body_height", d.bodyHeight, i.bodyHeight}});
    expectSame({{"morph_kernel_px", d.morphKernel, i.morphKernel},
                {"pixel_stride", d.pixelStride, i.pixelStride}});
}

TEST_F(ComponentDefaults, TrackerAndPeopleInput) {
    const auto d = daep::perception::TrackerParams{},
               i = daep::perception::TrackerParams::fromConfig(ini);
    expectSame(
        {{"accel_noise", d.predictor.accelNoise, i.predictor.accelNoise},
         {"measurement_sigma", d.predictor.measurementSigma, i.predictor.measurementSigma},
         {"initial_speed_sigma", d.predictor.initialSpeedSigma, i.predictor.initialSpeedSigma},
         {"drop_after_s", d.dropAfter, i.dropAfter},
         {"drop_after_misses_in_view", d.dropAfterMissesInView, i.dropAfterMissesInView},
         {"gate_chi2", d.gateChi2, i.gateChi2},
         {"confirm_hits", d.confirmHits, i.confirmHits},
         {"tentative_drop_after_s", d.tentativeDropAfter, i.tentativeDropAfter},
         {"static_after_s", d.staticAfter, i.staticAfter},
         {"static_radius", d.staticRadius, i.staticRadius},
         {"static_memory_s", d.staticMemory, i.staticMemory}});

    const auto dp = daep::mission::PeopleInputParams{};
    const auto ip = daep::mission::PeopleInputParams::fromConfig(ini);
    EXPECT_EQ(dp.source, ip.source);
    EXPECT_DOUBLE_EQ(dp.sensedRange, ip.sensedRange);
    EXPECT_DOUBLE_EQ(dp.sensedNoiseSigma, ip.sensedNoiseSigma);
    EXPECT_EQ(dp.excludeFromMap, ip.excludeFromMap);
}

}  // namespace
