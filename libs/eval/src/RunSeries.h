#pragma once

// Private to libs/eval: what the benchmark's plots read from a run directory.

#include <filesystem>
#include <utility>
#include <vector>

namespace daep::eval::detail {

/** timeseries.csv: coverage over exploration time. */
struct Series {
    std::vector<double> t, coverage;
};

/** collisions.csv: one episode; person -1 is static geometry. */
struct CollisionEpisode {
    int person = 0;
    double start = 0.0, end = 0.0;
};

/** Reads FILE's t and coverage columns; a missing file gives an empty series. */
Series readTimeseries(const std::filesystem::path& file);
/**
 * Reads FILE's episodes on the exploration clock of timeseries.csv: collisions.csv counts from
 * the spawn, so `explorationStart` (summary.json's exploration_start_s) is subtracted (episodes
 * during the climb start at 0), and an episode still ongoing at the end (end -1) ends at
 * `explorationEnd`. A missing file gives none.
 */
std::vector<CollisionEpisode> readCollisionEpisodes(const std::filesystem::path& file,
                                                    double explorationStart, double explorationEnd);
/** The episodes' [start, end] spans. */
std::vector<std::pair<double, double>> spansOf(const std::vector<CollisionEpisode>& episodes);
/** Coverage at time t: the last sample at or before t (a finished run keeps its final value). */
double coverageAt(const Series& s, double t);

}  // namespace daep::eval::detail
