#include "BenchmarkFigures.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "RunSeries.h"
#include "daep/eval/Statistics.h"

namespace fs = std::filesystem;

namespace daep::eval::detail {
namespace {

constexpr Rgb kStaticContact{30, 30, 30};
constexpr int kWidth = 900;
constexpr int kCoverageHeight = 440;
constexpr int kRowHeight = 16;

struct RunData {
    const RunResult* run;
    Series coverage;
    std::vector<CollisionEpisode> collisions;
};

/** The statistics of coverage across runs, sampled on a common time grid. */
struct Envelope {
    std::vector<double> t, mean, meanMinusStd, meanPlusStd, min, max;
};

Envelope envelopeOf(const std::vector<const RunData*>& runs, double end) {
    Envelope e;
    const double step = std::max(1.0, std::ceil(end / 1000.0));
    for (double x = 0.0; x <= end + 1e-9; x += step) {
        std::vector<double> v;
        for (const RunData* r : runs)
            v.push_back(coverageAt(r->coverage, x));
        const double mu = mean(v);
        double var = 0.0;
        for (double c : v)
            var += (c - mu) * (c - mu);
        const double sd = v.size() > 1 ? std::sqrt(var / (v.size() - 1)) : 0.0;
        e.t.push_back(x);
        e.mean.push_back(mu);
        e.meanMinusStd.push_back(std::max(0.0, mu - sd));
        e.meanPlusStd.push_back(std::min(100.0, mu + sd));
        e.min.push_back(*std::min_element(v.begin(), v.end()));
        e.max.push_back(*std::max_element(v.begin(), v.end()));
    }
    return e;
}

Plot coveragePanel(const std::vector<PlannerRuns>& planners,
                   const std::vector<std::vector<RunData>>& data, double end) {
    Plot plot(kWidth, kCoverageHeight);
    plot.setTitle("Coverage over time");
    plot.setSubtitle(
        "line: mean over runs; dark band: mean \u00b1 1 std; light band: min\u2013max");
    plot.setYLabel("coverage [%]");
    plot.setXLabel("time [s]");
    plot.setXRange(0.0, end);
    plot.setYRange(0.0, 100.0);
    plot.setLegendCorner(LegendCorner::BottomRight);
    for (std::size_t p = 0; p < planners.size(); ++p) {
        std::vector<const RunData*> runs;
        for (const auto& d : data[p])
            runs.push_back(&d);
        const Envelope e = envelopeOf(runs, end);
        const Rgb color = planners[p].color;
        plot.addBand(e.t, e.min, e.max, color, 0.12);
        plot.addBand(e.t, e.meanMinusStd, e.meanPlusStd, color, 0.25);
        plot.addLine(e.t, e.mean, color,
                     planners[p].name + " (" + std::to_string(runs.size()) +
                         (runs.size() == 1 ? " run)" : " runs)"));
    }
    return plot;
}

std::string rowLabel(const std::string& planner, const RunData& d) {
    return planner + " s" + std::to_string(d.run->spec.start) + " r" +
           std::to_string(d.run->spec.repetition) + ": " + std::to_string(d.collisions.size());
}

Plot collisionPanel(const std::vector<PlannerRuns>& planners,
                    const std::vector<std::vector<RunData>>& data, double end) {
    std::size_t rows = 0;
    for (const auto& runs : data)
        rows += runs.size();
    Plot plot(kWidth, std::max(150, 110 + kRowHeight * static_cast<int>(rows)));
    plot.setTitle("Collision episodes");
    plot.setSubtitle(
        "one row per run: planner, start, repetition: collisions; a bar spans an "
        "episode from its start to its end");
    plot.setXLabel("time [s]");
    plot.setXRange(0.0, end);
    plot.setLegendCorner(LegendCorner::TopRight);
    bool anyStatic = false;
    for (std::size_t p = 0; p < planners.size(); ++p) {
        for (const auto& d : data[p]) {
            std::vector<std::pair<double, double>> people, statics;
            for (const auto& e : d.collisions)
                (e.person < 0 ? statics : people).emplace_back(e.start, e.end);
            plot.addTimelineRow(rowLabel(planners[p].name, d), people, planners[p].color);
            if (!statics.empty())
                plot.addTimelineSpans(statics, kStaticContact);
            anyStatic = anyStatic || !statics.empty();
        }
    }
    if (anyStatic)
        plot.addLegendEntry("static geometry", kStaticContact);
    return plot;
}

}  // namespace

std::vector<std::string> writeFig4(const std::string& world, const std::string& mode,
                                   const std::vector<PlannerRuns>& planners,
                                   const std::string& stem) {
    std::vector<std::vector<RunData>> data;
    double end = 1.0;
    for (const auto& p : planners) {
        data.emplace_back();
        for (const RunResult* r : p.runs) {
            const fs::path dir(r->directory);
            RunData d{r, readTimeseries(dir / "timeseries.csv"), {}};
            const double runEnd =
                d.coverage.t.empty() ? r->metric("exploration_time_s") : d.coverage.t.back();
            d.collisions = readCollisionEpisodes(dir / "collisions.csv",
                                                 r->metric("exploration_start_s"), runEnd);
            if (!d.coverage.t.empty())
                end = std::max(end, d.coverage.t.back());
            for (const auto& e : d.collisions)
                end = std::max(end, e.end);
            data.back().push_back(std::move(d));
        }
    }
    Figure figure(world + " (" + mode + ")");
    figure.addPanel(coveragePanel(planners, data, end));
    figure.addPanel(collisionPanel(planners, data, end));
    return figure.saveAs(stem);
}

}  // namespace daep::eval::detail
