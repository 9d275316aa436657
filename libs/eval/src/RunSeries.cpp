#include "RunSeries.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <string>

namespace daep::eval::detail {

Series readTimeseries(const std::filesystem::path& file) {
    Series s;
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
        double t = 0, c = 0;
        if (std::sscanf(line.c_str(), "%lf,%lf", &t, &c) == 2)
            s.t.push_back(t), s.coverage.push_back(c);
    }
    return s;
}

std::vector<CollisionEpisode> readCollisionEpisodes(const std::filesystem::path& file,
                                                    double explorationStart,
                                                    double explorationEnd) {
    std::vector<CollisionEpisode> episodes;
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);  // header
    while (std::getline(in, line)) {
        CollisionEpisode e;
        if (std::sscanf(line.c_str(), "%d,%lf,%lf", &e.person, &e.start, &e.end) != 3)
            continue;
        e.end = e.end < 0.0 ? explorationEnd : e.end - explorationStart;
        e.start = std::max(0.0, e.start - explorationStart);
        episodes.push_back(e);
    }
    return episodes;
}

std::vector<std::pair<double, double>> spansOf(const std::vector<CollisionEpisode>& episodes) {
    std::vector<std::pair<double, double>> spans;
    for (const auto& e : episodes)
        spans.emplace_back(e.start, e.end);
    return spans;
}

double coverageAt(const Series& s, double t) {
    const auto it = std::upper_bound(s.t.begin(), s.t.end(), t);
    if (it == s.t.begin())
        return s.coverage.empty() ? 0.0 : s.coverage.front();
    return s.coverage[static_cast<std::size_t>(it - s.t.begin()) - 1];
}

}  // namespace daep::eval::detail
