#pragma once

#include <string>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
}

namespace daep {

/**
 * Typed, strict access to an ini section. Missing required keys and unparsable
 * values throw InputError naming "[section] key" and the config's source.
 */
class ConfigReader {
public:
    ConfigReader(const mrpt::config::CConfigFileBase& cfg, std::string section,
                 std::string source = "config");

    bool has(const std::string& key) const;
    double requireDouble(const std::string& key) const;
    int requireInt(const std::string& key) const;
    bool requireBool(const std::string& key) const;
    std::string requireString(const std::string& key) const;

    double getDouble(const std::string& key, double fallback) const;
    int getInt(const std::string& key, int fallback) const;
    bool getBool(const std::string& key, bool fallback) const;
    std::string getString(const std::string& key, const std::string& fallback) const;

    /** Angles are written as `<key>_deg` in the ini; this returns radians. */
    double requireAngleDeg(const std::string& keyDeg) const;

    /**
     * Where the key's value was given, for error messages: "file:line" or "--set section.key"
     * when the config is a TracedConfig that knows, else the source given to the constructor.
     */
    std::string where(const std::string& key) const;

    const std::string& section() const { return section_; }
    const mrpt::config::CConfigFileBase& config() const { return cfg_; }

private:
    std::string raw(const std::string& key) const;
    [[noreturn]] void fail(const std::string& key, const std::string& what) const;

    const mrpt::config::CConfigFileBase& cfg_;
    std::string section_;
    std::string source_;
};

/**
 * Directory of built-in data (worlds, default configs, the shipped experiments and datasets):
 * PREFIX/share/daep for an installed PREFIX/bin/<app>, else $DAEP_SHARE_DIR, else the
 * source tree's share/daep.
 */
std::string shareDirectory();

/**
 * A relative path that does not exist from the working directory, looked up in the shipped
 * files: under shareDirectory() (installed: config-ini/, datasets/), then the source tree.
 * Returns `path` unchanged when found nowhere, so errors name what the user wrote.
 */
std::string resolveDataPath(const std::string& path);

}  // namespace daep
