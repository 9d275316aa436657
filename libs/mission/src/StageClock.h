#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace daep::mission {

/** Wall seconds since `t0`. */
inline double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/** The parts of a simulated mission whose wall time timing.json reports. */
enum class Stage { Render, People, Map, World, Checks, Planning, Recording, Count };

/** Wall time per stage of a mission, charged by scopes around the calls of each stage. */
class StageClock {
public:
    /** Charges the wall time from its construction to its end to one stage. */
    class Scope {
    public:
        Scope(StageClock& clock, Stage stage)
            : clock_(clock), stage_(stage), start_(std::chrono::steady_clock::now()) {}
        ~Scope() {
            clock_.seconds_[std::size_t(stage_)] +=
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        }
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;

    private:
        StageClock& clock_;
        Stage stage_;
        std::chrono::steady_clock::time_point start_;
    };

    Scope time(Stage stage) { return Scope(*this, stage); }

    /** Seconds per stage by name, and "other": what of `total` no stage was charged. */
    std::vector<std::pair<std::string, double>> report(double total) const {
        static const char* const kNames[] = {"render", "people",   "map",      "world",
                                             "checks", "planning", "recording"};
        std::vector<std::pair<std::string, double>> out;
        double charged = 0.0;
        for (std::size_t i = 0; i < seconds_.size(); ++i) {
            out.emplace_back(kNames[i], seconds_[i]);
            charged += seconds_[i];
        }
        out.emplace_back("other", std::max(0.0, total - charged));
        return out;
    }

private:
    std::array<double, std::size_t(Stage::Count)> seconds_{};
};

}  // namespace daep::mission
