// Cycles' Light Paths limits (integrators/light_path_limits.h): per-kind bounce limits and the
// clamping of direct and indirect light, on scenes whose answer is known in closed form.
//
// Tolerance: as test_integrating_sphere.cpp, the image mean over P independent pixels (the
// `random` sampler) is within 4 s/√P of its expectation, s the pixel values' standard deviation;
// a correct renderer fails by chance with probability 6e-5 per assertion. Where a clamp of
// 1e-6 scales contributions, each of them is at most 3e-6 in the sum of its channels, and a
// pixel sums at most (max_bounces + 2) × 3 of them per sample: the bias bound added is 1e-4.
#include <gtest/gtest.h>

#include "integrators/light_path_limits.h"
#include "render_helpers.h"

using namespace stratum;
using namespace stratum_test;

TEST(BounceCounts, EachKindCountsAgainstItsOwnLimitAndTheTotal) {
    LightPathLimits limits;
    limits.diffuse = 1;
    limits.glossy = 0;
    BounceCounts counts;
    counts.scatter(ScatterKind::Transparent);
    EXPECT_EQ(counts.total(), 0u);
    counts.scatter(ScatterKind::Diffuse);
    EXPECT_FALSE(counts.exhausted(12, limits));
    // One more diffuse scattering would pass its limit; glossy ones never fit.
    EXPECT_EQ(counts.kinds_within(limits), scatter_kind_bit(ScatterKind::Transmission));
    counts.scatter(ScatterKind::Diffuse);
    EXPECT_TRUE(counts.exhausted(12, limits));
    BounceCounts total;
    total.scatter(ScatterKind::Transmission);
    total.scatter(ScatterKind::Transmission);
    EXPECT_FALSE(total.exhausted(2, LightPathLimits{}));
    EXPECT_TRUE(total.exhausted(1, LightPathLimits{}));
}

TEST(ClampContribution, ScalesTheSumOfTheChannelsKeepingTheColour) {
    // Cycles' film_clamp_light: |r| + |g| + |b| <= 3 × limit, not each channel.
    const Rgb red = clamp_contribution(Rgb(3.0f, 0.0f, 0.0f), 0.5f);
    EXPECT_FLOAT_EQ(red.r, 1.5f);
    EXPECT_FLOAT_EQ(red.g, 0.0f);
    const Rgb mixed = clamp_contribution(Rgb(4.0f, 2.0f, 0.0f), 1.0f);
    EXPECT_FLOAT_EQ(mixed.r, 2.0f);
    EXPECT_FLOAT_EQ(mixed.g, 1.0f);
    const Rgb under = clamp_contribution(Rgb(1.0f, 1.0f, 0.5f), 1.0f);
    EXPECT_FLOAT_EQ(under.b, 0.5f);
    const Rgb off = clamp_contribution(Rgb(100.0f, 0.0f, 0.0f), 0.0f);
    EXPECT_FLOAT_EQ(off.r, 100.0f);
}

// Integrating sphere B with diffuse walls: a diffuse limit N caps the series as max_bounces N
// does (L = L_e Σ_{m=0}^{N+1} k^m); the glossy and transmission limits do not touch it.
TEST(LightPathLimits, DiffuseLimitCapsTheSeriesOfADiffuseSphere) {
    IntegratingSphere s = make_closed_sphere(0.5f, 1.0f);
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    const Settings base{{"width", 16}, {"height", 16}, {"samples", 64}, {"max_bounces", 24}, {"seed", 5u}};
    for (const uint32_t limit : {0u, 1u, 3u}) {
        Settings settings = base;
        settings.emplace_back("diffuse_bounces", limit);
        const Measurement m = measure(s.scene, settings);
        ASSERT_TRUE(m.error.empty()) << m.error;
        const double expected = sphere_b_radiance(1.0, 0.5, 0.0, limit);
        EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error) << "diffuse_bounces " << limit;
    }
    Settings others = base;
    others.emplace_back("glossy_bounces", 0u);
    others.emplace_back("transmission_bounces", 0u);
    const Measurement m = measure(s.scene, others);
    ASSERT_TRUE(m.error.empty()) << m.error;
    EXPECT_NEAR(m.mean, sphere_b_radiance(1.0, 0.5, 0.0, 24), 4.0 * m.standard_error);
    stratum_scene_destroy(s.scene);
}

// Emission seen directly is direct light: a red wall of radiance (3, 0, 0) clamped at 0.5 shows
// (1.5, 0, 0), the channels' mean at the clamp (a per-channel clamp would show 0.5); clamp 2
// leaves it (mean 1), and the indirect clamp does not apply to it.
TEST(LightPathLimits, DirectClampScalesEmissionSeenByTheCamera) {
    StratumMaterialDesc wall = diffuse_grey(0.0f);
    wall.model = STRATUM_MATERIAL_EMISSION;
    wall.emission[0] = 3.0f;
    StratumScene* scene = make_sphere_interior(wall, 8, 0.0f, 0.0f, 0.0f);
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    for (const auto& [name, clamp, want] : {std::tuple<const char*, double, float>{"clamp_direct", 0.5, 1.5f},
                                            {"clamp_direct", 2.0, 3.0f},
                                            {"clamp_indirect", 0.5, 3.0f}}) {
        const RenderOutput out =
            render(scene, Settings{{"width", 4}, {"height", 4}, {"samples", 2}, {name, clamp}});
        ASSERT_TRUE(out.error.empty()) << out.error;
        for (size_t p = 0; p < out.rgba.size(); p += 4) {
            EXPECT_FLOAT_EQ(out.rgba[p], want) << name << " " << clamp;
            EXPECT_EQ(out.rgba[p + 1], 0.0f);
        }
    }
    stratum_scene_destroy(scene);
}

// What is direct: the emission seen, light samples at the first vertex and emission found after
// one scattering. In sphere B with one bounce these give L_e (1 + k); light samples at the
// second vertex and emission after two scatterings, MIS-weighted pairs of the same paths, give
// the remaining L_e k² (Cycles' split of its Direct and Indirect passes). Clamping indirect light
// to nothing leaves L_e (1 + k) = 1.5, clamping direct light to nothing L_e k² = 0.25.
TEST(LightPathLimits, IndirectClampLeavesTheDirectLightOfASphere) {
    IntegratingSphere s = make_closed_sphere(0.5f, 1.0f);
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    const Settings base{{"width", 16}, {"height", 16}, {"samples", 64}, {"max_bounces", 1}, {"seed", 9u}};
    constexpr double kClampBias = 1e-4;  // the header's bound
    Settings indirect = base;
    indirect.emplace_back("clamp_indirect", 1e-6);
    const Measurement m = measure(s.scene, indirect);
    ASSERT_TRUE(m.error.empty()) << m.error;
    EXPECT_NEAR(m.mean, 1.5, 4.0 * m.standard_error + kClampBias);
    Settings direct = base;
    direct.emplace_back("clamp_direct", 1e-6);
    const Measurement d = measure(s.scene, direct);
    ASSERT_TRUE(d.error.empty()) << d.error;
    EXPECT_NEAR(d.mean, 0.25, 4.0 * d.standard_error + kClampBias);
    stratum_scene_destroy(s.scene);
}

TEST(LightPathLimits, LimitsAndClampsKeepImagesBitIdenticalForAnyThreadCount) {
    IntegratingSphere s = make_closed_sphere(0.7f, 2.0f);
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    const auto with_threads = [&](uint32_t threads) {
        return render(s.scene, Settings{{"width", 24},
                                        {"height", 16},
                                        {"samples", 8},
                                        {"diffuse_bounces", 2u},
                                        {"glossy_bounces", 1u},
                                        {"clamp_direct", 1.0},
                                        {"clamp_indirect", 0.3},
                                        {"threads", threads},
                                        {"seed", 4u}});
    };
    const RenderOutput one = with_threads(1), two = with_threads(2);
    ASSERT_TRUE(one.error.empty()) << one.error;
    EXPECT_EQ(one.rgba, two.rgba);
    stratum_scene_destroy(s.scene);
}
