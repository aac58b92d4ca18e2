// The `random` sampler: values in [0,1), uniform, independent across dimensions and pixels,
// and a pure function of (pixel, sample, dimension, seed) — same value in any visiting order.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sampling/independent_sampler.h"
#include "sampling/sampler_registry.h"

using namespace stratum;

TEST(IndependentSampler, SameArgumentsSameValueInAnyOrder) {
    const IndependentSampler s({16, 5, 8, 8});
    std::vector<float> forward;
    for (uint32_t i = 0; i < 16; ++i) forward.push_back(s.get_1d({1, 5, i}, 3));
    (void)s.get_2d({7, 2, 4}, 6);
    for (uint32_t i = 16; i-- > 0;) EXPECT_EQ(s.get_1d({1, 5, i}, 3), forward[i]);
}

TEST(IndependentSampler, UniformMeanAndVarianceAndNoCorrelation) {
    // N values of U[0,1): mean 1/2 with standard error sqrt(1/12 / N); the sample correlation
    // of two independent dimensions has standard error 1/sqrt(N). Accept within 4 sigma.
    const IndependentSampler s({1, 42, 64, 64});
    const int n = 1 << 16;
    double sum = 0, sum2 = 0, cross = 0, sum_b = 0, sum_b2 = 0;
    float max_value = 0;
    for (int k = 0; k < n; ++k) {
        const PixelSample ps{static_cast<uint32_t>(k % 64), static_cast<uint32_t>(k / 64 % 64),
                             static_cast<uint32_t>(k / 4096)};
        const double a = s.get_1d(ps, 4), b = s.get_1d(ps, 5);
        max_value = std::max(max_value, static_cast<float>(std::max(a, b)));
        ASSERT_GE(a, 0.0);
        sum += a;
        sum2 += a * a;
        sum_b += b;
        sum_b2 += b * b;
        cross += a * b;
    }
    EXPECT_LT(max_value, 1.0f);
    const double mean = sum / n, var = sum2 / n - mean * mean;
    EXPECT_NEAR(mean, 0.5, 4.0 * std::sqrt(1.0 / 12.0 / n));
    // Variance of U[0,1) is 1/12; its estimator's standard error is sqrt((1/80 - 1/144)/N).
    EXPECT_NEAR(var, 1.0 / 12.0, 4.0 * std::sqrt((1.0 / 80.0 - 1.0 / 144.0) / n));
    const double mean_b = sum_b / n, var_b = sum_b2 / n - mean_b * mean_b;
    const double r = (cross / n - mean * mean_b) / std::sqrt(var * var_b);
    EXPECT_LT(std::abs(r), 4.0 / std::sqrt(static_cast<double>(n)));
}

TEST(IndependentSampler, SeedChangesEveryValue) {
    const IndependentSampler a({4, 1, 4, 4}), b({4, 2, 4, 4});
    int equal = 0;
    for (uint32_t i = 0; i < 256; ++i)
        equal += a.get_1d({i % 4, i / 4 % 4, i / 16}, 0) == b.get_1d({i % 4, i / 4 % 4, i / 16}, 0);
    EXPECT_LE(equal, 1);
}

TEST(SamplerRegistry, RandomIsRegistered) {
    ASSERT_NE(find_sampler("random"), nullptr);
    EXPECT_EQ(find_sampler("nonexistent"), nullptr);
    const auto sampler = find_sampler("random")->create({4, 0, 2, 2});
    EXPECT_GE(sampler->get_1d({0, 0, 0}, 0), 0.0f);
}
