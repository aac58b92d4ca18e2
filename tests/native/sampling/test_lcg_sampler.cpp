// The `lcg` sampler and the minstd sequence under it (seed 001's "standard" sampler).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "sampling/lcg_sampler.h"
#include "sampling/sequences/minstd.h"

using namespace stratum;

TEST(MinstdSequence, FirstOutputsOfSeedOneAndTheStandardsTenThousandth) {
    const uint32_t known[] = {16807,     282475249, 1622650073, 984943658,  1144108930,
                              470211272, 101027544, 1457850878, 1458777923, 2007237709};
    std::minstd_rand0 reference(1);
    uint32_t x = 1;
    for (uint32_t k : known) {
        x = minstd::next(x);
        EXPECT_EQ(x, k);
        EXPECT_EQ(x, reference());
    }
    x = 1;
    for (int k = 0; k < 10000; ++k) x = minstd::next(x);
    EXPECT_EQ(x, 1043618065u);  // [rand.predef]: the 10000th output of minstd_rand0()
    EXPECT_EQ(minstd::advance(1, 10000), 1043618065u);
}

TEST(MinstdSequence, AdvanceEqualsStepping) {
    uint32_t x = 123456789;
    for (uint64_t k = 0; k < 3000; ++k) {
        ASSERT_EQ(minstd::advance(123456789, k), x) << k;
        x = minstd::next(x);
    }
    EXPECT_EQ(minstd::advance(42, 2147483646ull), 42u);  // the period is m − 1
}

TEST(MinstdSequence, UnitMappingIsUniformRealDistributionsWithinOneUlp) {
    // libstdc++ computes (float(x − 1) / float(2^31 − 2)) in float; we compute in double and
    // round once, so the two may differ by the float rounding of x − 1: at most 1 ulp.
    std::minstd_rand0 engine;
    std::uniform_real_distribution<float> dist(0.0f, 1.0f);
    uint32_t state = 7;
    for (int k = 0; k < 20000; ++k) {
        engine.seed(state);
        const float expected = dist(engine);
        const float ours = minstd::to_unit_float(minstd::next(state));
        ASSERT_LE(std::abs(ours - expected), std::nextafter(expected, 2.0f) - expected) << state;
        state = minstd::next(state);
    }
    EXPECT_EQ(minstd::to_unit_float(1), 0.0f);
    EXPECT_LT(minstd::to_unit_float(minstd::kModulus - 1), 1.0f);
}

TEST(LcgSampler, ValueIsTheFirstOutputOfTheHashedEngine) {
    const LcgSampler s({16, 3, 8, 8});
    for (uint32_t d = 0; d < 8; ++d) {
        const PixelSample ps{2, 5, d * 3};
        const uint32_t state = s.initial_state(ps, d);
        ASSERT_GE(state, 1u);
        ASSERT_LT(state, minstd::kModulus);
        EXPECT_EQ(s.get_1d(ps, d), minstd::to_unit_float(minstd::next(state)));
    }
}

namespace {

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
    const double n = static_cast<double>(a.size());
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    for (size_t k = 0; k < a.size(); ++k) {
        sa += a[k], sb += b[k], saa += a[k] * a[k], sbb += b[k] * b[k], sab += a[k] * b[k];
    }
    const double cov = sab / n - sa / n * sb / n;
    return cov / std::sqrt((saa / n - sa / n * sa / n) * (sbb / n - sb / n * sb / n));
}

}  // namespace

TEST(LcgSampler, NeighbouringStreamsAreUncorrelated) {
    // Pairs (value at pixel (x, y), value at (x + 1, y)), likewise for the next sample and the
    // next dimension. For independent values the sample correlation r has standard error
    // 1/sqrt(N); accept |r| < 4/sqrt(N) (fixed seed, so deterministic).
    const LcgSampler s({64, 11, 256, 256});
    const int n = 1 << 16;
    std::vector<double> a, right, next_sample, next_dim;
    for (int k = 0; k < n; ++k) {
        const PixelSample ps{static_cast<uint32_t>(k % 256), static_cast<uint32_t>(k / 256), 5};
        a.push_back(s.get_1d(ps, 8));
        right.push_back(s.get_1d({ps.x + 1, ps.y, ps.index}, 8));
        next_sample.push_back(s.get_1d({ps.x, ps.y, ps.index + 1}, 8));
        next_dim.push_back(s.get_1d(ps, 9));
    }
    const double bound = 4.0 / std::sqrt(static_cast<double>(n));
    EXPECT_LT(std::abs(correlation(a, right)), bound);
    EXPECT_LT(std::abs(correlation(a, next_sample)), bound);
    EXPECT_LT(std::abs(correlation(a, next_dim)), bound);

    // The test has power: seeding with the linear combination 1 + x + 256·y (coursework style)
    // makes neighbouring pixels' first outputs almost equal (r ≈ 1).
    std::vector<double> la, lb;
    for (int k = 0; k < n; ++k) {
        const auto seed = static_cast<uint32_t>(1 + k);
        la.push_back(minstd::to_unit_float(minstd::next(seed)));
        lb.push_back(minstd::to_unit_float(minstd::next(seed + 1)));
    }
    EXPECT_GT(correlation(la, lb), 0.99);
}
