#pragma once
// Files of the mission tests: fresh scratch folders and the lines of an output.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace daep::test {

/** An empty folder of this process under the temporary folder. */
inline std::filesystem::path freshDir(const std::string& prefix, const std::string& name) {
    const std::filesystem::path d =
        std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()) + "_" + name);
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    return d;
}

inline std::vector<std::string> lines(const std::filesystem::path& p) {
    std::ifstream f(p);
    std::vector<std::string> out;
    for (std::string l; std::getline(f, l);)
        out.push_back(l);
    return out;
}

}  // namespace daep::test
