#include "daep/common/BuildInfo.h"

#include <unistd.h>

#include <array>
#include <cctype>
#include <ctime>

#include "daep_git_info.h"

namespace daep {

const BuildInfo& buildInfo() {
    static const BuildInfo info{DAEP_VERSION,
                                DAEP_GIT_COMMIT,
                                DAEP_GIT_DIRTY,
                                DAEP_BUILD_TYPE,
                                DAEP_COMPILER,
                                DAEP_SANITIZERS,
                                {{"MRPT", DAEP_MRPT_VERSION},
                                 {"OctoMap", DAEP_OCTOMAP_VERSION},
                                 {"Embree", DAEP_EMBREE_VERSION},
                                 {"OpenCV", DAEP_OPENCV_VERSION},
                                 {"Eigen", DAEP_EIGEN_VERSION},
                                 {"Assimp", DAEP_ASSIMP_VERSION}}};
    return info;
}

std::string shortCommit(const BuildInfo& info) {
    std::string s = info.gitCommit.substr(0, 7);
    if (info.gitDirty)
        s += "-dirty";
    return s;
}

std::string versionText(const std::string& app) {
    const BuildInfo& b = buildInfo();
    std::string text = app + " " + b.version + " (commit " + shortCommit(b) + ", " + b.buildType +
                       (b.sanitizers.empty() ? "" : ", sanitizers " + b.sanitizers) + ")\n";
    text += "  compiler  " + b.compiler + "\n  libraries";
    for (std::size_t i = 0; i < b.libraries.size(); ++i)
        text += (i ? ", " : " ") + b.libraries[i].first + " " + b.libraries[i].second;
    return text + "\n";
}

namespace {

bool needsQuoting(const std::string& arg) {
    if (arg.empty())
        return true;
    for (const char c : arg)
        if (!(std::isalnum(static_cast<unsigned char>(c)) ||
              std::string("-_./=:,+@%").find(c) != std::string::npos))
            return true;
    return false;
}

std::string quoted(const std::string& arg) {
    std::string out = "'";
    for (const char c : arg)
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

}  // namespace

std::string joinCommandLine(int argc, const char* const* argv) {
    std::string line;
    for (int i = 0; i < argc; ++i) {
        const std::string arg = argv[i] ? argv[i] : "";
        line += (i ? " " : "") + (needsQuoting(arg) ? quoted(arg) : arg);
    }
    return line;
}

RunProvenance runProvenance(int argc, const char* const* argv) {
    std::array<char, 256> host{};
    if (gethostname(host.data(), host.size() - 1) != 0)
        host[0] = '\0';
    const std::time_t now = std::time(nullptr);
    std::tm utc{};
    gmtime_r(&now, &utc);
    std::array<char, 32> date{};
    std::strftime(date.data(), date.size(), "%Y-%m-%dT%H:%M:%SZ", &utc);
    return {host.data(), date.data(), joinCommandLine(argc, argv)};
}

}  // namespace daep
