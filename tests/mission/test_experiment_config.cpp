#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileBase.h>

#include "daep/common/Error.h"
#include "daep/mission/ExperimentConfig.h"

using daep::InputError;
using daep::mission::ExperimentConfig;

namespace {

const std::string kMinimal =
    "[experiment]\nworld = cafe\nmode = static\nplanner = rhnbvp\nstart = 2\nseed = 5\n"
    "max_time_s = 100\nplanning_time = fixed\n";

std::string errorOf(const std::string& text, const std::vector<std::string>& overrides = {}) {
    try {
        ExperimentConfig::fromText(text, "exp.ini", overrides);
    } catch (const InputError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(ExperimentConfig, LayersDefaultsFileAndOverrides) {
    const auto cfg = ExperimentConfig::fromText(kMinimal + "[camera]\nwidth = 200\n", "exp.ini",
                                                {"camera.height=100", "experiment.seed=9"});
    const auto& c = cfg.config();
    EXPECT_EQ(c.read_string("experiment", "world", ""), "cafe");
    EXPECT_EQ(c.read_int("camera", "width", 0), 200);
    EXPECT_EQ(c.read_int("camera", "height", 0), 100);
    EXPECT_EQ(c.read_int("experiment", "seed", 0), 9);
    EXPECT_DOUBLE_EQ(c.read_double("map", "resolution", 0), 0.2);  // from defaults.ini
    const std::string dump = cfg.dump();
    EXPECT_NE(dump.find("width = 200"), std::string::npos);
    EXPECT_NE(dump.find("[rhnbvp]"), std::string::npos);
}

TEST(ExperimentConfig, InlineCommentsAreStripped) {
    const auto cfg =
        ExperimentConfig::fromText(kMinimal + "[camera]\nwidth = 200  # narrower\n", "exp.ini");
    EXPECT_EQ(cfg.config().read_int("camera", "width", 0), 200);
}

TEST(ExperimentConfig, EveryRequiredExperimentKeyIsEnforced) {
    for (const auto& key : ExperimentConfig::requiredExperimentKeys()) {
        std::string text;
        std::istringstream in(kMinimal);
        std::string line;
        while (std::getline(in, line))
            if (line.rfind(key + " =", 0) != 0)
                text += line + "\n";
        const std::string err = errorOf(text);
        EXPECT_NE(err.find("[experiment] " + key), std::string::npos) << key << ": " << err;
    }
}

TEST(ExperimentConfig, UnknownKeysAndSectionsAreRejectedWithTheirLine) {
    const std::string err = errorOf(kMinimal + "[camera]\nwidht = 200\n");
    EXPECT_NE(err.find("exp.ini:10"), std::string::npos) << err;
    EXPECT_NE(err.find("widht"), std::string::npos);
    EXPECT_NE(err.find("width"), std::string::npos);  // lists the valid keys
    EXPECT_NE(errorOf(kMinimal + "[camra]\nwidth = 1\n").find("unknown section [camra]"),
              std::string::npos);
    EXPECT_NE(errorOf(kMinimal, {"camera.widht=3"}).find("--set camera.widht=3"),
              std::string::npos);
    EXPECT_NE(errorOf(kMinimal, {"nodot=3"}).find("section.key=value"), std::string::npos);
}

TEST(ExperimentConfig, MalformedLinesNameTheirLine) {
    EXPECT_NE(errorOf("[experiment\nworld = cafe\n").find("exp.ini:1"), std::string::npos);
    EXPECT_NE(errorOf("[experiment]\nworld cafe\n").find("exp.ini:2"), std::string::npos);
    EXPECT_NE(errorOf("world = cafe\n").find("outside any [section]"), std::string::npos);
}
