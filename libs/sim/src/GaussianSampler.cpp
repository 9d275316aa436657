#include "GaussianSampler.h"

#include <cmath>

namespace daep::sim {
namespace {

double density(double x) {
    return std::exp(-0.5 * x * x);
}

double inverseDensity(double y) {
    return std::sqrt(-2.0 * std::log(y));
}

/** Area under the (unnormalised) density beyond r. */
double tailArea(double r) {
    return std::sqrt(M_PI / 2.0) * std::erfc(r / std::sqrt(2.0));
}

/**
 * Stacks layers of equal area v on top of the base strip (rectangle to r plus tail). Returns
 * how far the top layer overshoots the density's peak: > 0 means r is too small.
 */
template <std::size_t N>
double buildLayers(double r, std::array<double, N>& x) {
    const int layers = static_cast<int>(N) - 1;
    const double v = r * density(r) + tailArea(r);
    x[0] = v / density(r);
    x[1] = r;
    for (int i = 1; i < layers - 1; ++i) {
        const double y = density(x[i]) + v / x[i];
        if (y >= 1.0) {
            return y;
        }
        x[i + 1] = inverseDensity(y);
    }
    x[layers] = 0.0;
    return density(x[layers - 1]) + v / x[layers - 1] - 1.0;
}

}  // namespace

GaussianSampler::GaussianSampler() {
    double lo = 2.0;
    double hi = 5.0;
    for (int it = 0; it < 200; ++it) {
        r_ = 0.5 * (lo + hi);
        (buildLayers(r_, x_) > 0.0 ? lo : hi) = r_;
    }
    r_ = hi;  // the side whose top layer stays within the peak
    buildLayers(r_, x_);
    for (std::size_t i = 0; i < x_.size(); ++i) {
        fx_[i] = density(x_[i]);
    }
}

const GaussianSampler& standardNormal() {
    static const GaussianSampler sampler;
    return sampler;
}

}  // namespace daep::sim
