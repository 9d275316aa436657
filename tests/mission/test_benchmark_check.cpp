#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "daep/common/Error.h"
#include "daep/mission/BenchmarkCheck.h"

namespace fs = std::filesystem;
using daep::mission::checkBenchmark;
using daep::mission::sha256Hex;

namespace {

/** A benchmark of a small box world, all files in a private folder. */
class BenchmarkCheckTest : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("daep_benchcheck_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        std::ofstream(dir_ / "room.yaml")
            << "name: room\nexploration_box: {min: [-2, -2, 0], max: [2, 2, 2]}\nground: true\n"
               "starts: [[0, 0, 0.2], [1, 1, 0.2]]\n";
        std::ofstream(dir_ / "base.ini")
            << "[experiment]\nworld = room.yaml\nmode = static\nplanner = aep\nstart = 0\n"
               "seed = 1\nmax_time_s = 10\nplanning_time = fixed\n";
    }
    void TearDown() override { fs::remove_all(dir_); }

    /** `setLines` go to the [set] section from line 11 on. */
    daep::eval::BenchmarkConfig config(const std::vector<std::string>& sets = {},
                                       const std::string& setLines = "") const {
        const auto path = dir_ / "bench.ini";
        std::ofstream(path) << "[benchmark]\nplanners = aep, dep\nworlds = room.yaml\n"
                               "modes = static\nstarts = 0-1\nrepetitions = 1\nseed = 1\n"
                               "experiment = base.ini\n[set]\nexperiment.max_time_s = 5\n"
                            << setLines;
        return daep::eval::loadBenchmarkConfig(path.string(), sets);
    }

    std::string errorOf(const std::vector<std::string>& sets,
                        const std::string& setLines = "") const {
        try {
            checkBenchmark(config(sets, setLines));
        } catch (const daep::InputError& e) {
            return e.what();
        }
        return "";
    }

    fs::path dir_;
};

}  // namespace

TEST(Sha256, MatchesTheStandardTestVectors) {
    EXPECT_EQ(sha256Hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    EXPECT_EQ(sha256Hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
}

TEST_F(BenchmarkCheckTest, EveryRunGetsTheDigestOfItsParametersAndWorld) {
    const auto runs = checkBenchmark(config());
    ASSERT_EQ(runs.size(), 4u);
    for (const auto& run : runs) {
        EXPECT_EQ(run.inputs.digest.size(), 64u);
        ASSERT_EQ(run.inputs.files.size(), 1u);
        EXPECT_EQ(run.inputs.files[0].first, "room.yaml");
        EXPECT_NE(run.inputs.parameters.find("max_time_s = 5\n"), std::string::npos);
    }
    EXPECT_NE(runs[0].inputs.digest, runs[1].inputs.digest);  // another start
    // The same inputs give the same digest; any change to a parameter or the world changes it.
    EXPECT_EQ(checkBenchmark(config())[0].inputs.digest, runs[0].inputs.digest);
    EXPECT_NE(checkBenchmark(config({"camera.width=100"}))[0].inputs.digest, runs[0].inputs.digest);
    std::ofstream(dir_ / "room.yaml", std::ios::app) << "# a comment\n";
    const auto edited = checkBenchmark(config());
    EXPECT_NE(edited[0].inputs.digest, runs[0].inputs.digest);
    EXPECT_EQ(edited[0].inputs.parameters, runs[0].inputs.parameters);
}

TEST_F(BenchmarkCheckTest, BadMatrixErrorsNameWhereTheValueWasGiven) {
    EXPECT_EQ(errorOf({}), "");
    EXPECT_NE(errorOf({"benchmark.planners=aep,foo"})
                  .find("--set benchmark.planners: [benchmark] planners: unknown planner 'foo' "
                        "(known: "),
              std::string::npos);
    EXPECT_NE(errorOf({"benchmark.worlds=atlantis"})
                  .find("--set benchmark.worlds: [benchmark] worlds: world 'atlantis': no such"),
              std::string::npos)
        << errorOf({"benchmark.worlds=atlantis"});
    EXPECT_EQ(errorOf({"benchmark.starts=0-9"}),
              "--set benchmark.starts: [benchmark] starts: start 2 is out of range 0..1 for world "
              "room.yaml");
    EXPECT_NE(errorOf({"experiment.max_tme_s=3"})
                  .find("--set experiment.max_tme_s: unknown key 'experiment.max_tme_s'"),
              std::string::npos);
    EXPECT_NE(errorOf({"camera.width=x"}).find("--set camera.width: [camera] width: 'x' is not"),
              std::string::npos)
        << errorOf({"camera.width=x"});
    // Keys and values from the [set] section are blamed on their line.
    EXPECT_NE(errorOf({}, "camera.widht = 100\n").find("bench.ini:11: unknown key 'camera.widht'"),
              std::string::npos)
        << errorOf({}, "camera.widht = 100\n");
    EXPECT_NE(errorOf({}, "camera.width = x\n").find("bench.ini:11: [camera] width: 'x' is not"),
              std::string::npos)
        << errorOf({}, "camera.width = x\n");
}
