// Pearson's chi-square goodness-of-fit test, shared by the warp and BSDF tests.
#pragma once

#include <cmath>
#include <limits>
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

}  // namespace stratum::chi_square
