#pragma once

#include <mrpt/config/CConfigFileMemory.h>

#include <map>
#include <string>
#include <utility>

namespace daep {

/**
 * An in-memory config that remembers where each value came from ("file:line" or
 * "--set section.key"), so that ConfigReader's errors blame the place the user must fix.
 * Include it only where such a config is built: MRPT's headers are slow.
 */
class TracedConfig : public mrpt::config::CConfigFileMemory {
public:
    void setOrigin(const std::string& section, const std::string& key, std::string where) {
        origins_[{section, key}] = std::move(where);
    }
    /** Where [section] key was last set; "" when not recorded. */
    std::string origin(const std::string& section, const std::string& key) const {
        const auto it = origins_.find({section, key});
        return it == origins_.end() ? std::string() : it->second;
    }

private:
    std::map<std::pair<std::string, std::string>, std::string> origins_;
};

}  // namespace daep
