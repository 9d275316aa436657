#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "daep/common/BuildInfo.h"

namespace mrpt::config {
class CConfigFileBase;
}

namespace daep::mission {

/**
 * The effective parameters of one run: share/daep/config/defaults.ini, then the experiment
 * file, then `--set section.key=value` overrides. Keys unknown to defaults.ini are rejected
 * (typos), and the [experiment] keys without defaults must be given by the experiment file.
 * Errors are daep::InputError naming file:line and [section] key.
 */
class ExperimentConfig {
public:
    using Entry = std::pair<std::string, std::string>;
    struct Section {
        std::string name;
        std::vector<Entry> entries;
    };

    static ExperimentConfig fromFile(const std::string& path,
                                     const std::vector<std::string>& overrides = {});
    static ExperimentConfig fromText(const std::string& text, const std::string& source,
                                     const std::vector<std::string>& overrides = {});

    ExperimentConfig(ExperimentConfig&&) noexcept;
    ~ExperimentConfig();

    /** The merged config, for ConfigReader and the components' loaders. */
    const mrpt::config::CConfigFileBase& config() const;
    /** Where the experiment came from (file path or a label). */
    const std::string& source() const { return source_; }
    /** The merged parameters as ini text, in defaults.ini order. */
    std::string dump() const;

    /** How the run was started (host, date, command line), for the outputs' provenance. */
    const RunProvenance& invocation() const { return invocation_; }
    void setInvocation(RunProvenance invocation) { invocation_ = std::move(invocation); }

    /** [experiment] keys every experiment file must set. */
    static const std::vector<std::string>& requiredExperimentKeys();

private:
    ExperimentConfig();
    /** `where`: "file:line" or "--set section.key", named by errors about the value. */
    void set(const std::string& section, const std::string& key, const std::string& value,
             const std::string& where);

    struct Impl;
    std::unique_ptr<Impl> impl_;
    std::vector<Section> sections_;
    std::string source_;
    RunProvenance invocation_;
};

}  // namespace daep::mission
