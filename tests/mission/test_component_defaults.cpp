// The component structs' defaults are those of share/daep/config/defaults.ini: code that builds
// a component without a config (tests, benchmarks, a library user) gets what a run gets.
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>

#include <string>

#include "ComponentParams.h"
#include "daep/mission/PeopleInput.h"

namespace {

const std::string kDefaults = std::string(DAEP_SOURCE_DIR) + "/share/daep/config/defaults.ini";

class ComponentDefaults : public ::testing::Test {
protected:
    mrpt::config::CConfigFile ini{kDefaults};
};

TEST_F(ComponentDefaults, Camera) {
    const auto d = daep::sim::CameraParams{}, i = daep::mission::loadCameraParams(ini);
    EXPECT_EQ(d.width, i.width);
    EXPECT_EQ(d.height, i.height);
    EXPECT_DOUBLE_EQ(d.hfovRad, i.hfovRad);
    EXPECT_DOUBLE_EQ(d.maxRange, i.maxRange);
    EXPECT_DOUBLE_EQ(d.rateHz, i.rateHz);
    EXPECT_DOUBLE_EQ(d.noiseSigma, i.noiseSigma);
}

TEST_F(ComponentDefaults, DroneAndPeople) {
    const auto d = daep::sim::DroneParams{}, i = daep::mission::loadDroneParams(ini);
    EXPECT_DOUBLE_EQ(d.speed, i.speed);
    EXPECT_NEAR(d.yawRate, i.yawRate, 1e-7);  // the ini gives 1 rad/s in degrees, to 7 digits
    EXPECT_EQ(d.boxSize, i.boxSize);
    const auto dp = daep::world::PeopleParams{}, ip = daep::mission::loadPeopleParams(ini);
    EXPECT_DOUBLE_EQ(dp.speed, ip.speed);
    EXPECT_NEAR(dp.turnRate, ip.turnRate, 1e-7);
    EXPECT_EQ(dp.bodySize, ip.bodySize);
}

TEST_F(ComponentDefaults, Map) {
    const auto d = daep::mapping::MapParams{}, i = daep::mission::loadMapParams(ini);
    EXPECT_DOUBLE_EQ(d.resolution, i.resolution);
    EXPECT_DOUBLE_EQ(d.maxRange, i.maxRange);
    EXPECT_DOUBLE_EQ(d.probHit, i.probHit);
    EXPECT_DOUBLE_EQ(d.probMiss, i.probMiss);
    EXPECT_DOUBLE_EQ(d.clampMin, i.clampMin);
    EXPECT_DOUBLE_EQ(d.clampMax, i.clampMax);
    EXPECT_EQ(d.noReturnIsFree, i.noReturnIsFree);
}

TEST_F(ComponentDefaults, Detector) {
    const auto d = daep::perception::DetectorParams{}, i = daep::mission::loadDetectorParams(ini);
    for (const auto& [name, a, b] :
         {std::tuple{"max_range", d.maxRange, i.maxRange},
          std::tuple{"floor_height", d.floorHeight, i.floorHeight},
          std::tuple{"ceiling_height", d.ceilingHeight, i.ceilingHeight},
          std::tuple{"max_person_top", d.maxPersonTop, i.maxPersonTop},
          std::tuple{"min_vertical_extent", d.minVerticalExtent, i.minVerticalExtent},
          std::tuple{"max_width", d.maxWidth, i.maxWidth},
          std::tuple{"max_depth_spread", d.maxDepthSpread, i.maxDepthSpread},
          std::tuple{"min_area", d.minArea, i.minArea},
          std::tuple{"min_evidence_fraction", d.minEvidenceFraction, i.minEvidenceFraction},
          std::tuple{"depth_jump", d.depthJump, i.depthJump},
          std::tuple{"max_grazing_deg", d.maxGrazingAngle, i.maxGrazingAngle},
          std::tuple{"surface_margin", d.surfaceMargin, i.surfaceMargin},
          std::tuple{"centre_offset", d.centreOffset, i.centreOffset},
          std::tuple{"merge_distance", d.mergeDistance, i.mergeDistance},
          std::tuple{"sigma_along", d.sigmaAlong, i.sigmaAlong},
          std::tuple{"sigma_across", d.sigmaAcross, i.sigmaAcross},
          std::tuple{"imprint_keep_s", d.imprintKeep, i.imprintKeep},
          std::tuple{"min_fresh_fraction", d.minFreshFraction, i.minFreshFraction},
          std::tuple{"see_through_depth", d.seeThroughDepth, i.seeThroughDepth},
          std::tuple{"body_half_width", d.bodyHalfWidth, i.bodyHalfWidth},
          std::tuple{"body_height", d.bodyHeight, i.bodyHeight}})
        EXPECT_DOUBLE_EQ(a, b) << name;
    EXPECT_EQ(d.morphKernel, i.morphKernel);
    EXPECT_EQ(d.pixelStride, i.pixelStride);
}

TEST_F(ComponentDefaults, TrackerAndPeopleInput) {
    const auto d = daep::perception::TrackerParams{}, i = daep::mission::loadTrackerParams(ini);
    EXPECT_DOUBLE_EQ(d.predictor.accelNoise, i.predictor.accelNoise);
    EXPECT_DOUBLE_EQ(d.predictor.measurementSigma, i.predictor.measurementSigma);
    EXPECT_DOUBLE_EQ(d.predictor.initialSpeedSigma, i.predictor.initialSpeedSigma);
    EXPECT_DOUBLE_EQ(d.dropAfter, i.dropAfter);
    EXPECT_EQ(d.dropAfterMissesInView, i.dropAfterMissesInView);
    EXPECT_DOUBLE_EQ(d.gateChi2, i.gateChi2);
    EXPECT_EQ(d.confirmHits, i.confirmHits);
    EXPECT_DOUBLE_EQ(d.tentativeDropAfter, i.tentativeDropAfter);

    const auto dp = daep::mission::PeopleInputParams{};
    const auto ip = daep::mission::PeopleInputParams::fromConfig(ini);
    EXPECT_EQ(dp.source, ip.source);
    EXPECT_DOUBLE_EQ(dp.sensedRange, ip.sensedRange);
    EXPECT_DOUBLE_EQ(dp.sensedNoiseSigma, ip.sensedNoiseSigma);
    EXPECT_EQ(dp.excludeFromMap, ip.excludeFromMap);
}

}  // namespace
