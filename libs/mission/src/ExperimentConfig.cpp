#include "daep/mission/ExperimentConfig.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "daep/common/Config.h"
#include "daep/common/Error.h"
#include "daep/common/IniText.h"
#include "daep/common/TracedConfig.h"

namespace daep::mission {
namespace {

/** defaults.ini first, then every other .ini file in share/daep/config (one per planner), sorted.
 */
std::vector<std::string> defaultFiles() {
    const std::filesystem::path dir = std::filesystem::path(shareDirectory()) / "config";
    const std::filesystem::path main = dir / "defaults.ini";
    if (!std::filesystem::is_regular_file(main))
        throw InputError(main.string() + ": default parameters not found (set DAEP_SHARE_DIR?)");
    std::vector<std::string> others;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().extension() == ".ini" && e.path() != main)
            others.push_back(e.path().string());
    std::sort(others.begin(), others.end());
    others.insert(others.begin(), main.string());
    return others;
}

}  // namespace

struct ExperimentConfig::Impl {
    TracedConfig memory;
};

ExperimentConfig::ExperimentConfig() : impl_(std::make_unique<Impl>()) {}
ExperimentConfig::ExperimentConfig(ExperimentConfig&&) noexcept = default;
ExperimentConfig::~ExperimentConfig() = default;

const std::vector<std::string>& ExperimentConfig::requiredExperimentKeys() {
    static const std::vector<std::string> keys = {"world", "mode",       "planner",      "start",
                                                  "seed",  "max_time_s", "planning_time"};
    return keys;
}

const mrpt::config::CConfigFileBase& ExperimentConfig::config() const {
    return impl_->memory;
}

void ExperimentConfig::set(const std::string& section, const std::string& key,
                           const std::string& value, const std::string& where) {
    auto sec = std::find_if(sections_.begin(), sections_.end(),
                            [&](const Section& s) { return s.name == section; });
    if (sec == sections_.end()) {
        sections_.push_back({section, {}});
        sec = std::prev(sections_.end());
    }
    auto entry = std::find_if(sec->entries.begin(), sec->entries.end(),
                              [&](const Entry& e) { return e.first == key; });
    if (entry == sec->entries.end())
        sec->entries.emplace_back(key, value);
    else
        entry->second = value;
    impl_->memory.write(section, key, value);
    impl_->memory.setOrigin(section, key, where);
}

ExperimentConfig ExperimentConfig::fromFile(const std::string& path,
                                            const std::vector<std::string>& overrides) {
    const std::string file = resolveDataPath(path);
    return fromText(readTextFile(file), file, overrides);
}

ExperimentConfig ExperimentConfig::fromText(const std::string& text, const std::string& source,
                                            const std::vector<std::string>& overrides) {
    ExperimentConfig cfg;
    cfg.source_ = source;
    std::map<std::string, std::vector<std::string>> known;
    for (const auto& path : defaultFiles()) {
        for (const auto& l : parseIniText(readTextFile(path), path).entries) {
            auto& keys = known[l.section];
            if (std::count(keys.begin(), keys.end(), l.key))
                throw InputError(path + ":" + std::to_string(l.line) + ": [" + l.section + "] " +
                                 l.key + " is already defined by another defaults file");
            cfg.set(l.section, l.key, l.value, path + ":" + std::to_string(l.line));
            keys.push_back(l.key);
        }
    }
    const auto checkKnown = [&](const std::string& where, const std::string& section,
                                const std::string& key) {
        const auto sec = known.find(section);
        if (sec == known.end()) {
            std::string valid;
            for (const auto& [name, keys] : known)
                valid += (valid.empty() ? "" : ", ") + name;
            throw InputError(where + "unknown section [" + section + "] (valid: " + valid + ")");
        }
        const bool isRequired =
            section == "experiment" &&
            std::count(requiredExperimentKeys().begin(), requiredExperimentKeys().end(), key);
        if (!isRequired && std::count(sec->second.begin(), sec->second.end(), key) == 0) {
            std::string valid;
            for (const auto& k : sec->second)
                valid += (valid.empty() ? "" : ", ") + k;
            if (section == "experiment")
                for (const auto& k : requiredExperimentKeys())
                    valid += ", " + k;
            throw InputError(where + "unknown key '" + key + "' in [" + section +
                             "] (valid: " + valid + ")");
        }
    };
    std::vector<std::string> given;
    for (const auto& l : parseIniText(text, source).entries) {
        const std::string where = source + ":" + std::to_string(l.line);
        checkKnown(where + ": ", l.section, l.key);
        cfg.set(l.section, l.key, l.value, where);
        if (l.section == "experiment")
            given.push_back(l.key);
    }
    for (const auto& o : overrides) {
        const auto dot = o.find('.');
        const auto eq = o.find('=');
        if (dot == std::string::npos || eq == std::string::npos || dot > eq)
            throw InputError("--set " + o + ": expected section.key=value");
        const std::string section = trimBlanks(o.substr(0, dot));
        const std::string key = trimBlanks(o.substr(dot + 1, eq - dot - 1));
        checkKnown("--set " + o + ": ", section, key);
        cfg.set(section, key, trimBlanks(o.substr(eq + 1)), "--set " + section + "." + key);
        if (section == "experiment")
            given.push_back(key);
    }
    for (const auto& key : requiredExperimentKeys())
        if (std::count(given.begin(), given.end(), key) == 0)
            throw InputError(source + ": [experiment] " + key + ": required key is missing");
    return cfg;
}

std::string ExperimentConfig::dump() const {
    std::ostringstream out;
    for (const auto& sec : sections_) {
        out << "[" << sec.name << "]\n";
        for (const auto& [key, value] : sec.entries)
            out << key << " = " << value << "\n";
        out << "\n";
    }
    return out.str();
}

}  // namespace daep::mission
