#pragma once

#include <unistd.h>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace daep::test {

/** The small world most end-to-end tests fly: a room with one walker. */
inline const std::string kTinyIni = std::string(DAEP_E2E_DATA) + "/tiny_room.ini";

struct AppResult {
    int exitCode = -1;
    std::string out;
    std::string err;
};

inline std::string readText(const std::filesystem::path& p) {
    std::ifstream f(p);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

/** A fresh, empty directory under the system temp dir, private to this process. */
inline std::filesystem::path freshDir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("daep_e2e_" + std::to_string(::getpid()) + "_" + name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/** Runs a binary with the arguments (already shell-quoted), capturing both streams. */
inline AppResult runApp(const std::string& binary, const std::string& args,
                        const std::filesystem::path& scratch) {
    const auto out = scratch / "stdout.txt";
    const auto err = scratch / "stderr.txt";
    const std::string cmd = binary + " " + args + " > " + out.string() + " 2> " + err.string();
    const int status = std::system(cmd.c_str());
    AppResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = readText(out);
    r.err = readText(err);
    return r;
}

inline AppResult runExplore(const std::string& args, const std::filesystem::path& scratch) {
    return runApp(DAEP_EXPLORE_BIN, args, scratch);
}

/**
 * summary.json without what legitimately differs between equal runs: the wall_time_s line and
 * the "provenance" block (date, host, command line, build).
 */
inline std::string deterministicSummaryText(const std::string& summary) {
    std::istringstream in(summary);
    std::string line, out;
    bool inProvenance = false;
    while (std::getline(in, line)) {
        if (line.find("\"provenance\": {") != std::string::npos)
            inProvenance = true;
        else if (!inProvenance && line.find("wall_time_s") == std::string::npos)
            out += line + "\n";
        else if (inProvenance && line == "  }")
            inProvenance = false;
    }
    return out;
}

/** The number after "key": in a flat JSON object; NaN if absent. */
inline double jsonNumber(const std::string& json, const std::string& key) {
    const auto at = json.find("\"" + key + "\":");
    if (at == std::string::npos)
        return std::nan("");
    return std::strtod(json.c_str() + at + key.size() + 3, nullptr);
}

}  // namespace daep::test
