#pragma once

#include <string>
#include <utility>
#include <vector>

namespace daep {

/** What built this program: embedded at build time, so every output can say which build made it. */
struct BuildInfo {
    std::string version;     ///< the project's version (CMake's PROJECT_VERSION)
    std::string gitCommit;   ///< full commit hash of the source tree, or "unknown" outside git
    bool gitDirty = false;   ///< tracked files differed from the commit when it was built
    std::string buildType;   ///< Release, Debug, ...
    std::string compiler;    ///< compiler id and version
    std::string sanitizers;  ///< "" or the -fsanitize list the build used
    /** Library name and version, in a fixed order: MRPT, OctoMap, Embree, OpenCV, Eigen, Assimp. */
    std::vector<std::pair<std::string, std::string>> libraries;
};

const BuildInfo& buildInfo();

/** "abc1234" or "abc1234-dirty": the short form for table headers and file names. */
std::string shortCommit(const BuildInfo& info = buildInfo());

/** The text an app prints for --version: its name, version, commit, compiler and libraries. */
std::string versionText(const std::string& app);

/** Where and when a run happened and how it was started; the part of provenance a build cannot
 * know. */
struct RunProvenance {
    std::string host;         ///< gethostname()
    std::string dateUtc;      ///< ISO 8601, e.g. 2026-12-02T02:16:33Z
    std::string commandLine;  ///< argv joined by spaces, arguments with spaces or quotes quoted
};

RunProvenance runProvenance(int argc, const char* const* argv);

/** argv as one shell-readable line: arguments with spaces, quotes or other specials single-quoted.
 */
std::string joinCommandLine(int argc, const char* const* argv);

}  // namespace daep
