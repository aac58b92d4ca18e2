// `stratified` and `lhs`: exact strata counts, the keyed permutation, get_1d/get_2d agreement
// for all samplers of this family (lcg, stratified, lhs, bluenoise, fibonacci, fibonacci_static),
// and their registry entries.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sampling/bluenoise_sampler.h"
#include "sampling/fibonacci_sampler.h"
#include "sampling/hash.h"
#include "sampling/lcg_sampler.h"
#include "sampling/lhs_sampler.h"
#include "sampling/sampler_registry.h"
#include "sampling/stratified_sampler.h"

using namespace stratum;

namespace {

uint32_t bin(float u, uint32_t n) { return static_cast<uint32_t>(static_cast<double>(u) * n); }

}  // namespace

TEST(StratifiedPermutation, BijectiveForLengths2To1023) {
    for (uint32_t n = 2; n < 1024; ++n) {
        for (uint64_t key : {0ull, 1ull, 0x123456789abcdefull, ~0ull - n}) {
            std::vector<int> hit(n, 0);
            for (uint32_t i = 0; i < n; ++i) {
                const uint32_t j = permute_index(i, n, key);
                ASSERT_LT(j, n);
                ++hit[j];
            }
            for (uint32_t j = 0; j < n; ++j) ASSERT_EQ(hit[j], 1) << "n=" << n << " j=" << j;
        }
    }
    EXPECT_EQ(permute_index(0, 1, 99), 0u);
}

TEST(StratifiedPermutation, EveryImageEquallyLikelyOverKeys) {
    // For K random keys, the count of keys mapping i to j is Binomial(K, 1/n) for a uniform
    // permutation: mean K/n, sigma sqrt(K (1/n)(1 − 1/n)). Accept every one of the n² counts
    // within 5 sigma (two-sided tail 5.7e-7 per count, < 2e-4 over the 8² + 7² + 12² counts).
    const uint32_t keys = 20000;
    for (uint32_t n : {8u, 7u, 12u}) {
        std::vector<uint32_t> count(n * n, 0);
        for (uint32_t k = 0; k < keys; ++k)
            for (uint32_t i = 0; i < n; ++i) ++count[i * n + permute_index(i, n, hash_words(k, 0xabcu))];
        const double p = 1.0 / n, sigma = std::sqrt(keys * p * (1 - p));
        for (uint32_t c : count) EXPECT_NEAR(c, keys * p, 5 * sigma) << "n=" << n;
    }
}

TEST(StratifiedSampler, GridIsSquareOrTheCeilGrid) {
    struct Case {
        uint32_t spp, nx, ny;
    };
    for (const Case c : {Case{1, 1, 1}, Case{2, 2, 1}, Case{3, 2, 2}, Case{4, 2, 2}, Case{7, 3, 3},
                         Case{8, 4, 2}, Case{12, 4, 3}, Case{14, 4, 4}, Case{16, 4, 4}, Case{32, 8, 4},
                         Case{100, 10, 10}, Case{128, 16, 8}, Case{1024, 32, 32}}) {
        const StrataGrid g = strata_grid(c.spp);
        EXPECT_EQ(g.nx, c.nx) << c.spp;
        EXPECT_EQ(g.ny, c.ny) << c.spp;
    }
}

TEST(StratifiedSampler, EveryCellHoldsOneSampleOrAtMostOneOnTheCeilGrid) {
    // Exact products (aspect ≤ 2): every one of the spp cells holds exactly one sample.
    // Ceil grids (3, 5, 7, 11, 14, ...): spp distinct cells of the nx·ny hold one sample each.
    for (uint32_t spp : {1u, 2u, 3u, 4u, 5u, 7u, 8u, 11u, 12u, 14u, 16u, 32u, 64u, 100u, 128u, 256u}) {
        const StratifiedSampler s({spp, 7, 4, 4});
        const StrataGrid g = s.grid();
        const bool exact = g.nx * g.ny == spp;
        for (uint32_t pixel = 0; pixel < 3; ++pixel) {
            for (uint32_t pair : {0u, 2u, 8u, 10u, 16u, 40u}) {
                ASSERT_FALSE(pair_holds_1d_quantities(pair));
                std::vector<int> hit(g.nx * g.ny, 0);
                for (uint32_t i = 0; i < spp; ++i) {
                    const Vec2 v = s.get_2d({pixel, 1, i}, pair);
                    const uint32_t c = bin(v.x, g.nx) + g.nx * bin(v.y, g.ny);
                    ASSERT_EQ(c, s.cell({pixel, 1, i}, pair));
                    ++hit[c];
                }
                int used = 0;
                for (int h : hit) {
                    ASSERT_LE(h, 1) << "spp " << spp << " pair " << pair;
                    used += h;
                }
                ASSERT_EQ(used, static_cast<int>(spp));
                if (exact) {
                    ASSERT_EQ(used, static_cast<int>(g.nx * g.ny));
                }
            }
        }
    }
}

TEST(StratifiedSampler, PairsOfOneDQuantitiesGetSppStrataPerDimension) {
    // (4, 5) time, (6, 7) light choice + roulette, (12, 13) lobe: 1D strata of spp, as `lhs`.
    const uint32_t spp = 24;
    const StratifiedSampler s({spp, 3, 4, 4});
    for (uint32_t pair : {4u, 6u, 12u, 14u + 8u}) {
        ASSERT_TRUE(pair_holds_1d_quantities(pair));
        for (uint32_t k = 0; k < 2; ++k) {
            std::vector<int> hit(spp, 0);
            for (uint32_t i = 0; i < spp; ++i) {
                const float u = s.get_1d({1, 2, i}, pair + k);
                ASSERT_EQ(u, latin_hypercube_value({1, 2, i}, pair + k, spp, 3));
                ++hit[bin(u, spp)];
            }
            for (int h : hit) ASSERT_EQ(h, 1) << pair + k;
        }
    }
}

TEST(StratifiedSampler, EachBlockOfSppIsStratifiedAndShuffledAnew) {
    const uint32_t spp = 16;
    const StratifiedSampler s({spp, 0, 2, 2});
    int same = 0;
    for (uint32_t block = 0; block < 4; ++block) {
        std::vector<int> hit(spp, 0);
        for (uint32_t i = 0; i < spp; ++i) {
            const PixelSample ps{0, 0, block * spp + i};
            ++hit[s.cell(ps, 8)];
            same += block > 0 && s.cell(ps, 8) == s.cell({0, 0, i}, 8);
        }
        for (int h : hit) ASSERT_EQ(h, 1);
    }
    EXPECT_LT(same, 16);  // 48 comparisons, 3 expected by chance
}

TEST(StratifiedSampler, JitterIsUniformWithinTheCell) {
    // The offset within the cell, u·nx − cx, is U[0,1): its mean over N samples is 1/2 with
    // standard error sqrt(1/12 / N); accept within 4 standard errors.
    const uint32_t spp = 16;
    const StratifiedSampler s({spp, 5, 64, 64});
    double sum = 0;
    int n = 0;
    for (uint32_t p = 0; p < 4096; ++p)
        for (uint32_t i = 0; i < spp; ++i, ++n) {
            const Vec2 v = s.get_2d({p % 64, p / 64, i}, 2);
            sum += v.x * 4.0 - std::floor(v.x * 4.0);
        }
    EXPECT_NEAR(sum / n, 0.5, 4.0 * std::sqrt(1.0 / 12.0 / n));
}

TEST(LhsSampler, EveryStratumOfEveryDimensionHoldsOneSample) {
    for (uint32_t spp : {1u, 2u, 3u, 7u, 16u, 100u, 256u}) {
        const LhsSampler s({spp, 9, 8, 8});
        for (uint32_t pixel = 0; pixel < 4; ++pixel)
            for (uint32_t d = 0; d < 32; ++d) {
                std::vector<int> hit(spp, 0);
                for (uint32_t i = 0; i < spp; ++i) {
                    const float u = s.get_1d({pixel, 3, i}, d);
                    ASSERT_EQ(bin(u, spp), latin_hypercube_stratum({pixel, 3, i}, d, spp, 9));
                    ++hit[bin(u, spp)];
                }
                for (int h : hit) ASSERT_EQ(h, 1) << "spp " << spp << " dim " << d;
            }
    }
}

TEST(LhsSampler, DimensionsAndPixelsArePermutedIndependently) {
    const uint32_t spp = 32;
    auto order = [&](uint32_t x, uint32_t d) {
        std::vector<uint32_t> o;
        for (uint32_t i = 0; i < spp; ++i) o.push_back(latin_hypercube_stratum({x, 0, i}, d, spp, 1));
        return o;
    };
    EXPECT_NE(order(0, 0), order(0, 1));
    EXPECT_NE(order(0, 0), order(1, 0));
    EXPECT_NE(order(0, 0), order(0, 0 + 32));
}

namespace {

struct Named {
    std::string name;
    std::function<std::unique_ptr<Sampler>(const SamplerSettings&)> make;
};

std::vector<Named> family() {
    return {{"lcg", [](const SamplerSettings& s) { return std::make_unique<LcgSampler>(s); }},
            {"stratified", [](const SamplerSettings& s) { return std::make_unique<StratifiedSampler>(s); }},
            {"lhs", [](const SamplerSettings& s) { return std::make_unique<LhsSampler>(s); }},
            {"bluenoise", [](const SamplerSettings& s) { return std::make_unique<BlueNoiseSampler>(s); }},
            {"fibonacci", [](const SamplerSettings& s) { return std::make_unique<FibonacciSampler>(s); }},
            {"fibonacci_static",
             [](const SamplerSettings& s) { return std::make_unique<StaticFibonacciSampler>(s); }}};
}

}  // namespace

TEST(StratifiedFamily, Get1dOfEitherMemberEqualsTheComponentOfGet2d) {
    for (const Named& n : family()) {
        for (uint32_t spp : {1u, 6u, 16u}) {
            const auto s = n.make({spp, 4, 16, 16});
            for (uint32_t i = 0; i < 2 * spp; ++i)
                for (uint32_t d = 0; d < 40; ++d) {
                    const PixelSample ps{i % 5, 3, i};
                    const Vec2 v = s->get_2d(ps, d & ~1u);
                    ASSERT_EQ(s->get_1d(ps, d), (d & 1u) ? v.y : v.x) << n.name << " dim " << d;
                }
        }
    }
}

TEST(StratifiedFamily, RegisteredInMenuOrder) {
    const std::vector<std::string> order = {"random",    "lcg",       "stratified",      "lhs",
                                            "bluenoise", "fibonacci", "fibonacci_static"};
    const auto reg = sampler_registry();
    ASSERT_FALSE(reg.empty());
    EXPECT_EQ(std::string(reg[0].info.name), "random");
    std::vector<size_t> position;
    for (const std::string& name : order) {
        const SamplerEntry* e = find_sampler(name);
        ASSERT_NE(e, nullptr) << name;
        position.push_back(static_cast<size_t>(e - reg.data()));
        const auto s = e->create({4, 1, 2, 2});
        const float u = s->get_1d({1, 1, 3}, 7);
        EXPECT_TRUE(u >= 0.0f && u < 1.0f) << name;
    }
    for (size_t k = 1; k < position.size(); ++k) EXPECT_LT(position[k - 1], position[k]) << order[k];
}
