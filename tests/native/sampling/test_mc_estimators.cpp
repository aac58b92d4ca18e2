// Monte Carlo estimators of the textbook's exercise (Zhdanov et al. 2023, §4, Q4.2–4.8; digest
// /work/shared/research/textbook.md, §4 and table "Monte Carlo exercises"):
//
//     I = ∫₀² f(x) dx,  f(x) = x²/2,  I = [x³/6]₀² = 4/3.
//
// | estimator                       | random numbers | analytic Var of ONE estimate |
// |---------------------------------|----------------|------------------------------|
// | uniform on [0,2]                | 1              | 64/45                        |
// | 5 equal strata, 1 sample each   | 5              | 7936/562500 ≈ 0.014108       |
// | IS p₁ = x/2                     | 1              | 2/9                          |
// | IS p₂ = 3x²/8 (p₂ ∝ f)          | 1              | 0 (exact)                    |
// | MIS p₁+p₂, weights ½            | 2              | 1/18                         |
// | MIS balance heuristic           | 2              | quadrature ≈ 0.0323          |
// | MIS power heuristic (β = 2)     | 2              | quadrature ≈ 0.0446          |
// | control variate g = f − 0.1     | 1              | 0 (exact)                    |
// | control variate g = x           | 1              | 4/45                         |
// | RR, R = 0.9, uniform            | 1              | 16/9                         |
// | RR + IS p₁                      | 1              | 4/9                          |
// | RR + IS p₂                      | 1              | 16/81                        |
// | RR + IS p₁ + control var J=0.8I | 1              | 20.64/81 ≈ 0.254815          |
//
// Integrals used throughout:  ∫₀² f² dx = ∫₀² x⁴/4 dx = 32/20 = 8/5;  I² = 16/9.
//
// Test of each estimator Y (N independent estimates y_k, fixed PCG32 seed):
//  * mean:     |ȳ − 4/3| ≤ 4·σ/√N with σ² the analytic variance (CLT: ȳ ~ N(I, σ²/N)).
//  * variance: |s² − σ²| ≤ 4·SE(s²), SE(s²) ≈ sqrt((μ₄ − σ⁴)/N) (the large-N variance of the
//    unbiased sample variance). μ₄, the fourth central moment, is ESTIMATED from the same sample
//    (m₄ = Σ(y−ȳ)⁴/N): it only sets the scale of the tolerance, not the tested value, and
//    deriving it in closed form for the roulette and MIS mixtures would add thirteen more
//    derivations that the test never checks; with N = 10⁶ the relative error of m₄ is a few
//    percent, which moves a 4σ band by a fraction of a σ. σ⁴ in the SE is the analytic σ².
//  * zero-variance estimators: every estimate must equal 4/3 to float rounding (|y − 4/3| ≤
//    1e-14), so the sample variance is 0 up to rounding.
// With 4σ bands and 22 two-sided checks the chance of a false failure is ≤ 22·6.3e-5 ≈ 0.14 %.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <vector>

#include "sampling/pcg32.h"

namespace stratum {
namespace {

constexpr double kIntegral = 4.0 / 3.0;
constexpr int kEstimates = 1'000'000;
constexpr double kSigmas = 4.0;
constexpr double kRouletteSurvival = 0.9;  // R = 1.8/2, the digest's choice

double integrand(double x) { return 0.5 * x * x; }

// Uniform in the open interval (0,1): the midpoint of one of 2³² cells, so that x = 2√u and
// x = 2u^{1/3} never hit 0, where p₁ and p₂ vanish.
double open_uniform(Pcg32& rng) { return (static_cast<double>(rng.next_u32()) + 0.5) * 0x1p-32; }

// p₁(x) = x/2 on [0,2]: CDF x²/4, inverse x = 2√u.
double density_linear(double x) { return 0.5 * x; }
double sample_linear(double u) { return 2.0 * std::sqrt(u); }
// p₂(x) = 3x²/8 on [0,2]: CDF x³/8, inverse x = 2u^{1/3}. p₂ = f/I, the zero-variance density.
double density_quadratic(double x) { return 0.375 * x * x; }
double sample_quadratic(double u) { return 2.0 * std::cbrt(u); }

// ---- Estimators: one call returns ONE estimate of I --------------------------------------------

// Y = 2 f(2u). E[Y²] = 2 ∫₀² f² dx = 16/5; Var = 16/5 − 16/9 = 64/45.
double uniform_estimate(Pcg32& rng) { return 2.0 * integrand(2.0 * open_uniform(rng)); }

// Strata [a_k, a_k + h], h = 2/5, k = 0..4, one uniform sample x_k in each: Y = Σ h f(x_k).
// Var = Σ_k (h ∫_k f² − I_k²) = h ∫₀² f² − Σ I_k² (eq. 4.7–4.8),
//   h ∫₀² f² = (2/5)(8/5) = 16/25,
//   I_k = ((a_k+h)³ − a_k³)/6 = (8/750)(3k² + 3k + 1) → (8/750)·{1, 7, 19, 37, 61},
//   Σ I_k² = (64/562500)(1 + 49 + 361 + 1369 + 3721) = 352064/562500,
//   Var = (360000 − 352064)/562500 = 7936/562500 ≈ 0.014108.
// The digest's "≈ 0.0705" is 5·Var = N·Var, the per-sample variance comparable with the
// uniform 64/45 (the stratified sum uses 5 samples); 5 · 7936/562500 = 0.070542 matches it.
constexpr int kStrata = 5;
double stratified_estimate(Pcg32& rng) {
    constexpr double width = 2.0 / kStrata;
    double sum = 0.0;
    for (int k = 0; k < kStrata; ++k) sum += width * integrand(width * (k + open_uniform(rng)));
    return sum;
}

// Y = f/p₁ = x with x ~ p₁. E[Y²] = ∫₀² x² · x/2 dx = [x⁴/8]₀² = 2; Var = 2 − 16/9 = 2/9.
double is_linear_estimate(Pcg32& rng) {
    const double x = sample_linear(open_uniform(rng));
    return integrand(x) / density_linear(x);
}

// Y = f/p₂ = (x²/2)/(3x²/8) = 4/3 for every x: Var = ∫ f²/p₂ − I² = I ∫ f − I² = 0.
double is_quadratic_estimate(Pcg32& rng) {
    const double x = sample_quadratic(open_uniform(rng));
    return integrand(x) / density_quadratic(x);
}

// MIS, one sample from each density (eq. 4.13): Y = w₁(x₁) f(x₁)/p₁(x₁) + w₂(x₂) f(x₂)/p₂(x₂),
// x₁ ~ p₁ and x₂ ~ p₂ independent, w₁ + w₂ ≡ 1. The two terms are independent, so
//   Var = Σ_i [ ∫₀² w_i² f²/p_i dx − (∫₀² w_i f dx)² ].                              (MIS-Var)
using MisWeight = double (*)(double p_own, double p_other);
double weight_half(double, double) { return 0.5; }
double weight_balance(double p_own, double p_other) { return p_own / (p_own + p_other); }
double weight_power(double p_own, double p_other) {
    return p_own * p_own / (p_own * p_own + p_other * p_other);
}

double mis_estimate(Pcg32& rng, MisWeight weight) {
    const double x1 = sample_linear(open_uniform(rng));
    const double x2 = sample_quadratic(open_uniform(rng));
    const double p11 = density_linear(x1), p21 = density_quadratic(x1);
    const double p12 = density_linear(x2), p22 = density_quadratic(x2);
    return weight(p11, p21) * integrand(x1) / p11 + weight(p22, p12) * integrand(x2) / p22;
}

// Weights ½ in (MIS-Var): ¼(∫f²/p₁ − I²) + ¼(∫f²/p₂ − I²) = ¼·2/9 + ¼·0 = 1/18.
// Balance: w_i f/p_i = f/(p₁+p₂) = 4x/(4+3x) in both terms; power: w_i = p_i²/(p₁²+p₂²). Their
// (MIS-Var) integrands are rational in x with logs/arctans in closed form, so the test evaluates
// (MIS-Var) by composite Simpson quadrature instead (integrands smooth on [0,2]: the
// denominators 4+3x and 16+9x² have no zeros there; error O(h⁴) ≈ 1e-14 at 4096 panels).
// The quadrature is checked against the closed form 1/18 of the ½ weights.
double simpson(const std::function<double(double)>& g, double a, double b) {
    constexpr int panels = 4096;  // even
    const double h = (b - a) / panels;
    double sum = g(a) + g(b);
    for (int i = 1; i < panels; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * g(a + i * h);
    return sum * h / 3.0;
}

double mis_analytic_variance(MisWeight weight) {
    // Term i, evaluated at x with own density p_own and the other density p_other; the
    // integrands vanish like x at 0, so x = 0 is handled by its limit 0 (f = 0 there).
    const auto term = [weight](double (*p_own)(double), double (*p_other)(double)) {
        const auto second_moment = [&](double x) {
            if (x == 0.0) return 0.0;
            const double w = weight(p_own(x), p_other(x));
            return w * w * integrand(x) * integrand(x) / p_own(x);
        };
        const auto first_moment = [&](double x) {
            if (x == 0.0) return 0.0;
            return weight(p_own(x), p_other(x)) * integrand(x);
        };
        const double mean = simpson(first_moment, 0.0, 2.0);
        return simpson(second_moment, 0.0, 2.0) - mean * mean;
    };
    return term(density_linear, density_quadratic) + term(density_quadratic, density_linear);
}

// Control variate, the "main part" (eq. 4.22–4.23), uniform sampling on [0,2]:
// Y = J + 2 (f − g)(x), J = ∫₀² g.
// g = f − 0.1 (the digest's): J = 4/3 − 0.2, Y = J + 0.2 = 4/3 for every x; Var = 0.
double control_variate_main_part_estimate(Pcg32& rng) {
    const double x = 2.0 * open_uniform(rng);
    const double g = integrand(x) - 0.1;
    constexpr double g_integral = kIntegral - 0.2;
    return g_integral + 2.0 * (integrand(x) - g);
}
// g = x: J = 2, Y = 2 + x² − 2x with x ~ U[0,2]. E[x^k] = 2^k/(k+1):
//   E[x² − 2x] = 4/3 − 2 = −2/3;  E[(x² − 2x)²] = E[x⁴] − 4E[x³] + 4E[x²] = 16/5 − 8 + 16/3 = 8/15;
//   Var = 8/15 − 4/9 = 4/45 ≈ 0.0889 (not in the digest's table).
double control_variate_linear_estimate(Pcg32& rng) {
    const double x = 2.0 * open_uniform(rng);
    constexpr double g_integral = 2.0;
    return g_integral + 2.0 * (integrand(x) - x);
}

// Russian roulette (eq. 4.26–4.27), survival R: with u ≤ R the estimate continues with the
// rescaled number u/R (uniform on (0,1) given survival) and is divided by R, else it is 0.
// For a base estimate X: E[Y] = R·E[X]/R = I, E[Y²] = R·E[X²]/R² = E[X²]/R, so
//   Var = E[X²]/R − I².                                                              (RR-Var)
template <typename BaseEstimate>
double roulette(Pcg32& rng, BaseEstimate base) {
    const double u = open_uniform(rng);
    if (u > kRouletteSurvival) return 0.0;
    return base(u / kRouletteSurvival) / kRouletteSurvival;
}

// X = 2 f(2u): E[X²] = 16/5; Var = 16/(5·0.9) − 16/9 = 32/9 − 16/9 = 16/9 ≈ 1.7778 (digest ✓).
double roulette_uniform_estimate(Pcg32& rng) {
    return roulette(rng, [](double u) { return 2.0 * integrand(2.0 * u); });
}
// X = f/p₁ (eq. 4.29): E[X²] = 2; Var = 2/0.9 − 16/9 = 20/9 − 16/9 = 4/9 (digest ✓).
double roulette_is_linear_estimate(Pcg32& rng) {
    return roulette(rng, [](double u) {
        const double x = sample_linear(u);
        return integrand(x) / density_linear(x);
    });
}
// X = f/p₂ = 4/3: E[X²] = 16/9; Var = (16/9)/0.9 − 16/9 = (16/9)(1/9) = 16/81 (digest ✓).
double roulette_is_quadratic_estimate(Pcg32& rng) {
    return roulette(rng, [](double u) {
        const double x = sample_quadratic(u);
        return integrand(x) / density_quadratic(x);
    });
}

// RR + IS(p₁) + control variate g = J p₁ (eq. 4.30, with the digest's fix 1/P → 1/R):
//   survive (prob R): Y = (1/R) f/p₁ − (1/R − 1) J;   absorbed: Y = J.
// E[Y] = E[f/p₁] − (1−R)J + (1−R)J = I. Variance (eq. 4.31):
//   E[Y²] = R·E[((1/R)X − (1/R − 1)J)²] + (1−R)J²
//         = E[X²]/R − 2(1/R − 1)IJ + (1/R − 1)J²
//   Var   = E[X²]/R − (1/R − 1)(2I − J)J − I².
// J = 0.8I, R = 0.9: 20/9 − (1/9)(1.2I)(0.8I) − 16/9 = 4/9 − 0.96·16/81 = 20.64/81 ≈ 0.254815
// (digest 0.2548 ✓; smaller than RR + IS alone, 4/9, as 0 < J < 2I, eq. 4.32).
constexpr double kControlIntegral = 0.8 * kIntegral;
double roulette_is_control_variate_estimate(Pcg32& rng) {
    const double u = open_uniform(rng);
    if (u > kRouletteSurvival) return kControlIntegral;
    const double x = sample_linear(u / kRouletteSurvival);
    return integrand(x) / density_linear(x) / kRouletteSurvival -
           (1.0 / kRouletteSurvival - 1.0) * kControlIntegral;
}

// ---- Checks -----------------------------------------------------------------------------------

struct SampleMoments {
    double mean;
    double variance;       // unbiased: Σ(y − ȳ)²/(N − 1)
    double fourth_moment;  // central: Σ(y − ȳ)⁴/N
    double max_deviation;  // max |y − I|
};

SampleMoments measure(double (*estimate)(Pcg32&), uint64_t seed) {
    Pcg32 rng(seed, 54u);
    std::vector<double> ys(kEstimates);
    for (double& y : ys) y = estimate(rng);
    // Neumaier-compensated sum: a plain running sum of 10⁶ values near 4/3 drifts by ~1e-11,
    // which alone would give the zero-variance estimators a "variance" of ~1e-23.
    double sum = 0.0, compensation = 0.0, max_deviation = 0.0;
    for (double y : ys) {
        const double t = sum + y;
        compensation += std::fabs(sum) >= std::fabs(y) ? (sum - t) + y : (y - t) + sum;
        sum = t;
        max_deviation = std::fmax(max_deviation, std::fabs(y - kIntegral));
    }
    const double mean = (sum + compensation) / kEstimates;
    double m2 = 0.0, m4 = 0.0;
    for (double y : ys) {
        const double d2 = (y - mean) * (y - mean);
        m2 += d2;
        m4 += d2 * d2;
    }
    return {mean, m2 / (kEstimates - 1), m4 / kEstimates, max_deviation};
}

void expect_estimator(const char* name, double (*estimate)(Pcg32&), double analytic_variance, uint64_t seed) {
    const SampleMoments m = measure(estimate, seed);
    std::printf("[ mc ] %-28s N=%d mean=%.6f var=%.6f analytic var=%.6f\n", name, kEstimates, m.mean,
                m.variance, analytic_variance);
    const double mean_tolerance = kSigmas * std::sqrt(analytic_variance / kEstimates);
    EXPECT_NEAR(m.mean, kIntegral, mean_tolerance) << name;
    const double variance_se =
        std::sqrt((m.fourth_moment - analytic_variance * analytic_variance) / kEstimates);
    EXPECT_NEAR(m.variance, analytic_variance, kSigmas * variance_se) << name;
}

void expect_zero_variance_estimator(const char* name, double (*estimate)(Pcg32&), uint64_t seed) {
    const SampleMoments m = measure(estimate, seed);
    std::printf("[ mc ] %-28s N=%d mean=%.17g var=%.3g max|y-I|=%.3g\n", name, kEstimates, m.mean, m.variance,
                m.max_deviation);
    EXPECT_LE(m.max_deviation, 1e-14) << name;
    EXPECT_LE(m.variance, 1e-28) << name;
}

double mis_half_estimate(Pcg32& rng) { return mis_estimate(rng, weight_half); }
double mis_balance_estimate(Pcg32& rng) { return mis_estimate(rng, weight_balance); }
double mis_power_estimate(Pcg32& rng) { return mis_estimate(rng, weight_power); }

// The closed forms above against the digest's table (given to 4 digits: ±5e-5), and the
// quadrature against the closed form of the ½ weights.
TEST(MonteCarloEstimators, AnalyticVariancesMatchDigestTable) {
    EXPECT_NEAR(64.0 / 45.0, 1.4222, 5e-5);
    EXPECT_NEAR(kStrata * 7936.0 / 562500.0, 0.0705, 5e-5);
    EXPECT_NEAR(mis_analytic_variance(weight_half), 1.0 / 18.0, 1e-12);
    EXPECT_NEAR(mis_analytic_variance(weight_balance), 0.0323, 5e-5);
    EXPECT_NEAR(mis_analytic_variance(weight_power), 0.0446, 5e-5);
    EXPECT_NEAR(16.0 / 9.0, 1.7778, 5e-5);
    EXPECT_NEAR(4.0 / 9.0, 0.4444, 5e-5);
    EXPECT_NEAR(16.0 / 81.0, 0.1975, 5e-5);
    EXPECT_NEAR(20.64 / 81.0, 0.2548, 5e-5);
}

TEST(MonteCarloEstimators, Uniform) { expect_estimator("uniform", uniform_estimate, 64.0 / 45.0, 1); }
TEST(MonteCarloEstimators, FiveStrata) {
    expect_estimator("5 strata", stratified_estimate, 7936.0 / 562500.0, 2);
}
TEST(MonteCarloEstimators, ImportanceLinear) {
    expect_estimator("IS p=x/2", is_linear_estimate, 2.0 / 9.0, 3);
}
TEST(MonteCarloEstimators, ImportanceQuadraticIsExact) {
    expect_zero_variance_estimator("IS p=3x^2/8", is_quadratic_estimate, 4);
}
TEST(MonteCarloEstimators, MisHalfWeights) {
    expect_estimator("MIS weights 1/2", mis_half_estimate, 1.0 / 18.0, 5);
}
TEST(MonteCarloEstimators, MisBalance) {
    expect_estimator("MIS balance", mis_balance_estimate, mis_analytic_variance(weight_balance), 6);
}
TEST(MonteCarloEstimators, MisPower) {
    expect_estimator("MIS power", mis_power_estimate, mis_analytic_variance(weight_power), 7);
}
TEST(MonteCarloEstimators, ControlVariateMainPartIsExact) {
    expect_zero_variance_estimator("CV g=f-0.1", control_variate_main_part_estimate, 8);
}
TEST(MonteCarloEstimators, ControlVariateLinear) {
    expect_estimator("CV g=x", control_variate_linear_estimate, 4.0 / 45.0, 9);
}
TEST(MonteCarloEstimators, RouletteUniform) {
    expect_estimator("RR R=0.9", roulette_uniform_estimate, 16.0 / 9.0, 10);
}
TEST(MonteCarloEstimators, RouletteImportanceLinear) {
    expect_estimator("RR + IS x/2", roulette_is_linear_estimate, 4.0 / 9.0, 11);
}
TEST(MonteCarloEstimators, RouletteImportanceQuadratic) {
    expect_estimator("RR + IS 3x^2/8", roulette_is_quadratic_estimate, 16.0 / 81.0, 12);
}
TEST(MonteCarloEstimators, RouletteImportanceControlVariate) {
    expect_estimator("RR + IS x/2 + CV J=0.8I", roulette_is_control_variate_estimate, 20.64 / 81.0, 13);
}

}  // namespace
}  // namespace stratum
