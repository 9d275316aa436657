#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace daep::sim {

/**
 * SplitMix64: a tiny, fast 64-bit generator. The camera seeds one per frame from the caller's
 * mt19937_64, whose ~5 ns per draw would otherwise dominate the noise of a 640 x 480 frame.
 */
class SplitMix64 {
public:
    using result_type = uint64_t;
    explicit SplitMix64(uint64_t seed) : state_(seed) {}

    static constexpr result_type min() { return 0; }
    static constexpr result_type max() { return UINT64_MAX; }

    result_type operator()() {
        uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }

private:
    uint64_t state_;
};

/**
 * Standard normal samples by the ziggurat method (Marsaglia & Tsang): about one 64-bit draw per
 * sample, where std::normal_distribution needs a logarithm and a square root per pair.
 */
class GaussianSampler {
public:
    GaussianSampler();

    /** `Rng` yields uniform 64-bit words. */
    template <typename Rng>
    double operator()(Rng& rng) const {
        for (;;) {
            const uint64_t bits = rng();
            const int layer = static_cast<int>(bits & (kLayers - 1));
            // Bit 7 gives the sign, arithmetically: a branch on it mispredicts half the time.
            const double sign = static_cast<double>(static_cast<int>((bits >> 6) & 2u) - 1);
            const double x = uniform(bits) * x_[layer];
            if (x < x_[layer + 1]) {
                return sign * x;
            }
            if (layer == 0) {
                return sign * tail(rng);
            }
            const double y = fx_[layer] + uniform(rng()) * (fx_[layer + 1] - fx_[layer]);
            if (y < std::exp(-0.5 * x * x)) {
                return sign * x;
            }
        }
    }

private:
    static constexpr int kLayers = 128;

    /** Uniform in [0, 1) from the top 53 bits (the low byte picks layer and sign). */
    static double uniform(uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1.0p-53; }

    template <typename Rng>
    double tail(Rng& rng) const {
        double dx = 0.0;
        double dy = 0.0;
        do {
            dx = -std::log1p(-uniform(rng())) / r_;
            dy = -std::log1p(-uniform(rng()));
        } while (dy + dy < dx * dx);
        return r_ + dx;
    }

    double r_ = 0.0;                        ///< start of the tail
    std::array<double, kLayers + 1> x_{};   ///< layer right edges, x_[0] the base, x_[kLayers] 0
    std::array<double, kLayers + 1> fx_{};  ///< exp(-x^2 / 2) at x_
};

/** The sampler's tables, built once. */
const GaussianSampler& standardNormal();

}  // namespace daep::sim
