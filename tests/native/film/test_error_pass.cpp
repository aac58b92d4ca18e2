// The error pass (Stratum Error, film/passes.h) against the error it estimates: on the closed
// integrating sphere (test_integrating_sphere.cpp: walls of reflectance k = 0.5 emitting
// L_e = 1), each pixel is rendered with 32 seeds; the spread of its value over the seeds is its
// actual error, and the error pass of each render estimates that same quantity from one render.
//
// Squared, the two agree in expectation for independent samples: the pass is then s/√n with s²
// the unbiased sample variance of the pixel's n samples (the film's gain is 1 for the
// independent samplers), so E[pass²] = σ²/n, the variance of the pixel mean, which the seeds'
// sample variance also estimates without bias. The test compares
// the means over the pixels of both (red channel; the sphere is grey).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "render_helpers.h"
#include "setting_choices.h"

using namespace stratum_test;

namespace {

constexpr int kSize = 8;
constexpr uint32_t kSeeds = 32;

struct ErrorAgreement {
    double actual = 0, estimated = 0;  // pixel means of the seeds' variance and of the pass²
    double relative_se = 0;            // of actual / estimated, from the spread over the pixels
};

// Per pixel: the variance over the seeds of its value, and the mean over the seeds of its error
// pass squared; averaged over the pixels.
ErrorAgreement measure_error_pass(StratumScene* scene, const char* sampler, uint32_t samples,
                                  uint32_t max_bounces) {
    const size_t pixels = kSize * kSize;
    std::vector<double> sum(pixels, 0.0), sum_sq(pixels, 0.0), pass_sq(pixels, 0.0);
    for (uint32_t seed = 0; seed < kSeeds; ++seed) {
        StratumRenderer* r = nullptr;
        EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
        EXPECT_EQ(apply_settings(r, {{"width", kSize},
                                     {"height", kSize},
                                     {"samples", samples},
                                     {"max_bounces", max_bounces},
                                     {"seed", seed},
                                     {"sampler", sampler},
                                     {"passes", "Stratum Error"},
                                     // One light sample per vertex, as when the figures in the
                                     // test's comment were measured: inside the emissive sphere
                                     // the tree's default 8 splits take 3x the time per sample.
                                     {"light_tree_splits", 1}}),
                  "");
        EXPECT_TRUE(render_to_end(r)) << stratum_last_error();
        std::vector<float> rgba(pixels * 4), error(pixels * 3);
        EXPECT_EQ(stratum_renderer_read_pixels(r, rgba.data(), rgba.size()), STRATUM_OK);
        EXPECT_EQ(stratum_renderer_read_pass(r, "Stratum Error", error.data(), error.size()), STRATUM_OK);
        stratum_renderer_destroy(r);
        for (size_t p = 0; p < pixels; ++p) {
            sum[p] += rgba[4 * p];
            sum_sq[p] += static_cast<double>(rgba[4 * p]) * rgba[4 * p];
            pass_sq[p] += static_cast<double>(error[3 * p]) * error[3 * p] / kSeeds;
        }
    }
    std::vector<double> actual(pixels);
    for (size_t p = 0; p < pixels; ++p) {
        const double mean = sum[p] / kSeeds;
        actual[p] = (sum_sq[p] - kSeeds * mean * mean) / (kSeeds - 1);
    }
    const auto mean_and_relative_se = [&](const std::vector<double>& v) {
        double m = 0, m2 = 0;
        for (const double x : v) m += x / static_cast<double>(v.size());
        for (const double x : v) m2 += (x - m) * (x - m) / static_cast<double>(v.size() - 1);
        return std::pair{m, std::sqrt(m2 / static_cast<double>(v.size())) / m};
    };
    const auto [a, a_se] = mean_and_relative_se(actual);
    const auto [e, e_se] = mean_and_relative_se(pass_sq);
    return {a, e, std::sqrt(a_se * a_se + e_se * e_se)};
}

}  // namespace

TEST(ErrorPass, EstimatesTheActualErrorOfIndependentSamples) {
    IntegratingSphere s = make_closed_sphere(0.5f, 1.0f, 12);
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    for (const uint32_t bounces : {1u, 12u}) {
        const ErrorAgreement m = measure_error_pass(s.scene, "random", 16, bounces);
        const double ratio = m.actual / m.estimated;
        // Unbiased for each other (see the top): |ratio − 1| within 4 standard errors of the
        // ratio, estimated from the spread of the 64 pixels' values (a chance failure ~6e-5).
        EXPECT_NEAR(ratio, 1.0, 4.0 * m.relative_se)
            << "max_bounces " << bounces << ": actual variance " << m.actual << ", pass² " << m.estimated;
        // A real test: the pixels are noisy and the ratio is known to a few percent.
        EXPECT_GT(m.estimated, 0.0);
        EXPECT_LT(m.relative_se, 0.1);
    }
    stratum_scene_destroy(s.scene);
}

// What docs/passes.md reports: the ratio actual / estimated error (square roots of the means
// above) for every sampler. Samples of one pixel from a low-discrepancy sequence are not
// independent; the pass scales their spread by the gain it measures from the pixel's prefixes
// (film/error_estimate.h). At 16 samples of a 12-bounce path the prefixes do not yet show the
// whole gain (ratio 0.61-0.63 for sobol, zsobol, stratified, lhs, fibonacci), so on this scene
// the pass still never understates the error, for any sampler: the ratio of the variances stays
// within 4 standard errors of at most 1.
TEST(ErrorPass, MeasuresWhatThePassMeansForEverySampler) {
    IntegratingSphere s = make_closed_sphere(0.5f, 1.0f, 12);
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    for (const uint32_t bounces : {1u, 12u}) {
        for (const char* sampler : setting_choices("sampler")) {
            const ErrorAgreement m = measure_error_pass(s.scene, sampler, 16, bounces);
            std::printf("max_bounces %2u  %-18s actual/estimated error %.3f (± %.3f)\n", bounces, sampler,
                        std::sqrt(m.actual / m.estimated),
                        0.5 * m.relative_se * std::sqrt(m.actual / m.estimated));
            EXPECT_GT(m.estimated, 0.0) << sampler;
            EXPECT_LE(m.actual / m.estimated, 1.0 + 4.0 * m.relative_se)
                << sampler << ", max_bounces " << bounces;
        }
    }
    stratum_scene_destroy(s.scene);
}
