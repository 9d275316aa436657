#pragma once

#include <string>
#include <vector>

#include "daep/eval/RunRecorder.h"

namespace daep::mission {

/**
 * The daep-explore application (MRPT app pattern: a thin main calls initialize() then run()).
 * A test can run the real app by calling the same two functions.
 */
class ExploreApp {
public:
    /** Parses the command line; returns false when there is nothing to run (e.g. --help). */
    bool initialize(int argc, const char* const* argv);
    /** Runs the experiment; returns the process exit code. Errors are printed to stderr. */
    int run();

    const eval::RunSummary& summary() const { return summary_; }
    const std::string& outputDir() const { return outputDir_; }

    static std::string usage();

private:
    int renderScene() const;

    std::string configPath_;
    std::vector<std::string> overrides_;
    std::string outputDir_;
    std::string renderSceneDir_;  ///< --render-scene: only render that run's scene to PNG
    bool quiet_ = false;
    RunProvenance invocation_;
    eval::RunSummary summary_;
};

}  // namespace daep::mission
