#include "daep/eval/BenchmarkConfig.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include "daep/common/Error.h"
#include "daep/common/IniText.h"

namespace fs = std::filesystem;

namespace daep::eval {

namespace {

const std::vector<std::string> kBenchmarkKeys = {"planners",    "worlds", "modes",     "starts",
                                                 "repetitions", "seed",   "experiment"};
/** Far beyond any real experiment; more would only exhaust memory while expanding. */
constexpr std::uint64_t kMaxRuns = 1000000;
constexpr int kMaxListValues = 10000;

/** Set per run by the matrix, so [set] must not name them. */
const std::set<std::string> kMatrixKeys = {"experiment.world", "experiment.mode",
                                           "experiment.planner", "experiment.start",
                                           "experiment.seed"};

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> items;
    std::string item;
    for (char c : text + ",") {
        if (c != ',') {
            item += c;
            continue;
        }
        if (!trimBlanks(item).empty())
            items.push_back(trimBlanks(item));
        item.clear();
    }
    return items;
}

int parseInt(const std::string& text, const std::string& what) {
    std::size_t used = 0;
    int value = 0;
    try {
        value = std::stoi(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != text.size())
        throw InputError(what + ": '" + text + "' is not an integer");
    return value;
}

/** A value together with where it came from, for error messages. */
struct Entry {
    std::string value;
    std::string where;  ///< "file:line" or "--set benchmark.key"
};

class Parser {
public:
    explicit Parser(std::string path) : path_(std::move(path)) {}

    void read() {
        const IniText ini = parseIniText(readTextFile(path_), path_);
        for (const auto& header : ini.sections)
            if (header.name != "benchmark" && header.name != "set")
                throw InputError(path_ + ":" + std::to_string(header.line) + ": unknown section [" +
                                 header.name + "] (expected [benchmark] or [set])");
        for (const auto& e : ini.entries) {
            const std::string where = path_ + ":" + std::to_string(e.line);
            if (e.section == "benchmark")
                setBenchmark(e.key, e.value, where, false);
            else
                addSet(e.key, e.value, where);
        }
    }

    void override(const std::string& assignment) {
        const auto eq = assignment.find('=');
        const auto dot = assignment.find('.');
        if (eq == std::string::npos || dot == std::string::npos || dot > eq)
            throw InputError("--set " + assignment + ": expected section.key=value");
        const std::string key = trimBlanks(assignment.substr(0, eq));
        const std::string value = trimBlanks(assignment.substr(eq + 1));
        const std::string where = "--set " + key;
        if (key.compare(0, dot + 1, "benchmark.") == 0)
            setBenchmark(key.substr(dot + 1), value, where, true);
        else
            addSet(key, value, where);
    }

    BenchmarkConfig build() const {
        BenchmarkConfig cfg;
        cfg.source = path_;
        cfg.planners = list("planners");
        cfg.worlds = list("worlds");
        cfg.modes = list("modes");
        for (const auto& m : cfg.modes)
            if (m != "static" && m != "dynamic")
                fail("modes", "mode '" + m + "' is not static or dynamic");
        try {
            cfg.starts = parseIntList(require("starts").value);
        } catch (const InputError& e) {
            fail("starts", e.what());
        }
        cfg.repetitions = integer("repetitions");
        if (cfg.repetitions < 1)
            fail("repetitions", "must be at least 1");
        cfg.seed = integer("seed");
        if (cfg.seed > std::numeric_limits<int>::max() - (cfg.repetitions - 1))
            fail("seed", "seed + repetitions - 1 must fit an int");
        const std::uint64_t runs = std::uint64_t(cfg.planners.size()) * cfg.worlds.size() *
                                   cfg.modes.size() * cfg.starts.size() * cfg.repetitions;
        if (runs > kMaxRuns)
            fail("repetitions", "the matrix has " + std::to_string(runs) + " runs (at most " +
                                    std::to_string(kMaxRuns) + ")");
        cfg.experiment = experimentPath();
        cfg.sets = sets_;
        for (const auto& [key, entry] : values_)
            cfg.origins[key] = entry.where;
        cfg.origins.insert(setOrigins_.begin(), setOrigins_.end());
        return cfg;
    }

private:
    void setBenchmark(const std::string& key, const std::string& value, const std::string& where,
                      bool replace) {
        if (std::find(kBenchmarkKeys.begin(), kBenchmarkKeys.end(), key) == kBenchmarkKeys.end())
            throw InputError(where + ": unknown key [benchmark] " + key);
        if (!replace && values_.count(key))
            throw InputError(where + ": duplicate key [benchmark] " + key + " (first at " +
                             values_.at(key).where + ")");
        values_[key] = {value, where};
    }

    void addSet(const std::string& key, const std::string& value, const std::string& where) {
        const auto dot = key.find('.');
        if (dot == std::string::npos || dot == 0 || dot + 1 == key.size())
            throw InputError(where + ": [set] key '" + key + "' is not section.key");
        if (kMatrixKeys.count(key))
            throw InputError(where + ": " + key + " is set per run; use [benchmark] instead");
        setOrigins_[key] = where;
        for (auto& [k, v] : sets_)
            if (k == key) {
                v = value;
                return;
            }
        sets_.emplace_back(key, value);
    }

    const Entry& require(const std::string& key) const {
        const auto it = values_.find(key);
        if (it == values_.end())
            throw InputError(path_ + ": missing required key [benchmark] " + key);
        return it->second;
    }

    [[noreturn]] void fail(const std::string& key, const std::string& what) const {
        throw InputError(require(key).where + ": [benchmark] " + key + ": " + what);
    }

    std::vector<std::string> list(const std::string& key) const {
        auto items = splitList(require(key).value);
        if (items.empty())
            fail(key, "empty list");
        for (const auto& item : items)
            if (std::count(items.begin(), items.end(), item) > 1)
                fail(key, "'" + item + "' listed twice");
        return items;
    }

    int integer(const std::string& key) const {
        const Entry& entry = require(key);
        try {
            return parseInt(entry.value, "value");
        } catch (const InputError& e) {
            fail(key, e.what());
        }
    }

    std::string experimentPath() const {
        const fs::path given = require("experiment").value;
        if (given.empty())
            fail("experiment", "empty path");
        fs::path full = given.is_absolute() ? given : fs::path(path_).parent_path() / given;
        std::error_code ec;
        full = fs::weakly_canonical(fs::absolute(full), ec);
        if (ec || !fs::is_regular_file(full))
            fail("experiment", "no such file '" + full.string() + "'");
        return full.string();
    }

    std::string path_;
    std::map<std::string, Entry> values_;
    std::vector<std::pair<std::string, std::string>> sets_;
    std::map<std::string, std::string> setOrigins_;
};

std::string safeName(const std::string& s) {
    std::string out = s;
    for (char& c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '.')
            c = '-';
    return out;
}

}  // namespace

std::string RunSpec::id() const {
    return safeName(world) + "_" + safeName(mode) + "_" + safeName(planner) + "_s" +
           std::to_string(start) + "_r" + std::to_string(repetition);
}

std::vector<RunSpec> BenchmarkConfig::expand() const {
    std::vector<RunSpec> runs;
    for (const auto& world : worlds)
        for (const auto& mode : modes)
            for (const auto& planner : planners)
                for (int start : starts)
                    for (int rep = 0; rep < repetitions; ++rep)
                        runs.push_back({world, mode, planner, start, rep, seed + rep, {}});
    return runs;
}

std::vector<std::string> BenchmarkConfig::runOverrides(const RunSpec& run) const {
    std::vector<std::string> out;
    for (const auto& [key, value] : sets)
        out.push_back(key + "=" + value);
    out.push_back("experiment.world=" + run.world);
    out.push_back("experiment.mode=" + run.mode);
    out.push_back("experiment.planner=" + run.planner);
    out.push_back("experiment.start=" + std::to_string(run.start));
    out.push_back("experiment.seed=" + std::to_string(run.seed));
    return out;
}

std::string BenchmarkConfig::where(const std::string& key) const {
    const auto it = origins.find(key);
    return it == origins.end() ? source : it->second;
}

std::vector<int> parseIntList(const std::string& text) {
    std::vector<int> values;
    std::set<int> seen;
    const auto items = splitList(text);
    if (items.empty())
        throw InputError("empty list");
    for (const auto& item : items) {
        const auto dash = item.find('-', 1);
        const int lo = parseInt(trimBlanks(item.substr(0, dash)), "range");
        const int hi =
            dash == std::string::npos ? lo : parseInt(trimBlanks(item.substr(dash + 1)), "range");
        if (lo < 0 || hi < lo)
            throw InputError("bad range '" + item + "'");
        if (hi - lo >= kMaxListValues - static_cast<int>(values.size()))
            throw InputError("more than " + std::to_string(kMaxListValues) + " values");
        for (long long v = lo; v <= hi; ++v) {  // long long: hi may be INT_MAX
            if (!seen.insert(static_cast<int>(v)).second)
                throw InputError(std::to_string(v) + " listed twice");
            values.push_back(static_cast<int>(v));
        }
    }
    return values;
}

BenchmarkConfig loadBenchmarkConfig(const std::string& path,
                                    const std::vector<std::string>& overrides) {
    Parser parser(path);
    parser.read();
    for (const auto& o : overrides)
        parser.override(o);
    return parser.build();
}

}  // namespace daep::eval
