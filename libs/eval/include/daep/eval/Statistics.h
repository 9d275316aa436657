#pragma once

#include <vector>

namespace daep::eval {

/** Linear-interpolated percentile (0..100) of the values; 0 for an empty set. */
double percentile(std::vector<double> values, double pct);
inline double median(std::vector<double> values) {
    return percentile(std::move(values), 50.0);
}

double mean(const std::vector<double>& values);

}  // namespace daep::eval
