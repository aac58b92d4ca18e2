// Properties every sampler must have, run over EVERY entry of sampler_registry(), so a sampler
// added later is covered without touching this file (research/samplers.md §3, §5):
//   * values in [0,1), never 1.0 (pitfall 8);
//   * a pure function of (pixel, index, dimension, seed): bit-identical in any visiting order
//     and from a second instance (pbrt-v4 `ConsistentValues`);
//   * get_1d(s, d) == get_2d(s, d & ~1)[d & 1]: one value per dimension, however it is asked;
//   * per-dimension means near 1/2 and pairwise correlations between dimensions near 0.
//
// Statistical bounds. For N independent U[0,1) values the mean has standard error
// σ = sqrt(1/12 / N) and the sample correlation of two independent dimensions 1/√N; we accept
// 4σ and 4/√N (a false alarm has probability 6e-5 per check for an independent sampler; the
// seeds are fixed, so a pass is reproducible). For low-discrepancy samplers these bounds are
// valid upper bounds, not tight ones: the mean of x and the product x·y are smooth integrands
// whose quasi-Monte Carlo error is O((log N)^s / N) (Koksma–Hlawka), and Owen-scrambled nets
// are never worse than a constant times Monte Carlo (Owen 1997b) — far below 4/√N at
// N = 65536. A failure therefore means a real defect: a biased warp of the bits, a constant
// dimension, or dimensions that share one stream (pitfall 1, Cycles #109907).
//
// The values are drawn over many pixels × samples (32 × 32 pixels × 64 samples = 65536), which
// is what an image sees. Per-entry expectations (kExpectations) handle samplers for which that
// set does not make sense:
//   * fibonacci_static: every pixel gets the same lattice (seed 000 table 3, "static seed"), so
//     values across pixels are P copies of one pixel's points, not N = P·spp independent draws;
//     the mean/correlation checks use one pixel with spp = 1024 and N = 1024 instead.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "sampling/sampler_registry.h"

using namespace stratum;

namespace {

struct Expectation {
    const char* name;
    bool same_points_in_every_pixel;  // statistics over one pixel's samples only
};

// Samplers that need something other than the default (statistics across many pixels).
constexpr Expectation kExpectations[] = {
    {"fibonacci_static", true},
};

Expectation expectation_for(const std::string& name) {
    for (const Expectation& e : kExpectations)
        if (name == e.name) return e;
    return {nullptr, false};
}

std::vector<std::string> registered_names() {
    std::vector<std::string> names;
    for (const SamplerEntry& e : sampler_registry()) names.emplace_back(e.info.name);
    return names;
}

// Settings the checks run under: power-of-two and odd sample counts, several seeds.
constexpr SamplerSettings kSettings[] = {
    {1, 0, 16, 16}, {16, 7, 16, 16}, {64, 12345, 32, 32}, {100, 3, 16, 9}, {256, 0xdeadbeef, 8, 8},
};
constexpr uint32_t kDimensions = 40;  // camera block and four bounce blocks

class Registry : public ::testing::TestWithParam<std::string> {
protected:
    std::unique_ptr<Sampler> create(const SamplerSettings& settings) const {
        const SamplerEntry* entry = find_sampler(GetParam());
        return entry ? entry->create(settings) : nullptr;
    }
};

TEST_P(Registry, ValuesInUnitIntervalNeverOne) {
    for (const SamplerSettings& settings : kSettings) {
        const auto sampler = create(settings);
        ASSERT_NE(sampler, nullptr);
        for (uint32_t y = 0; y < settings.height; y += 3) {
            for (uint32_t x = 0; x < settings.width; x += 2) {
                for (uint32_t i = 0; i < settings.samples; ++i) {
                    for (uint32_t d = 0; d < kDimensions; d += 2) {
                        const PixelSample ps{x, y, i};
                        const Vec2 v = sampler->get_2d(ps, d);
                        const float w = sampler->get_1d(ps, d);
                        ASSERT_TRUE(v.x >= 0.0f && v.x < 1.0f && v.y >= 0.0f && v.y < 1.0f && w >= 0.0f &&
                                    w < 1.0f)
                            << "pixel (" << x << "," << y << ") sample " << i << " dim " << d << ": " << v.x
                            << ", " << v.y << ", " << w << " (spp " << settings.samples << ")";
                    }
                }
            }
        }
    }
}

TEST_P(Registry, SameArgumentsGiveBitIdenticalValuesInAnyVisitingOrder) {
    // pbrt-v4 ConsistentValues: record pixel (1,5) forwards, visit another pixel, revisit
    // (1,5) with samples and dimensions in reverse, and again from a fresh instance.
    for (const SamplerSettings& settings : kSettings) {
        const auto sampler = create(settings);
        const auto fresh = create(settings);
        ASSERT_NE(sampler, nullptr);
        const uint32_t px = 1 % settings.width, py = 5 % settings.height;
        std::vector<float> forward;
        for (uint32_t i = 0; i < settings.samples; ++i) {
            for (uint32_t d = 0; d < kDimensions; ++d) forward.push_back(sampler->get_1d({px, py, i}, d));
            for (uint32_t d = 0; d < kDimensions; d += 2) {
                const Vec2 v = sampler->get_2d({px, py, i}, d);
                forward.push_back(v.x);
                forward.push_back(v.y);
            }
        }
        const uint32_t ox = 7 % settings.width, oy = 2 % settings.height;
        for (uint32_t i = 0; i < settings.samples; ++i)
            for (uint32_t d = 0; d < kDimensions; ++d) (void)sampler->get_1d({ox, oy, i}, d);
        const size_t per_sample = kDimensions + kDimensions;
        for (const Sampler* s : {sampler.get(), fresh.get()}) {
            for (uint32_t i = settings.samples; i-- > 0;) {
                const float* expected = &forward[i * per_sample];
                for (uint32_t d = kDimensions; d-- > 0;) {
                    const float v = s->get_1d({px, py, i}, d);
                    ASSERT_EQ(std::memcmp(&v, &expected[d], sizeof v), 0)
                        << "sample " << i << " dim " << d << " spp " << settings.samples;
                }
                for (uint32_t d = kDimensions; d > 0;) {
                    d -= 2;
                    const Vec2 v = s->get_2d({px, py, i}, d);
                    ASSERT_EQ(std::memcmp(&v.x, &expected[kDimensions + d], sizeof v.x), 0) << i << " " << d;
                    ASSERT_EQ(std::memcmp(&v.y, &expected[kDimensions + d + 1], sizeof v.y), 0)
                        << i << " " << d;
                }
            }
        }
    }
}

TEST_P(Registry, OneDimensionalAndPairValuesAgree) {
    for (const SamplerSettings& settings : kSettings) {
        const auto sampler = create(settings);
        ASSERT_NE(sampler, nullptr);
        for (uint32_t k = 0; k < 64; ++k) {
            const PixelSample ps{(3 * k) % settings.width, (5 * k + 1) % settings.height,
                                 k % settings.samples};
            for (uint32_t d = 0; d < kDimensions; ++d) {
                const Vec2 pair = sampler->get_2d(ps, d & ~1u);
                const float one = sampler->get_1d(ps, d);
                ASSERT_EQ(one, (d & 1u) ? pair.y : pair.x)
                    << "pixel (" << ps.x << "," << ps.y << ") sample " << ps.index << " dim " << d;
            }
        }
    }
}

TEST_P(Registry, DimensionMeansAreHalfAndDimensionsUncorrelated) {
    const Expectation expect = expectation_for(GetParam());
    // One pixel × 1024 samples where pixels share their points, else 32² pixels × 64 samples.
    const SamplerSettings settings = expect.same_points_in_every_pixel ? SamplerSettings{1024, 99, 32, 32}
                                                                       : SamplerSettings{64, 99, 32, 32};
    const uint32_t pixels = expect.same_points_in_every_pixel ? 1 : settings.width * settings.height;
    const auto sampler = create(settings);
    ASSERT_NE(sampler, nullptr);
    constexpr uint32_t kDims = 16;
    std::vector<std::vector<double>> values(kDims);
    for (uint32_t p = 0; p < pixels; ++p) {
        for (uint32_t i = 0; i < settings.samples; ++i) {
            const PixelSample ps{p % settings.width, p / settings.width, i};
            for (uint32_t d = 0; d < kDims; ++d) values[d].push_back(sampler->get_1d(ps, d));
        }
    }
    const auto n = static_cast<double>(values[0].size());
    std::vector<double> mean(kDims), sd(kDims);
    for (uint32_t d = 0; d < kDims; ++d) {
        double sum = 0, sum2 = 0;
        for (const double v : values[d]) {
            sum += v;
            sum2 += v * v;
        }
        mean[d] = sum / n;
        sd[d] = std::sqrt(std::max(0.0, sum2 / n - mean[d] * mean[d]));
        EXPECT_NEAR(mean[d], 0.5, 4.0 * std::sqrt(1.0 / 12.0 / n)) << "dimension " << d << ", N = " << n;
        EXPECT_GT(sd[d], 0.0) << "dimension " << d << " is constant";
    }
    const std::pair<uint32_t, uint32_t> kPairs[] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {2, 9}, {1, 14}};
    for (const auto& [a, b] : kPairs) {
        double cross = 0;
        for (size_t k = 0; k < values[a].size(); ++k)
            cross += (values[a][k] - mean[a]) * (values[b][k] - mean[b]);
        const double r = cross / n / (sd[a] * sd[b]);
        EXPECT_LT(std::abs(r), 4.0 / std::sqrt(n)) << "dimensions " << a << ", " << b << ": r = " << r;
    }
}

INSTANTIATE_TEST_SUITE_P(SamplerProperties, Registry, ::testing::ValuesIn(registered_names()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

}  // namespace
