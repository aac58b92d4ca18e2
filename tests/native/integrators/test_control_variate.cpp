// Issue 6 acceptance point 4, control variate part (textbook eq. 5.17, 4.30–4.32; research/
// textbook.md §2.1 test B): the closed integrating sphere (h = 0, walls L_e, reflectance k),
// BSDF sampling only, albedo roulette from the first vertex (survival = k), ambient L_a.
//
// Per path, with cosine sampling the BSDF weight f·cos/pdf is k and the survival k, so the
// throughput stays 1. Vertex i (0..m, the path dies by roulette after vertex m) adds its
// emission L_e and the control variate's ambient estimate k·L_a, and, if the path survives,
// subtracts L_a·(f·cos/pdf)/k = L_a (eq. 5.17 in the form common.md gives the path tracer).
// The path's value is therefore
//     X = (m+1)(L_e + kL_a) − m·L_a = L_a + J·c,   c = L_e − (1 − k)L_a,  J = m + 1,
// with J geometric on {1, 2, ...}, P(J = j) = k^{j−1}(1 − k): mean 1/(1 − k), variance
// k/(1 − k)². So E[X] = L_a + c/(1 − k) = L_e/(1 − k) = L for every L_a (unbiased), and
//     Var X = c²·k/(1 − k)²                                   (the book's eq. 4.32 form),
// zero at L_a = L = L_e/(1 − k), smaller than the plain estimator's (L_a = 0) iff 0 < L_a < 2L.
//
// The bounce cap is 1024 (the maximum): the chance that a path reaches it is k^1025 ≈ 0.
#include <gtest/gtest.h>

#include <cstdio>

#include "render_helpers.h"

using namespace stratum_test;

namespace {

constexpr float kReflectance = 0.6f;  // not dyadic: the sums round
constexpr double kEmission = 0.8;
constexpr double kRadiance = kEmission / (1.0 - kReflectance);  // L = 2

IntegratingSphere closed_emissive_sphere() {
    IntegratingSphereDesc d;
    d.reflectance = kReflectance;
    d.emission = static_cast<float>(kEmission);
    d.rings = 16;  // closed: the formulas hold for any closed shape
    return make_integrating_sphere(d);
}

Settings control_variate_settings(uint32_t size, uint32_t spp, double ambient, uint32_t seed) {
    return {{"width", size},       {"height", size},    {"samples", spp},
            {"max_bounces", 1024}, {"seed", seed},      {"light_sampling", "bsdf"},
            {"rr_mode", "albedo"}, {"rr_min_depth", 0}, {"control_variate", ambient}};
}

}  // namespace

// L_a = L: every path returns exactly L_a, so every pixel is L to float rounding.
// Rounding bound: with u = 2⁻²⁴, each vertex does ~3 additions to a running sum of magnitude
// ≤ 2L_a + L_e ≤ 3L_a (error ≤ 9u·L_a per vertex) and updates the throughput by a weight and
// a survival division (f, cos and pdf each a few operations: ≤ 6u relative per vertex, so after
// j vertices the terms it scales carry ≤ 6j·u relative error, on two terms ≤ L_a each). Over
// J vertices the error is ≤ 9uJ·L_a + 12u·L_a·J(J+1)/2 ≤ 6u·L_a·J(J+2). We bound J ≤ 50: the
// chance that any of the 32·32·16 = 16384 paths has more vertices is 16384·0.6⁵⁰ ≈ 1.3e-7.
// So |X − L_a| ≤ 6·50·52·u·L_a ≈ 9.3e-4 L_a per path, and a pixel (the mean of 16 paths,
// summed in float: ≤ 16u more) stays within the same bound. An ambient 1% off L already gives
// c = −0.008, a per-path standard deviation |c|√k/(1 − k) = 0.77% of L, 0.19% per pixel, whose
// extremes over 1024 pixels (~3σ) are six times the bound: the test discriminates.
TEST(ControlVariate, AmbientEqualToTheSphereRadianceGivesZeroVariance) {
    IntegratingSphere s = closed_emissive_sphere();
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    const RenderOutput out = render(s.scene, control_variate_settings(32, 16, kRadiance, 9));
    ASSERT_TRUE(out.error.empty()) << out.error;
    ASSERT_EQ(out.rgba.size(), 32u * 32u * 4u);
    const double u = std::ldexp(1.0, -24);
    const double bound = 6.0 * 50.0 * 52.0 * u;
    float lo = out.rgba[0], hi = out.rgba[0];
    for (size_t i = 0; i < out.rgba.size(); i += 4) {
        lo = std::min(lo, out.rgba[i]);
        hi = std::max(hi, out.rgba[i]);
        ASSERT_NEAR(out.rgba[i], kRadiance, bound * kRadiance) << "pixel " << i / 4;
    }
    EXPECT_LE((hi - lo) / kRadiance, 2.0 * bound) << "spread " << (hi - lo);
    // The same renders without the control variate are far from constant (variance 2.4 per path).
    const RenderOutput plain = render(s.scene, control_variate_settings(32, 16, 0.0, 9));
    ASSERT_TRUE(plain.error.empty()) << plain.error;
    EXPECT_GT(std::sqrt(pixel_stats(plain.rgba).variance), 100.0 * bound * kRadiance);
    stratum_scene_destroy(s.scene);
}

// The L_a sweep over [0, 2L]: 1 sample per pixel, so each pixel is one path's X and the sample
// variance over the N = 128² pixels (independent: the `random` sampler) estimates Var X.
// Standard error of a sample variance: √((μ₄ − σ⁴)/N), μ₄ the fourth central moment. X − E X =
// c(J − E J), and the geometric J (success probability p = 1 − k, q = k) has excess kurtosis
// 6 + p²/q, so μ₄ = σ⁴(9 + p²/q) and se(s²) = σ²√((8 + p²/q)/N): 2.2% of σ² for k = 0.6.
// The mean is checked too (se σ/√N). Each point is accepted within 4σ.
TEST(ControlVariate, VarianceFollowsTheTextbookCurveOverTheAmbientSweep) {
    IntegratingSphere s = closed_emissive_sphere();
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    const double k = kReflectance, p = 1.0 - k;
    constexpr uint32_t kSize = 128;
    const double n = static_cast<double>(kSize) * kSize;
    for (const double fraction : {0.0, 0.25, 0.5, 0.8, 1.25, 1.6, 2.0}) {
        const double ambient = fraction * kRadiance;
        const RenderOutput out = render(s.scene, control_variate_settings(kSize, 1, ambient, 21));
        ASSERT_TRUE(out.error.empty()) << out.error;
        const PixelStats st = pixel_stats(out.rgba);
        const double c = kEmission - (1.0 - k) * ambient;
        const double variance = c * c * k / (p * p);
        const double variance_se = variance * std::sqrt((8.0 + p * p / k) / n);
        // The table docs/study.md quotes (the book's claim 9: the curve of eq. 4.32).
        std::printf("control variate L_a = %.2f L: per-path variance %.4f, expected %.4f +- %.4f\n", fraction,
                    st.variance, variance, variance_se);
        EXPECT_NEAR(st.variance, variance, 4.0 * variance_se)
            << "L_a = " << fraction << " L: variance " << st.variance << " expected " << variance;
        EXPECT_NEAR(st.mean, kRadiance, 4.0 * std::sqrt(variance / n)) << "L_a = " << fraction << " L";
    }
    stratum_scene_destroy(s.scene);
}
