#include "daep/eval/Statistics.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace daep::eval {

double percentile(std::vector<double> values, double pct) {
    if (values.empty())
        return 0.0;
    std::sort(values.begin(), values.end());
    const double rank = std::clamp(pct, 0.0, 100.0) / 100.0 * (values.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(rank));
    const auto hi = std::min(lo + 1, values.size() - 1);
    const double frac = rank - lo;
    return values[lo] + frac * (values[hi] - values[lo]);
}

double mean(const std::vector<double>& values) {
    if (values.empty())
        return 0.0;
    return std::accumulate(values.begin(), values.end(), 0.0) / values.size();
}

}  // namespace daep::eval
