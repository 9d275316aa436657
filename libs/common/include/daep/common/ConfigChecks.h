#pragma once

#include <sstream>
#include <string>

#include "daep/common/Config.h"
#include "daep/common/Error.h"

namespace daep {

/** Range checks on top of ConfigReader; errors name "[section] key" like ConfigReader's own. */
[[noreturn]] inline void failRange(const ConfigReader& r, const std::string& key, double value,
                                   const std::string& what) {
    std::ostringstream os;
    os << "config: [" << r.section() << "] " << key << ": " << value << " " << what;
    throw InputError(os.str());
}

inline double requirePositive(const ConfigReader& r, const std::string& key) {
    const double v = r.requireDouble(key);
    if (!(v > 0.0))
        failRange(r, key, v, "must be > 0");
    return v;
}

inline double requireNonNegative(const ConfigReader& r, const std::string& key) {
    const double v = r.requireDouble(key);
    if (v < 0.0)
        failRange(r, key, v, "must be >= 0");
    return v;
}

/** A value in (lo, hi]. */
inline double requireInRange(const ConfigReader& r, const std::string& key, double lo, double hi) {
    const double v = r.requireDouble(key);
    if (!(v > lo && v <= hi)) {
        std::ostringstream os;
        os << "must be in (" << lo << ", " << hi << "]";
        failRange(r, key, v, os.str());
    }
    return v;
}

inline int requireIntAtLeast(const ConfigReader& r, const std::string& key, int lo) {
    const int v = r.requireInt(key);
    if (v < lo)
        failRange(r, key, v, "must be >= " + std::to_string(lo));
    return v;
}

}  // namespace daep
