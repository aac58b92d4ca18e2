// Pearson's chi-square goodness-of-fit test, shared by the warp and BSDF tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "core/math.h"

namespace stratum::chi_square {

// Regularised upper incomplete gamma Q(a, x): series for x < a + 1, Lentz continued fraction
// otherwise (Abramowitz & Stegun 6.5.29 and 6.5.31). The chi-square p-value is Q(dof/2, x/2).
inline double upper_incomplete_gamma(double a, double x) {
    if (x <= 0.0) return 1.0;
    const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
    if (x < a + 1.0) {
        double term = 1.0 / a, sum = term;
        for (int n = 1; n < 1000 && std::abs(term) > 1e-15 * std::abs(sum); ++n) {
            term *= x / (a + n);
            sum += term;
        }
        return 1.0 - sum * std::exp(log_prefactor);
    }
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 1000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        d = std::abs(d) < tiny ? tiny : d;
        c = b + an / c;
        c = std::abs(c) < tiny ? tiny : c;
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1.0) < 1e-15) break;
    }
    return std::exp(log_prefactor) * h;
}

struct ChiSquare {
    double statistic = 0;
    int dof = 0;
    double p_value = 0;
    double density_mass = 0;  // integral of the density over the sphere (should be <= 1)
};

// Pearson's test of observed against expected counts, pooling bins with expected < 5.
inline ChiSquare pearson(const std::vector<double>& observed, const std::vector<double>& expected) {
    ChiSquare r;
    double pooled_observed = 0, pooled_expected = 0;
    int bins = 0;
    for (size_t i = 0; i < observed.size(); ++i) {
        if (expected[i] < 5.0) {
            pooled_observed += observed[i];
            pooled_expected += expected[i];
            continue;
        }
        r.statistic += sqr(float(observed[i] - expected[i])) / expected[i];
        ++bins;
    }
    if (pooled_expected > 0.0 || pooled_observed > 0.0) {
        r.statistic += pooled_expected > 0.0 ? sqr(float(pooled_observed - pooled_expected)) / pooled_expected
                                             : std::numeric_limits<double>::infinity();
        ++bins;
    }
    r.dof = bins - 1;
    r.p_value = upper_incomplete_gamma(0.5 * r.dof, 0.5 * r.statistic);
    return r;
}

// Draws one direction from (u, u_lobe); false when the sampler produces none.
using DirectionSampler = std::function<bool(Vec2, float, Vec3*)>;
using DirectionDensity = std::function<float(Vec3)>;

// Chi-square test of `sample_count` directions against `density` over the whole sphere: 12 x 20
// bins in (theta, phi), theta edges at quantiles of the density's own theta marginal (roughly
// equal expected counts), expected counts integrated by the midpoint rule on a fine grid of
// theta_fine x phi_fine cells (finer for peaked densities), failed samples counted against
// the density's missing mass. density_mass reports the integral of the density.
inline ChiSquare chi_square_directions(const DirectionSampler& sample, const DirectionDensity& density,
                                       uint64_t seed, int sample_count, int theta_fine, int phi_fine) {
    const int kThetaFine = theta_fine, kPhiFine = phi_fine, kSampleCount = sample_count;
    constexpr int kThetaBins = 12, kPhiBins = 20;
    const double dtheta = double(kPi) / kThetaFine, dphi = 2.0 * double(kPi) / kPhiFine;
    std::vector<double> fine(kThetaFine * kPhiFine), theta_mass(kThetaFine, 0.0);
    double total = 0;
    for (int i = 0; i < kThetaFine; ++i) {
        const double theta = (i + 0.5) * dtheta;
        for (int j = 0; j < kPhiFine; ++j) {
            const double phi = (j + 0.5) * dphi;
            const Vec3 w(float(std::sin(theta) * std::cos(phi)), float(std::sin(theta) * std::sin(phi)),
                         float(std::cos(theta)));
            const double m = density(w) * std::sin(theta) * dtheta * dphi;
            fine[i * kPhiFine + j] = m;
            theta_mass[i] += m;
            total += m;
        }
    }
    // Theta bin edges at quantiles of the density's theta marginal.
    std::vector<int> theta_bin(kThetaFine);
    double cumulative = 0;
    for (int i = 0; i < kThetaFine; ++i) {
        theta_bin[i] = std::min(int(cumulative / total * kThetaBins), kThetaBins - 1);
        cumulative += theta_mass[i];
    }
    const int outside = kThetaBins * kPhiBins;  // failed samples: mass 1 - total
    std::vector<double> expected(outside + 1, 0.0), observed(outside + 1, 0.0);
    for (int i = 0; i < kThetaFine; ++i)
        for (int j = 0; j < kPhiFine; ++j)
            expected[theta_bin[i] * kPhiBins + j * kPhiBins / kPhiFine] +=
                fine[i * kPhiFine + j] * kSampleCount;
    expected[outside] = std::max(1.0 - total, 0.0) * kSampleCount;

    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> uniform(0.0f, kOneMinusEpsilon);
    for (int s = 0; s < kSampleCount; ++s) {
        Vec3 w;
        if (!sample({uniform(rng), uniform(rng)}, uniform(rng), &w)) {
            observed[outside] += 1;
            continue;
        }
        const double theta = std::acos(std::clamp(double(w.z), -1.0, 1.0));
        double phi = std::atan2(double(w.y), double(w.x));
        if (phi < 0) phi += 2.0 * kPi;
        const int i = std::min(int(theta / dtheta), kThetaFine - 1),
                  j = std::min(int(phi / dphi), kPhiFine - 1);
        observed[theta_bin[i] * kPhiBins + j * kPhiBins / kPhiFine] += 1;
    }
    ChiSquare r = pearson(observed, expected);
    r.density_mass = total;
    return r;
}

}  // namespace stratum::chi_square
