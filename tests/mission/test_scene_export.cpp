#include <gtest/gtest.h>
#include <mrpt/img/CImage.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/opengl/COctoMapVoxels.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfLines.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/serialization/CArchive.h>
#include <unistd.h>

#include <filesystem>
#include <set>

#include "daep/mission/ExperimentConfig.h"
#include "daep/mission/Mission.h"

namespace {

namespace fs = std::filesystem;
namespace gl = mrpt::opengl;

const std::string kTinyRoom = std::string(DAEP_SOURCE_DIR) + "/tests/e2e/data/tiny_room.ini";

std::size_t distinctColours(const mrpt::img::CImage& image) {
    std::set<std::uint32_t> colours;
    for (std::size_t y = 0; y < image.getHeight(); y += 4)
        for (std::size_t x = 0; x < image.getWidth(); x += 4) {
            const auto* p = image.ptr<std::uint8_t>(x, y);
            colours.insert(std::uint32_t(p[0]) << 16 | std::uint32_t(p[1]) << 8 | p[2]);
        }
    return colours.size();
}

class SceneExport : public ::testing::Test {
protected:
    void SetUp() override {
        out_ = fs::temp_directory_path() / ("daep_test_scene_export_" + std::to_string(::getpid()));
        fs::remove_all(out_);
        const auto config = daep::mission::ExperimentConfig::fromFile(
            kTinyRoom,
            {"experiment.max_time_s=15", "output.png_width=320", "output.png_height=240"});
        daep::mission::Mission(config, out_.string(), nullptr).run();
    }
    void TearDown() override { fs::remove_all(out_); }
    fs::path out_;
};

TEST_F(SceneExport, SceneFileLoadsWithEveryNamedObject) {
    gl::COpenGLScene scene;
    {
        mrpt::io::CFileGZInputStream in((out_ / "scene.3Dscene").string());
        mrpt::serialization::archiveFrom(in) >> scene;
    }
    for (const char* name : {"occupied_voxels", "trajectory", "people", "predicted_paths", "tree",
                             "box", "grid", "drone"})
        EXPECT_NE(scene.getByName(name), nullptr) << name;
    const auto voxels =
        std::dynamic_pointer_cast<gl::COctoMapVoxels>(scene.getByName("occupied_voxels"));
    ASSERT_NE(voxels, nullptr);
    EXPECT_GT(voxels->getVoxelCount(0), 500u);
    const auto trajectory =
        std::dynamic_pointer_cast<gl::CSetOfLines>(scene.getByName("trajectory"));
    ASSERT_NE(trajectory, nullptr);
    EXPECT_GT(trajectory->getLineCount(), 10u);
    const auto tree = std::dynamic_pointer_cast<gl::CSetOfLines>(scene.getByName("tree"));
    ASSERT_NE(tree, nullptr);
    EXPECT_GT(tree->getLineCount(), 0u);
    const auto people = std::dynamic_pointer_cast<gl::CSetOfObjects>(scene.getByName("people"));
    ASSERT_NE(people, nullptr);
    EXPECT_EQ(std::distance(people->begin(), people->end()), 1);  // tiny_room has one walker
}

TEST_F(SceneExport, PngsHaveTheConfiguredSizeAndContent) {
    const fs::path perspective = out_ / "scene_perspective.png";
    const fs::path top = out_ / "scene_top.png";
    if (!fs::exists(perspective) && !fs::exists(top))
        GTEST_SKIP() << "no EGL/OpenGL here: the mission skipped the PNGs (see its warning)";
    for (const auto& path : {perspective, top}) {
        mrpt::img::CImage image;
        ASSERT_TRUE(image.loadFromFile(path.string())) << path;
        EXPECT_EQ(image.getWidth(), 320u) << path;
        EXPECT_EQ(image.getHeight(), 240u) << path;
        EXPECT_GT(distinctColours(image), 20u) << path;
    }
    // The top view shows the walker in the people's magenta and the flown trajectory in black
    // (drawn over the voxels); no voxel takes either colour.
    mrpt::img::CImage image;
    ASSERT_TRUE(image.loadFromFile(top.string()));
    std::size_t magenta = 0, black = 0;
    for (std::size_t y = 0; y < image.getHeight(); ++y)
        for (std::size_t x = 0; x < image.getWidth(); ++x) {
            const bool overlay = x < 135 && (y < 110 || y > 212);  // legend, scale bar
            if (overlay)
                continue;
            const auto* p = image.ptr<std::uint8_t>(x, y);  // B, G, R
            magenta += p[2] > 120 && p[0] > 120 && p[1] < 60;
            black += p[0] < 30 && p[1] < 30 && p[2] < 30;
        }
    EXPECT_GT(magenta, 10u);
    EXPECT_GT(black, 30u);
}

}  // namespace
