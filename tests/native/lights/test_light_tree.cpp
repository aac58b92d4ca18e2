// The light tree (lights/light_tree.h) through LightSet's `tree` selection: its pmf is a
// distribution at every shading point, choose() draws by it, a light gets 0 only where it
// cannot light the point, and the edge cases (one light, zero power, lights at infinity).
//
// | scene            | contents                                                                |
// |------------------|-------------------------------------------------------------------------|
// | mixed_lights     | point lamps (with and without radius), spots (hard and blended edges),   |
// |                  | one-sided area lamps (with and without spread) and emissive triangles,  |
// |                  | at random places and orientations in [−4, 4]³, powers in [0.1, 10]      |
// | shading points   | uniform in [−5, 5]³, normals uniform on the sphere (fixed seeds)        |
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "light_placement.h"
#include "lights/area_light.h"
#include "lights/emissive_triangle.h"
#include "lights/light_set.h"
#include "lights/point_light.h"
#include "lights/spot_light.h"
#include "lights/sun_light.h"

using namespace stratum;
using stratum_test::facing;
using stratum_test::Random;

namespace {

// Lights of every kind in turn; with `directional` false only those that shine every way (point
// lamps and two-sided triangles), whose tree has no dead end (below).
void add_mixed_lights(LightSet& set, uint32_t count, uint32_t seed, bool directional = true) {
    Random rng(seed);
    for (uint32_t i = 0; i < count; ++i) {
        const Vec3 at = rng.point(4.0f);
        const Rgb power(rng.uniform(0.1f, 10.0f));
        switch (directional ? i % 6 : (i % 3 == 2 ? 5 : i % 3)) {
            case 0:
                set.add(PointLight(at, power, 0.0f), i);
                break;
            case 1:
                set.add(PointLight(at, power, 0.2f), i);
                break;
            case 2:
                set.add(
                    SpotLight(facing(at, rng.direction()), power, 0.0f, rng.uniform(0.3f, 2.0f), 0.0f, false),
                    i);
                break;
            case 3:
                set.add(
                    SpotLight(facing(at, rng.direction()), power, 0.1f, rng.uniform(0.3f, 2.0f), 0.5f, true),
                    i);
                break;
            case 4:
                set.add(AreaLight(facing(at, rng.direction(), 0.5f), 1.0f, 1.0f, (i % 12) == 4, power,
                                  (i % 12) == 4 ? 1.0f : kPi),
                        i);
                break;
            default:
                set.add(EmissiveTriangle(at, at + rng.direction() * 0.5f, at + rng.direction() * 0.5f,
                                         Rgb(rng.uniform(0.1f, 5.0f))),
                        i);
                break;
        }
    }
}

// Float rounding of a pmf summed over all lights. Each level of the descent multiplies by p_0 or
// by 1 − p_0 (each a rounded float, relative error ≤ 2^-24, and 1 − p_0 absolute error ≤ 2^-25
// more), and one product rounding per level (≤ 2^-24 relative): the two branches' sums differ
// from p_0 + (1 − p_0) = 1 by ≤ 2^-25 + 2·2^-24 < 2^-22.5 per level. With the share of the tree
// (1 − N_inf p_inf, two more roundings), the sum is within (depth + 2)·2^-22 of 1.
double sum_tolerance(const LightSet& set) { return (set.tree().depth() + 2) * std::ldexp(1.0, -22); }

}  // namespace

// Σ_i pmf(p, n, i) = 1 where the descent cannot end at an inner node whose children both have
// importance 0: lights that shine every way (a point lamp's or a two-sided triangle's bound is
// 0 only for p exactly in the tangent plane of n or of the triangle, a null set). One-sided
// lamps and spots can make such dead ends (a cluster's bound is looser than its children's, as
// in pbrt-v4 and Cycles, which then take no light either): there Σ_i pmf ≤ 1 and the rest is
// the probability of no light, which the χ² test below checks as a bin of its own.
TEST(LightTree, PmfSumsToOneAtEveryShadingPoint) {
    LightSet set;
    add_mixed_lights(set, 300, 1, false);
    set.add(SunLight(Vec3(0.3f, 0.2f, 0.9f), Rgb(2.0f), 0.05f), 1000);
    set.finalize(10.0f);
    LightSet directional;
    add_mixed_lights(directional, 300, 1);
    directional.finalize(10.0f);
    Random rng(2);
    for (int k = 0; k < 200; ++k) {
        const Vec3 p = rng.point(5.0f);
        const Vec3 n = k % 4 == 0 ? Vec3(0.0f, 0.0f, 0.0f) : rng.direction();
        double sum = 0.0, directional_sum = 0.0;
        for (uint32_t i = 0; i < set.size(); ++i) sum += set.probability(i, p, n, LightSelection::Tree);
        for (uint32_t i = 0; i < directional.size(); ++i)
            directional_sum += directional.probability(i, p, n, LightSelection::Tree);
        EXPECT_NEAR(sum, 1.0, sum_tolerance(set)) << "shading point " << k;
        EXPECT_LE(directional_sum, 1.0 + sum_tolerance(directional)) << "shading point " << k;
    }
}

// choose() against pmf(): 10^5 draws at each of 4 shading points over 60 lights and a sun. The
// statistic Σ (O − E)²/E over the lights (and the no-light outcome) with E ≥ 5 (the rest pooled in one bin,
// itself kept only if E ≥ 5) is χ² with k − 1 degrees of freedom under the hypothesis. Its 1 − 10^-4 quantile
// by Wilson and Hilferty (1931): k' (1 − 2/(9k') + z √(2/(9k')))³ with k' = k − 1 and
// z = 3.719 (the normal's 1 − 10^-4 quantile), within 1% of the exact quantile for k' ≥ 10;
// the seed is fixed, so the test is deterministic and fails by chance for 1e-4 of seeds.
TEST(LightTree, ChooseFrequenciesMatchThePmfByChiSquare) {
    LightSet set;
    add_mixed_lights(set, 60, 3);
    set.add(SunLight(Vec3(0.0f, 0.0f, 1.0f), Rgb(1.0f), 0.0f), 1000);
    set.finalize(10.0f);
    Random rng(4);
    constexpr int kDraws = 100000;
    for (int k = 0; k < 4; ++k) {
        const Vec3 p = rng.point(3.0f), n = rng.direction();
        std::vector<int> counts(set.size() + 1, 0);
        for (int d = 0; d < kDraws; ++d) {
            float choice = 0.0f;
            const uint32_t light = set.choose(rng.uniform(0.0f, 1.0f), p, n, LightSelection::Tree, &choice);
            ++counts[light];
            // The probability choose() reports is the pmf, bit for bit (MIS weighs by both).
            if (light < set.size()) {
                ASSERT_EQ(choice, set.probability(light, p, n, LightSelection::Tree));
            }
        }
        // Bin size(): no light, with the probability the pmfs leave (dead ends, see above).
        double total = 0.0;
        for (uint32_t i = 0; i < set.size(); ++i) total += set.probability(i, p, n, LightSelection::Tree);
        double chi2 = 0.0, pooled_expected = 0.0, pooled_observed = 0.0;
        int bins = 0;
        for (uint32_t i = 0; i <= set.size(); ++i) {
            const double pmf = i < set.size()
                                   ? static_cast<double>(set.probability(i, p, n, LightSelection::Tree))
                                   : 1.0 - total;
            const double expected = kDraws * std::max(0.0, pmf);
            if (expected < 5.0) {
                pooled_expected += expected;
                pooled_observed += counts[i];
                continue;
            }
            chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
            ++bins;
        }
        if (pooled_expected >= 5.0) {
            chi2 +=
                (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
            ++bins;
        }
        ASSERT_GE(bins, 11) << "too few bins for the quantile's approximation";
        const double dof = bins - 1, a = 2.0 / (9.0 * dof);
        const double quantile = dof * std::pow(1.0 - a + 3.719 * std::sqrt(a), 3.0);
        EXPECT_LT(chi2, quantile) << "shading point " << k << ", " << bins << " bins";
    }
}

// A light gets pmf 0 only where it cannot light the point: wherever the pmf is 0, no sample of
// the light reaches p with radiance along a direction off the surface's plane.
TEST(LightTree, ZeroPmfOnlyWhereTheLightCannotContribute) {
    LightSet set;
    add_mixed_lights(set, 120, 5);
    set.finalize(10.0f);
    Random rng(6);
    int zeros = 0;
    for (int k = 0; k < 300; ++k) {
        const Vec3 p = rng.point(5.0f), n = rng.direction();
        for (uint32_t i = 0; i < set.size(); ++i) {
            if (set.probability(i, p, n, LightSelection::Tree) > 0.0f) continue;
            ++zeros;
            for (int s = 0; s < 16; ++s) {
                LightSample ls;
                const Vec2 u{rng.uniform(0.0f, 1.0f), rng.uniform(0.0f, 1.0f)};
                if (!set.light(i).sample(p, n, u, TriangleSampling::Area, &ls)) continue;
                EXPECT_TRUE(ls.radiance.is_black() || dot(ls.wi, n) == 0.0f)
                    << "light " << i << " at shading point " << k << " has pmf 0 but lights it";
            }
        }
    }
    // The scene has one-sided lamps and spots: some (light, point) pairs must be cut.
    EXPECT_GT(zeros, 0);
}

TEST(LightTree, FacingAwayIsZeroFacingTowardIsNot) {
    LightSet set;
    // An area lamp at z = 1 facing down (−Z), a spot at z = 1 pointing up with a 60° cone.
    set.add(AreaLight(facing(Vec3(0.0f, 0.0f, 1.0f), Vec3(0.0f, 0.0f, -1.0f)), 0.5f, 0.5f, false, Rgb(5.0f)),
            0);
    set.add(SpotLight(facing(Vec3(3.0f, 0.0f, 1.0f), Vec3(0.0f, 0.0f, 1.0f)), Rgb(5.0f), 0.0f, kPi / 3.0f,
                      0.0f, false),
            1);
    set.finalize(10.0f);
    const Vec3 up(0.0f, 0.0f, 1.0f);
    // Below both: the area lamp lights it, the spot (shining up) cannot.
    EXPECT_EQ(set.probability(0, Vec3(0.0f, 0.0f, 0.0f), up, LightSelection::Tree), 1.0f);
    EXPECT_EQ(set.probability(1, Vec3(0.0f, 0.0f, 0.0f), up, LightSelection::Tree), 0.0f);
    // Above both: the spot's cone holds the point, the area lamp's back faces it.
    EXPECT_EQ(set.probability(0, Vec3(3.0f, 0.0f, 4.0f), up, LightSelection::Tree), 0.0f);
    EXPECT_EQ(set.probability(1, Vec3(3.0f, 0.0f, 4.0f), up, LightSelection::Tree), 1.0f);
    // Neither can reach a point above the lamp outside the spot's cone: no light is chosen.
    float choice = 1.0f;
    EXPECT_EQ(set.choose(0.5f, Vec3(-6.0f, 0.0f, 4.0f), up, LightSelection::Tree, &choice), set.size());
    EXPECT_EQ(choice, 0.0f);
}

TEST(LightTree, OneLightZeroPowerAndLightsAtInfinity) {
    const Vec3 p(0.0f, 0.0f, 0.0f), up(0.0f, 0.0f, 1.0f);
    float choice = 0.0f;
    {
        LightSet set;
        set.add(PointLight(Vec3(1.0f, 2.0f, 3.0f), Rgb(4.0f), 0.0f), 0);
        set.finalize(10.0f);
        EXPECT_EQ(set.choose(0.7f, p, up, LightSelection::Tree, &choice), 0u);
        EXPECT_EQ(choice, 1.0f);
        EXPECT_EQ(set.probability(0, p, up, LightSelection::Tree), 1.0f);
    }
    {
        // A black lamp is left out of the tree; the other takes every choice.
        LightSet set;
        set.add(PointLight(Vec3(1.0f, 0.0f, 3.0f), Rgb(0.0f), 0.0f), 0);
        set.add(PointLight(Vec3(-1.0f, 0.0f, 3.0f), Rgb(2.0f), 0.0f), 1);
        set.finalize(10.0f);
        EXPECT_EQ(set.probability(0, p, up, LightSelection::Tree), 0.0f);
        EXPECT_EQ(set.probability(1, p, up, LightSelection::Tree), 1.0f);
        for (const float u : {0.0f, 0.5f, 0.9999f})
            EXPECT_EQ(set.choose(u, p, up, LightSelection::Tree, &choice), 1u);
    }
    {
        // Nothing emits: no light is chosen.
        LightSet set;
        set.add(PointLight(Vec3(1.0f, 0.0f, 3.0f), Rgb(0.0f), 0.0f), 0);
        set.finalize(10.0f);
        EXPECT_EQ(set.choose(0.3f, p, up, LightSelection::Tree, &choice), set.size());
        EXPECT_EQ(choice, 0.0f);
    }
    {
        // A sun and the tree: ½ each (pbrt-v4's p_inf = 1/(N_inf + 1)); the sun alone: 1.
        LightSet set;
        set.add(SunLight(Vec3(0.0f, 0.0f, 1.0f), Rgb(1.0f), 0.0f), 0);
        set.add(PointLight(Vec3(1.0f, 0.0f, 3.0f), Rgb(3.0f), 0.0f), 1);
        set.add(PointLight(Vec3(-1.0f, 0.0f, 3.0f), Rgb(1.0f), 0.0f), 2);
        set.finalize(10.0f);
        EXPECT_EQ(set.probability(0, p, up, LightSelection::Tree), 0.5f);
        EXPECT_EQ(set.choose(0.25f, p, up, LightSelection::Tree, &choice), 0u);
        EXPECT_EQ(choice, 0.5f);
        const float lamps =
            set.probability(1, p, up, LightSelection::Tree) + set.probability(2, p, up, LightSelection::Tree);
        EXPECT_NEAR(lamps, 0.5f, 1e-7f);
        // The lamps are at equal distance and angle: the brighter gets 3/4 of the tree's half.
        EXPECT_NEAR(set.probability(1, p, up, LightSelection::Tree), 0.375f, 1e-6f);
        LightSet sun_only;
        sun_only.add(SunLight(Vec3(0.0f, 0.0f, 1.0f), Rgb(1.0f), 0.0f), 0);
        sun_only.finalize(10.0f);
        EXPECT_EQ(sun_only.choose(0.9f, p, up, LightSelection::Tree, &choice), 0u);
        EXPECT_EQ(choice, 1.0f);
    }
}

// The emission of light tracing has no shading point: under `tree` it chooses by power.
TEST(LightTree, EmissionChoosesByPower) {
    LightSet set;
    add_mixed_lights(set, 12, 7);
    set.finalize(10.0f);
    for (uint32_t i = 0; i < set.size(); ++i)
        EXPECT_EQ(set.probability(i, LightSelection::Tree), set.probability(i, LightSelection::Power));
}
