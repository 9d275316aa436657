#pragma once

#include <Eigen/Core>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "daep/common/Config.h"
#include "daep/common/Error.h"

namespace daep {

/** Range checks on top of ConfigReader; errors name "[section] key" like ConfigReader's own. */
[[noreturn]] inline void failRange(const ConfigReader& r, const std::string& key, double value,
                                   const std::string& what) {
    std::ostringstream os;
    os << r.where(key) << ": [" << r.section() << "] " << key << ": " << value << " " << what;
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
    if (!(v >= 0.0))
        failRange(r, key, v, "must be >= 0");
    return v;
}

/** The positive sizes `<prefix>_x`, `<prefix>_y`, `<prefix>_z` (a box's, a body's). */
inline Eigen::Vector3d requirePositiveXyz(const ConfigReader& r, const std::string& prefix) {
    const double x = requirePositive(r, prefix + "_x");
    const double y = requirePositive(r, prefix + "_y");
    return {x, y, requirePositive(r, prefix + "_z")};
}

/** A value strictly between lo and hi. */
inline double requireBetween(const ConfigReader& r, const std::string& key, double lo, double hi) {
    const double v = r.requireDouble(key);
    if (!(v > lo && v < hi)) {
        std::ostringstream os;
        os << "must be in (" << lo << ", " << hi << ")";
        failRange(r, key, v, os.str());
    }
    return v;
}

/** An integer in [lo, hi]. */
inline int requireIntBetween(const ConfigReader& r, const std::string& key, int lo, int hi) {
    const int v = r.requireInt(key);
    if (v < lo || v > hi)
        failRange(r, key, v, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
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

/** One of the listed words; the error names the key, the value and the words allowed. */
inline std::string requireOneOf(const ConfigReader& r, const std::string& key,
                                const std::vector<std::string>& allowed) {
    const std::string v = r.requireString(key);
    for (const std::string& a : allowed)
        if (v == a)
            return v;
    std::string list;
    for (std::size_t i = 0; i < allowed.size(); ++i)
        list += (i == 0 ? "" : i + 1 == allowed.size() ? " or " : ", ") + allowed[i];
    throw InputError(r.where(key) + ": [" + r.section() + "] " + key + ": '" + v + "' must be " +
                     list);
}

/**
 * An ini word read into an enum once, as MRPT's read_enum: `words` pairs each allowed word
 * with its value; any other word is an InputError naming the key and the allowed words.
 */
template <typename E>
E requireEnum(const ConfigReader& r, const std::string& key,
              const std::vector<std::pair<std::string, E>>& words) {
    std::vector<std::string> allowed;
    for (const auto& w : words)
        allowed.push_back(w.first);
    const std::string v = requireOneOf(r, key, allowed);
    for (const auto& w : words)
        if (w.first == v)
            return w.second;
    return words.front().second;  // not reached: requireOneOf threw
}

}  // namespace daep
