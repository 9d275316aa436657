#pragma once
// Questions about a path that a user's file gave: std::filesystem's plain overloads throw
// filesystem_error for a name the system refuses (too long, say), which is bad input, not a
// failure of the program. These answer "no" instead, and the caller's "no such file" error
// names the path.

#include <filesystem>
#include <system_error>

namespace daep {

inline bool pathExists(const std::filesystem::path& p) noexcept {
    std::error_code ec;
    return std::filesystem::exists(p, ec);
}

inline bool isRegularFile(const std::filesystem::path& p) noexcept {
    std::error_code ec;
    return std::filesystem::is_regular_file(p, ec);
}

inline bool isDirectory(const std::filesystem::path& p) noexcept {
    std::error_code ec;
    return std::filesystem::is_directory(p, ec);
}

}  // namespace daep
