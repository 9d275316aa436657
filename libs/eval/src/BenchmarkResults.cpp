#include "daep/eval/BenchmarkResults.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "BenchmarkFigures.h"
#include "RunSeries.h"
#include "daep/common/BuildInfo.h"
#include "daep/common/Error.h"
#include "daep/eval/Plot.h"
#include "daep/eval/RunRecorder.h"
#include "daep/eval/Statistics.h"

namespace fs = std::filesystem;

namespace daep::eval {

namespace {

const std::string kProvenancePrefix = "provenance.";
using detail::coverageAt;
using detail::readCollisionEpisodes;
using detail::readTimeseries;
using detail::Series;
using detail::spansOf;

const std::set<std::string> kLabelKeys = {"world", "mode", "planner", "start", "seed"};
const std::vector<std::string> kMetricOrder = {
    "coverage_percent", "reachable_percent", "exploration_time_s",
    "path_length_m",    "planning_time_s",   "plan_ms_median",
    "plan_ms_p95",      "collisions",        "static_collisions",
    "iterations",       "aborted_paths",     "hover_evasions",
    "stale_plans",      "finished",          "end_reason",
    "known_volume_m3",  "box_volume_m3",     "exploration_start_s",
    "wall_time_s"};

/** results.csv's provenance columns: the fields that can differ between the runs of a benchmark. */
struct ProvenanceColumn {
    const char* name;
    const char* key;  ///< in summary.json's "provenance"
};
const ProvenanceColumn kProvenanceColumns[] = {
    {"version", "version"},     {"git_commit", "git_commit"},
    {"git_dirty", "git_dirty"}, {"build_type", "build_type"},
    {"host", "host"},           {"date_utc", "date_utc"}};

/** The table rows: label, summary key, whether higher is better. */
struct RowDef {
    const char* label;
    const char* key;
    bool higherIsBetter;
};
const RowDef kRows[] = {{"C %", "coverage_percent", true},
                        {"T s", "exploration_time_s", false},
                        {"PL m", "path_length_m", false},
                        {"PT s", "planning_time_s", false},
                        {"NOC", "collisions", false}};

std::string readText(const fs::path& p) {
    std::ifstream in(p);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos)
        return s;
    std::string out = "\"";
    for (char c : s)
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string format2(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f", v);
    return buf;
}

double sampleStddev(const std::vector<double>& v) {
    if (v.size() < 2)
        return 0.0;
    const double m = mean(v);
    double sum = 0.0;
    for (double x : v)
        sum += (x - m) * (x - m);
    return std::sqrt(sum / (v.size() - 1));
}

std::string displayName(const std::string& planner) {
    if (planner == "rhnbvp")
        return "RH-NBVP";
    std::string out = planner;
    for (char& c : out)
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

/**
 * nlohmann's SAX events to (key, text) pairs: nested objects' members get dotted keys
 * ("provenance.git_commit"), array elements "[i]"; numbers keep their text as written.
 */
class FlatJsonCollector : public nlohmann::json_sax<nlohmann::json> {
public:
    bool null() override { return add("null"); }
    bool boolean(bool value) override { return add(value ? "true" : "false"); }
    bool number_integer(number_integer_t value) override { return add(std::to_string(value)); }
    bool number_unsigned(number_unsigned_t value) override { return add(std::to_string(value)); }
    bool number_float(number_float_t, const string_t& text) override { return add(text); }
    bool string(string_t& value) override { return add(value); }
    bool binary(binary_t&) override { throw std::runtime_error("JSON: unexpected binary value"); }
    bool start_object(std::size_t) override {
        frames_.push_back({frames_.empty() ? "" : nextName() + ".", false, 0, ""});
        return true;
    }
    bool key(string_t& name) override {
        frames_.back().key = name;
        return true;
    }
    bool end_object() override { return pop(); }
    bool start_array(std::size_t) override {
        if (frames_.empty())
            throw std::runtime_error("JSON: expected an object, found an array");
        frames_.push_back({nextName(), true, 0, ""});
        return true;
    }
    bool end_array() override { return pop(); }
    bool parse_error(std::size_t, const std::string&,
                     const nlohmann::detail::exception& error) override {
        throw std::runtime_error(std::string("JSON: ") + error.what());
    }

    std::vector<std::pair<std::string, std::string>> take() { return std::move(pairs_); }

private:
    struct Frame {
        std::string prefix;
        bool isArray;
        int index;
        std::string key;
    };

    std::string nextName() {
        Frame& f = frames_.back();
        return f.isArray ? f.prefix + "[" + std::to_string(f.index++) + "]" : f.prefix + f.key;
    }
    bool add(std::string value) {
        if (frames_.empty())
            throw std::runtime_error("JSON: expected an object");
        pairs_.emplace_back(nextName(), std::move(value));
        return true;
    }
    bool pop() {
        frames_.pop_back();
        return true;
    }

    std::vector<Frame> frames_;
    std::vector<std::pair<std::string, std::string>> pairs_;
};

std::vector<std::string> writeCoveragePlot(
    const std::string& world, const std::string& mode,
    const std::vector<std::pair<std::string, std::vector<Series>>>& byPlanner,
    const std::vector<std::string>& allPlanners, const std::string& stem) {
    double end = 0.0;
    for (const auto& [planner, runs] : byPlanner)
        for (const auto& s : runs)
            if (!s.t.empty())
                end = std::max(end, s.t.back());
    Plot plot(900, 520);
    plot.setTitle("Coverage over time: " + world + " (" + mode + ")");
    plot.setXLabel("time [s]");
    plot.setYLabel("coverage [%]");
    plot.setYRange(0.0, 100.0);
    plot.setLegendCorner(LegendCorner::BottomRight);  // coverage rises from the bottom left
    for (std::size_t p = 0; p < byPlanner.size(); ++p) {
        const auto& runs = byPlanner[p].second;
        std::vector<double> t, mu, lo, hi;
        for (double x = 0.0; x <= end + 1e-9; x += 1.0) {
            std::vector<double> v;
            for (const auto& s : runs)
                v.push_back(coverageAt(s, x));
            t.push_back(x);
            mu.push_back(mean(v));
            lo.push_back(*std::min_element(v.begin(), v.end()));
            hi.push_back(*std::max_element(v.begin(), v.end()));
        }
        // Colour by the planner's place among all planners, the same in every figure.
        const auto index = std::find(allPlanners.begin(), allPlanners.end(), byPlanner[p].first);
        const Rgb color = seriesColor(static_cast<std::size_t>(index - allPlanners.begin()));
        plot.addBand(t, lo, hi, color, 0.22);
        plot.addLine(t, mu, color,
                     displayName(byPlanner[p].first) + " (" + std::to_string(runs.size()) +
                         (runs.size() == 1 ? " run)" : " runs)"));
    }
    return plot.saveAs(stem);
}

std::vector<std::string> writeCollisionPlot(const RunResult& run, const std::string& stem) {
    const Series s = readTimeseries(fs::path(run.directory) / "timeseries.csv");
    const auto spans = spansOf(readCollisionEpisodes(
        fs::path(run.directory) / "collisions.csv", run.metric("exploration_start_s"),
        s.t.empty() ? run.metric("exploration_time_s") : s.t.back()));
    Plot plot(900, 360);
    plot.setTitle("Collisions: " + displayName(run.spec.planner) + ", " + run.spec.world + " (" +
                  run.spec.mode + "), start " + std::to_string(run.spec.start) + ", rep " +
                  std::to_string(run.spec.repetition) + ": " + std::to_string(spans.size()) +
                  (spans.size() == 1 ? " collision" : " collisions"));
    plot.setXLabel("time [s]");
    plot.setYLabel("coverage [%]");
    plot.setYRange(0.0, 100.0);
    plot.addLine(s.t, s.coverage, seriesColor(0), "coverage");
    plot.addIntervals(spans, {255, 140, 0}, "collision ongoing");
    return plot.saveAs(stem);
}

}  // namespace

std::string RunResult::provenanceValue(const std::string& key) const {
    for (const auto& [k, v] : provenance)
        if (k == key)
            return v;
    return "";
}

std::string buildDescription(const RunResult& run) {
    std::string text = "daep " + run.build() + " (" + run.provenanceValue("build_type") + ", " +
                       run.provenanceValue("compiler");
    const std::string sanitizers = run.provenanceValue("sanitizers");
    if (!sanitizers.empty())
        text += ", sanitizers " + sanitizers;
    std::string libraries;
    for (const auto& [key, version] : run.provenance)
        if (key.rfind("libraries.", 0) == 0)
            libraries += (libraries.empty() ? "" : ", ") + key.substr(10) + " " + version;
    return text + (libraries.empty() ? "" : "; " + libraries) + ")";
}

std::string RunResult::build() const {
    const std::string commit = provenanceValue("git_commit");
    if (commit.empty())
        return "";
    return provenanceValue("version") + " " + commit.substr(0, 7) +
           (provenanceValue("git_dirty") == "true" ? "-dirty" : "");
}

double RunResult::metric(const std::string& key, double fallback) const {
    for (const auto& [k, v] : metrics)
        if (k == key) {
            if (v == "true")
                return 1.0;
            if (v == "false")
                return 0.0;
            char* end = nullptr;
            const double d = std::strtod(v.c_str(), &end);
            return end != v.c_str() ? d : fallback;
        }
    return fallback;
}

namespace {

nlohmann::ordered_json inputFiles(const RunInputs& inputs) {
    nlohmann::ordered_json files = nlohmann::ordered_json::object();
    for (const auto& [name, digest] : inputs.files)
        files[name] = digest;
    return files;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> parseFlatJson(const std::string& text) {
    FlatJsonCollector collector;
    nlohmann::json::sax_parse(text, &collector);
    return collector.take();
}

void writeRunSpec(const std::string& runDirectory, const RunSpec& spec, int loadThreads) {
    fs::create_directories(runDirectory);
    const BuildInfo& build = buildInfo();
    const nlohmann::ordered_json json = {{"world", spec.world},
                                         {"mode", spec.mode},
                                         {"planner", spec.planner},
                                         {"start", spec.start},
                                         {"repetition", spec.repetition},
                                         {"seed", spec.seed},
                                         {"params_digest", spec.inputs.digest},
                                         {"input_files", inputFiles(spec.inputs)},
                                         {"launched_by",
                                          {{"version", build.version},
                                           {"git_commit", build.gitCommit},
                                           {"git_dirty", build.gitDirty},
                                           {"cpu_load_threads", loadThreads}}}};
    std::ofstream out(fs::path(runDirectory) / kRunSpecFile);
    out << json.dump(2) << "\n";
    if (!out)
        throw std::runtime_error("cannot write " +
                                 (fs::path(runDirectory) / kRunSpecFile).string());
}

RunResult readRun(const std::string& runDirectory) {
    const fs::path dir(runDirectory);
    RunResult r;
    r.directory = runDirectory;
    r.log = (dir / kRunLogFile).string();
    const auto specFile = dir / kRunSpecFile;
    if (!fs::exists(specFile))
        throw std::runtime_error("no " + specFile.string());
    const auto spec = parseFlatJson(readText(specFile));
    auto get = [&](const char* key) {
        for (const auto& [k, v] : spec)
            if (k == key)
                return v;
        throw std::runtime_error(specFile.string() + ": no \"" + std::string(key) + "\"");
    };
    r.spec = {get("world"),
              get("mode"),
              get("planner"),
              std::stoi(get("start")),
              std::stoi(get("repetition")),
              std::stoi(get("seed")),
              {}};
    for (const auto& [k, v] : spec)
        if (k == "params_digest")
            r.spec.inputs.digest = v;
        else if (k.rfind("input_files.", 0) == 0)
            r.spec.inputs.files.emplace_back(k.substr(12), v);
        else if (k == "launched_by.cpu_load_threads")
            r.loadThreads = std::atoi(v.c_str());

    const auto exitFile = dir / kExitCodeFile;
    const bool hasExit = fs::exists(exitFile);
    if (hasExit)
        r.exitCode = std::atoi(readText(exitFile).c_str());
    const auto summary = dir / "summary.json";
    if (fs::exists(summary)) {
        try {
            for (auto& [key, value] : parseFlatJson(readText(summary))) {
                if (key.rfind(kProvenancePrefix, 0) == 0)
                    r.provenance.emplace_back(key.substr(kProvenancePrefix.size()), value);
                else if (!kLabelKeys.count(key))
                    r.metrics.emplace_back(key, value);
            }
        } catch (const std::runtime_error&) {
            r.metrics.clear();
            r.provenance.clear();
        }
    }
    if (!hasExit)
        r.status = r.metrics.empty() ? "pending" : "ok";  // ok: run by an external engine
    else if (r.exitCode == 130)
        r.status = "pending";  // interrupted; the next invocation runs it again
    else
        r.status = r.exitCode == 0 && !r.metrics.empty() ? "ok" : "failed";
    return r;
}

std::vector<RunResult> readRuns(const std::string& benchmarkDirectory) {
    std::vector<RunResult> runs;
    const fs::path root = fs::path(benchmarkDirectory) / "runs";
    if (!fs::is_directory(root))
        return runs;
    for (const auto& entry : fs::directory_iterator(root))
        if (entry.is_directory() && fs::exists(entry.path() / kRunSpecFile))
            runs.push_back(readRun(entry.path().string()));
    std::sort(runs.begin(), runs.end(),
              [](const RunResult& a, const RunResult& b) { return a.directory < b.directory; });
    return runs;
}

void writeResultsCsv(const std::vector<RunResult>& runs, const std::string& path) {
    std::vector<std::string> keys = kMetricOrder;
    for (const auto& r : runs)
        for (const auto& kv : r.metrics)
            if (std::find(keys.begin(), keys.end(), kv.first) == keys.end())
                keys.push_back(kv.first);
    std::ofstream out(path);
    out << "world,mode,planner,start,repetition,seed,status,exit_code,log";
    for (const auto& k : keys)
        out << ',' << k;
    for (const auto& column : kProvenanceColumns)
        out << ',' << column.name;
    out << ",cpu_load_threads,params_digest\n";
    for (const auto& r : runs) {
        out << csvField(r.spec.world) << ',' << r.spec.mode << ',' << csvField(r.spec.planner)
            << ',' << r.spec.start << ',' << r.spec.repetition << ',' << r.spec.seed << ','
            << r.status << ',' << (r.exitCode >= 0 ? std::to_string(r.exitCode) : "") << ','
            << csvField(r.log);
        for (const auto& k : keys) {
            const auto it = std::find_if(r.metrics.begin(), r.metrics.end(),
                                         [&k](const auto& kv) { return kv.first == k; });
            out << ',' << (it == r.metrics.end() ? "" : csvField(it->second));
        }
        for (const auto& column : kProvenanceColumns)
            out << ',' << csvField(r.provenanceValue(column.key));
        out << ',' << r.loadThreads << ',' << r.spec.inputs.digest << '\n';
    }
    if (!out)
        throw std::runtime_error("cannot write " + path);
}

std::string ResultTable::markdown() const {
    std::ostringstream out;
    out << "|      |";
    for (const auto& p : planners)
        out << ' ' << displayName(p) << " |";
    out << "\n|---|";
    for (std::size_t i = 0; i < planners.size(); ++i)
        out << "---|";
    out << '\n';
    for (std::size_t r = 0; r < rows.size(); ++r) {
        out << "| **" << rows[r] << "** |";
        for (std::size_t p = 0; p < planners.size(); ++p) {
            const TableCell& c = cells[r][p];
            if (c.worlds == 0) {
                out << " - |";
                continue;
            }
            const std::string m = format2(c.mean);
            // Ties at the printed precision are all bold.
            const bool bold = best[r] >= 0 && m == format2(cells[r][best[r]].mean);
            out << ' ' << (bold ? "**" + m + "**" : m) << " ± " << format2(c.stddev) << " |";
        }
        out << '\n';
    }
    return out.str();
}

std::vector<ResultTable> buildTables(const std::vector<RunResult>& runs,
                                     const std::vector<std::string>& plannerOrder) {
    std::vector<std::string> modes, planners = plannerOrder;
    for (const auto& r : runs) {
        if (r.status != "ok")
            continue;
        if (std::find(modes.begin(), modes.end(), r.spec.mode) == modes.end())
            modes.push_back(r.spec.mode);
        if (std::find(planners.begin(), planners.end(), r.spec.planner) == planners.end())
            planners.push_back(r.spec.planner);
    }
    std::vector<ResultTable> tables;
    for (const auto& mode : modes) {
        ResultTable t;
        t.mode = mode;
        t.planners = planners;
        for (const auto& row : kRows) {
            t.rows.push_back(row.label);
            std::vector<TableCell> cells;
            int best = -1;
            for (const auto& planner : planners) {
                std::map<std::string, std::vector<double>> perWorld;
                for (const auto& r : runs)
                    if (r.status == "ok" && r.spec.mode == mode && r.spec.planner == planner)
                        perWorld[r.spec.world].push_back(r.metric(row.key));
                std::vector<double> worldMeans;
                for (const auto& [world, values] : perWorld)
                    worldMeans.push_back(mean(values));
                TableCell c{mean(worldMeans), sampleStddev(worldMeans),
                            static_cast<int>(worldMeans.size())};
                const bool better = best < 0 || (row.higherIsBetter ? c.mean > cells[best].mean
                                                                    : c.mean < cells[best].mean);
                if (c.worlds > 0 && better)
                    best = static_cast<int>(cells.size());
                cells.push_back(c);
            }
            t.cells.push_back(std::move(cells));
            t.best.push_back(best);
        }
        tables.push_back(std::move(t));
    }
    return tables;
}

std::string perWorldMarkdown(const std::vector<RunResult>& runs, const std::string& mode,
                             const std::vector<std::string>& planners) {
    std::set<std::string> worlds;
    for (const auto& r : runs)
        if (r.status == "ok" && r.spec.mode == mode)
            worlds.insert(r.spec.world);
    std::ostringstream out;
    out << "| world | planner | runs | C % | C / reachable % | T s | NOC | static |\n"
        << "|---|---|---|---|---|---|---|---|\n";
    for (const auto& world : worlds) {
        for (const auto& planner : planners) {
            std::vector<double> c, share, t, noc, statics;
            for (const auto& r : runs) {
                if (r.status != "ok" || r.spec.mode != mode || r.spec.world != world ||
                    r.spec.planner != planner)
                    continue;
                c.push_back(r.metric("coverage_percent"));
                const double reach = r.metric("reachable_percent");
                if (reach > 0.0)
                    share.push_back(100.0 * c.back() / reach);
                t.push_back(r.metric("exploration_time_s"));
                noc.push_back(r.metric("collisions"));
                statics.push_back(r.metric("static_collisions"));
            }
            if (c.empty())
                continue;
            out << "| " << world << " | " << displayName(planner) << " | " << c.size() << " | "
                << format2(mean(c)) << " | " << (share.empty() ? "-" : format2(mean(share)))
                << " | " << format2(mean(t)) << " | " << format2(mean(noc)) << " | "
                << format2(mean(statics)) << " |\n";
        }
    }
    return out.str();
}

std::vector<std::string> writePlots(const std::vector<RunResult>& runs,
                                    const std::string& plotDirectory) {
    std::vector<std::string> written;
    auto add = [&written](const std::vector<std::string>& paths) {
        written.insert(written.end(), paths.begin(), paths.end());
    };
    // (world, mode) -> planner -> runs, in run order.
    std::vector<std::pair<std::pair<std::string, std::string>,
                          std::vector<std::pair<std::string, std::vector<const RunResult*>>>>>
        groups;
    std::map<std::string, const RunResult*> bestRun;  // planner_world_mode -> highest coverage
    std::vector<std::string> planners;
    for (const auto& r : runs) {
        if (r.status != "ok")
            continue;
        if (std::find(planners.begin(), planners.end(), r.spec.planner) == planners.end())
            planners.push_back(r.spec.planner);
        const auto key = std::make_pair(r.spec.world, r.spec.mode);
        auto g = std::find_if(groups.begin(), groups.end(),
                              [&key](const auto& e) { return e.first == key; });
        if (g == groups.end())
            g = groups.insert(groups.end(), {key, {}});
        auto p = std::find_if(g->second.begin(), g->second.end(),
                              [&r](const auto& e) { return e.first == r.spec.planner; });
        if (p == g->second.end())
            p = g->second.insert(g->second.end(), {r.spec.planner, {}});
        p->second.push_back(&r);
        const std::string id = r.spec.planner + "_" + r.spec.world + "_" + r.spec.mode;
        const RunResult*& best = bestRun[id];
        if (!best || r.metric("coverage_percent") > best->metric("coverage_percent"))
            best = &r;
    }
    // Colour by the planner's place among all planners, the same in every figure.
    auto colorOf = [&planners](const std::string& planner) {
        const auto index = std::find(planners.begin(), planners.end(), planner);
        return seriesColor(static_cast<std::size_t>(index - planners.begin()));
    };
    for (const auto& [key, byPlanner] : groups) {
        const std::string name = key.first + "_" + key.second;
        std::vector<std::pair<std::string, std::vector<Series>>> series;
        std::vector<detail::PlannerRuns> fig4;
        for (const auto& [planner, plannerRuns] : byPlanner) {
            series.push_back({planner, {}});
            for (const RunResult* r : plannerRuns)
                series.back().second.push_back(
                    readTimeseries(fs::path(r->directory) / "timeseries.csv"));
            fig4.push_back({displayName(planner), colorOf(planner), plannerRuns});
        }
        add(writeCoveragePlot(key.first, key.second, series, planners,
                              (fs::path(plotDirectory) / ("coverage_" + name)).string()));
        add(detail::writeFig4(key.first, key.second, fig4,
                              (fs::path(plotDirectory) / ("fig4_" + name)).string()));
    }
    for (const auto& [id, run] : bestRun)
        add(writeCollisionPlot(*run, (fs::path(plotDirectory) / ("collisions_" + id)).string()));
    return written;
}

namespace {

/** What ran beside the runs, when daep-benchmark --load kept cores busy for any of them. */
std::string loadMarkdown(const std::map<int, int>& okRunsByLoad) {
    if (okRunsByLoad.empty() || (okRunsByLoad.size() == 1 && okRunsByLoad.begin()->first == 0))
        return "";
    std::ostringstream out;
    out << "\n**Under load** (`daep-benchmark --load N`: N threads kept busy beside the runs): ";
    bool first = true;
    for (const auto& [threads, n] : okRunsByLoad) {
        out << (first ? "" : ", ") << n << " run" << (n == 1 ? "" : "s") << " with " << threads
            << " busy thread" << (threads == 1 ? "" : "s");
        first = false;
    }
    out << ".\n";
    return out.str();
}

}  // namespace

std::string provenanceMarkdown(const std::vector<RunResult>& runs) {
    // Build description -> runs made by it, in first-seen order; the same for hosts.
    std::vector<std::pair<std::string, int>> builds, hosts;
    auto count = [](std::vector<std::pair<std::string, int>>& list, const std::string& key) {
        auto it = std::find_if(list.begin(), list.end(),
                               [&key](const auto& e) { return e.first == key; });
        if (it == list.end())
            list.emplace_back(key, 1);
        else
            ++it->second;
    };
    std::string first, last;
    std::size_t unknown = 0;
    std::map<int, int> loads;  // busy threads beside the run -> ok runs
    for (const auto& r : runs) {
        if (r.status == "ok")
            ++loads[r.loadThreads];
        if (r.provenance.empty()) {
            unknown += r.status == "ok";
            continue;
        }
        count(builds, buildDescription(r));
        count(hosts, r.provenanceValue("host"));
        const std::string date = r.provenanceValue("date_utc");
        if (!date.empty() && (first.empty() || date < first))
            first = date;
        last = std::max(last, date);
    }
    std::ostringstream out;
    if (builds.size() > 1)
        out << "**Mixed builds**: these runs were made by " << builds.size()
            << " different builds (see the git_commit column of results.csv):\n\n";
    for (const auto& [build, n] : builds)
        out << (builds.size() > 1 ? "- " : "Made by ") << build << " (" << n << " run"
            << (n == 1 ? "" : "s") << ")\n";
    if (unknown > 0)
        out << (builds.empty() ? "" : "\n") << unknown
            << " ok runs record no build (made before daep recorded provenance).\n";
    if (!hosts.empty()) {
        out << "\nOn ";
        for (std::size_t i = 0; i < hosts.size(); ++i)
            out << (i ? ", " : "") << hosts[i].first << " (" << hosts[i].second << ")";
        out << ", " << first << " to " << last << ". Aggregated by " << shortCommit() << ".\n";
    }
    out << loadMarkdown(loads);
    return out.str();
}

std::size_t aggregateBenchmark(const std::string& benchmarkDirectory,
                               const std::vector<std::string>& plannerOrder) {
    const fs::path dir = fs::absolute(benchmarkDirectory).lexically_normal();
    if (!fs::is_directory(dir))
        throw InputError(benchmarkDirectory + ": no such folder");
    const auto runs = readRuns(dir.string());
    if (runs.empty())
        throw InputError(benchmarkDirectory + ": no runs in this folder (no runs/*/" +
                         kRunSpecFile + ")");
    writeResultsCsv(runs, (dir / "results.csv").string());
    std::ofstream table(dir / "table.md");
    std::size_t ok = 0, failed = 0;
    for (const auto& r : runs)
        ok += r.status == "ok", failed += r.status == "failed";
    table << "# Benchmark results\n\n"
          << provenanceMarkdown(runs)
          << "\nMean ± std over worlds of the per-world mean of runs "
             "(paper Table I); best value in bold (highest C, lowest T, PL, PT, NOC). "
          << ok << " ok runs, " << failed << " failed, " << runs.size() - ok - failed
          << " pending.\n";
    for (const auto& t : buildTables(runs, plannerOrder)) {
        std::set<std::string> worlds;
        for (const auto& r : runs)
            if (r.status == "ok" && r.spec.mode == t.mode)
                worlds.insert(r.spec.world);
        std::string list;
        for (const auto& w : worlds)
            list += (list.empty() ? "" : ", ") + w;
        table << "\n## " << t.mode << " (" << worlds.size() << " worlds: " << list << ")\n\n"
              << t.markdown() << "\nPer world, means over the runs:\n\n"
              << perWorldMarkdown(runs, t.mode, t.planners);
    }
    if (!table)
        throw std::runtime_error("cannot write " + (dir / "table.md").string());
    writePlots(runs, (dir / "plots").string());
    return runs.size();
}

}  // namespace daep::eval
