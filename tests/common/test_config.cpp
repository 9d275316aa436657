#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>
#include <functional>

#include "daep/common/Config.h"
#include "daep/common/ConfigChecks.h"
#include "daep/common/Error.h"
#include "daep/common/Types.h"

using daep::ConfigReader;
using daep::InputError;

namespace {

mrpt::config::CConfigFileMemory makeConfig() {
    mrpt::config::CConfigFileMemory cfg;
    cfg.write("cam", "width", "640");
    cfg.write("cam", "fov_deg", "90");
    cfg.write("cam", "noise", "0.5");
    cfg.write("cam", "enabled", "true");
    cfg.write("cam", "bad", "12abc");
    cfg.write("cam", "name", "depth");
    return cfg;
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(ConfigReader, ReadsTypedValues) {
    const auto cfg = makeConfig();
    const ConfigReader r(cfg, "cam", "test.ini");
    EXPECT_EQ(r.requireInt("width"), 640);
    EXPECT_DOUBLE_EQ(r.requireDouble("noise"), 0.5);
    EXPECT_NEAR(r.requireAngleDeg("fov_deg"), M_PI / 2, 1e-12);
    EXPECT_TRUE(r.requireBool("enabled"));
    EXPECT_EQ(r.requireString("name"), "depth");
    EXPECT_EQ(r.getInt("absent", 3), 3);
}

TEST(ConfigReader, MissingAndMalformedKeysNameSourceSectionAndKey) {
    const auto cfg = makeConfig();
    const ConfigReader r(cfg, "cam", "test.ini");
    const std::string missing = errorOf([&] { r.requireDouble("height"); });
    EXPECT_NE(missing.find("test.ini"), std::string::npos);
    EXPECT_NE(missing.find("[cam] height"), std::string::npos);
    EXPECT_NE(missing.find("missing"), std::string::npos);
    EXPECT_NE(errorOf([&] { r.requireDouble("bad"); }).find("12abc"), std::string::npos);
    EXPECT_NE(errorOf([&] { r.requireInt("noise"); }).find("not an integer"), std::string::npos);
    EXPECT_NE(errorOf([&] { r.requireBool("name"); }).find("not a boolean"), std::string::npos);
}

// Seen while writing fuzz_experiment_ini (not a sanitizer error): start = 4294967296 was silently
// read as start 0.
TEST(ConfigReader, IntegersBeyondAnIntAreErrors) {
    mrpt::config::CConfigFileMemory cfg;
    cfg.write("experiment", "start", "4294967296");
    cfg.write("experiment", "seed", "-2147483648");
    const ConfigReader r(cfg, "experiment", "test.ini");
    EXPECT_EQ(errorOf([&] { r.requireInt("start"); }),
              "test.ini: [experiment] start: '4294967296' is out of range");
    EXPECT_EQ(r.requireInt("seed"), -2147483648LL);
}

TEST(ConfigChecks, RangeErrorsNameSourceKeyValueAndRange) {
    const auto cfg = makeConfig();
    const ConfigReader r(cfg, "cam", "test.ini");
    EXPECT_EQ(daep::requireIntBetween(r, "width", 16, 8192), 640);
    EXPECT_EQ(errorOf([&] { daep::requireIntBetween(r, "width", 16, 600); }),
              "test.ini: [cam] width: 640 must be in [16, 600]");
    EXPECT_DOUBLE_EQ(daep::requireBetween(r, "fov_deg", 0.0, 180.0), 90.0);
    EXPECT_EQ(errorOf([&] { daep::requireBetween(r, "noise", 0.5, 1.0); }),
              "test.ini: [cam] noise: 0.5 must be in (0.5, 1)");
    mrpt::config::CConfigFileMemory nan;
    nan.write("cam", "sigma", "nan");
    const ConfigReader n(nan, "cam", "test.ini");
    EXPECT_FALSE(errorOf([&] { daep::requireNonNegative(n, "sigma"); }).empty());
}

TEST(Types, WrapAngleStaysInHalfOpenInterval) {
    for (double a = -20.0; a <= 20.0; a += 0.37) {
        const double w = daep::wrapAngle(a);
        EXPECT_GT(w, -M_PI - 1e-12);
        EXPECT_LE(w, M_PI + 1e-12);
        EXPECT_NEAR(std::remainder(w - a, 2 * M_PI), 0.0, 1e-9);
    }
    EXPECT_NEAR(daep::wrapAngle(-M_PI), M_PI, 1e-12);
}

TEST(Types, AabbVolumeAndContainment) {
    daep::Aabb box{{-7.5, -7.5, 0}, {7.5, 7.5, 2}};
    EXPECT_DOUBLE_EQ(box.volume(), 450.0);
    EXPECT_TRUE(box.contains({7.5, 0, 1}));
    EXPECT_FALSE(box.contains({7.6, 0, 1}));
}
