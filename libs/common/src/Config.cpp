#include "daep/common/Config.h"

#include <mrpt/config/CConfigFileBase.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>

#include "daep/common/Error.h"
#include "daep/common/TracedConfig.h"

namespace daep {

ConfigReader::ConfigReader(const mrpt::config::CConfigFileBase& cfg, std::string section,
                           std::string source)
    : cfg_(cfg), section_(std::move(section)), source_(std::move(source)) {}

bool ConfigReader::has(const std::string& key) const {
    return cfg_.keyExists(section_, key);
}

std::string ConfigReader::where(const std::string& key) const {
    if (const auto* traced = dynamic_cast<const TracedConfig*>(&cfg_)) {
        std::string origin = traced->origin(section_, key);
        if (!origin.empty())
            return origin;
    }
    return source_;
}

void ConfigReader::fail(const std::string& key, const std::string& what) const {
    throw InputError(where(key) + ": [" + section_ + "] " + key + ": " + what);
}

std::string ConfigReader::raw(const std::string& key) const {
    if (!has(key))
        fail(key, "required key is missing");
    std::string v = cfg_.read_string(section_, key, "", false);
    const auto b = v.find_first_not_of(" \t");
    const auto e = v.find_last_not_of(" \t\r");
    return b == std::string::npos ? std::string() : v.substr(b, e - b + 1);
}

double ConfigReader::requireDouble(const std::string& key) const {
    const std::string v = raw(key);
    std::istringstream is(v);
    double d = 0;
    if (!(is >> d) || !is.eof() || !std::isfinite(d))
        fail(key, "'" + v + "' is not a number");
    return d;
}

int ConfigReader::requireInt(const std::string& key) const {
    const std::string v = raw(key);
    std::istringstream is(v);
    long long i = 0;
    if (!(is >> i) || !is.eof())
        fail(key, "'" + v + "' is not an integer");
    if (i < std::numeric_limits<int>::min() || i > std::numeric_limits<int>::max())
        fail(key, "'" + v + "' is out of range");
    return static_cast<int>(i);
}

bool ConfigReader::requireBool(const std::string& key) const {
    const std::string v = raw(key);
    if (v == "true" || v == "1" || v == "yes" || v == "on")
        return true;
    if (v == "false" || v == "0" || v == "no" || v == "off")
        return false;
    fail(key, "'" + v + "' is not a boolean (true|false)");
}

std::string ConfigReader::requireString(const std::string& key) const {
    const std::string v = raw(key);
    if (v.empty())
        fail(key, "value is empty");
    return v;
}

double ConfigReader::getDouble(const std::string& key, double fallback) const {
    return has(key) ? requireDouble(key) : fallback;
}
int ConfigReader::getInt(const std::string& key, int fallback) const {
    return has(key) ? requireInt(key) : fallback;
}
bool ConfigReader::getBool(const std::string& key, bool fallback) const {
    return has(key) ? requireBool(key) : fallback;
}
std::string ConfigReader::getString(const std::string& key, const std::string& fallback) const {
    return has(key) ? requireString(key) : fallback;
}

double ConfigReader::requireAngleDeg(const std::string& keyDeg) const {
    return requireDouble(keyDeg) * M_PI / 180.0;
}

namespace {

/** PREFIX/share/daep when this program is an installed PREFIX/bin/<app>; "" otherwise. */
std::string installedShareDirectory() {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec)
        return "";
    const fs::path share = exe.parent_path().parent_path() / "share" / "daep";
    return fs::is_regular_file(share / "config" / "defaults.ini", ec) ? share.string() : "";
}

}  // namespace

std::string shareDirectory() {
    static const std::string installed = installedShareDirectory();
    if (!installed.empty())
        return installed;
    if (const char* env = std::getenv("DAEP_SHARE_DIR"); env && *env)
        return env;
    return DAEP_SHARE_DIR;
}

std::string resolveDataPath(const std::string& path) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (path.empty() || fs::path(path).is_absolute() || fs::exists(path, ec))
        return path;
    for (const fs::path& root : {fs::path(shareDirectory()), fs::path(DAEP_SOURCE_ROOT)})
        if (fs::exists(root / path, ec))
            return (root / path).string();
    return path;
}

}  // namespace daep
