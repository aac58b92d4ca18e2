// The light tree's adaptive splitting (lights/light_tree.h): the per-light probabilities pmf()
// gives under a cut are the frequencies with which the cut's sub-estimators take each light, and
// they sum to one per cut node.
//
// | scene            | contents                                                                |
// |------------------|-------------------------------------------------------------------------|
// | lights           | 64 lights at random places in [−4, 4]³ (seed 11), powers in [0.1, 10]:  |
// |                  | point lamps (radius 0 and 0.2), spots, one-sided area lamps, emissive    |
// |                  | triangles in turn; or only point lamps (the sum test)                    |
// | shading points   | uniform in [−3, 3]³ (inside the lights' spread, so the cut fills up),    |
// |                  | normals uniform on the sphere (fixed seeds)                             |
// | cut              | at most 8 nodes (light_tree_splits = 8)                                 |
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "light_placement.h"
#include "lights/area_light.h"
#include "lights/emissive_triangle.h"
#include "lights/light_set.h"
#include "lights/point_light.h"
#include "lights/spot_light.h"

using namespace stratum;
using stratum_test::facing;
using stratum_test::Random;

namespace {

constexpr uint32_t kMaxCut = 8;

void add_lights(LightSet& set, uint32_t count, uint32_t seed, bool points_only) {
    Random rng(seed);
    for (uint32_t i = 0; i < count; ++i) {
        const Vec3 at = rng.point(4.0f);
        const Rgb power(rng.uniform(0.1f, 10.0f));
        switch (points_only ? i % 2 : i % 5) {
            case 0:
                set.add(PointLight(at, power, 0.0f), i);
                break;
            case 1:
                set.add(PointLight(at, power, 0.2f), i);
                break;
            case 2:
                set.add(
                    SpotLight(facing(at, rng.direction()), power, 0.1f, rng.uniform(0.3f, 2.0f), 0.5f, true),
                    i);
                break;
            case 3:
                set.add(AreaLight(facing(at, rng.direction(), 0.5f), 1.0f, 1.0f, false, power, kPi), i);
                break;
            default:
                set.add(EmissiveTriangle(at, at + rng.direction() * 0.5f, at + rng.direction() * 0.5f,
                                         Rgb(rng.uniform(0.1f, 5.0f))),
                        i);
                break;
        }
    }
}

}  // namespace

// Each cut node's sub-estimator draws once per trial (an independent u each), 2·10^5 trials at
// each of 4 shading points. Light i lies below exactly one cut node, so its count over the trials
// is Binomial(D, p_i) with p_i = pmf(p, n, i, 8): mean D p_i, σ_i = √(D p_i (1 − p_i)). Lights
// with D p_i ≥ 25 are tested one by one, the rest pooled (the pooled count's variance is at most
// D Σ p_i (1 − p_i): counts of lights under one node are multinomial, negatively correlated, and
// nodes draw independently), a bin kept if its expectation is ≥ 25. Tolerance 5σ: a normal tail
// of 5.7e-7; for the smallest bins (mean 25, Poisson-like) the upper tail P(X ≥ 50) ≈ 2e-5, so
// over ≤ 4·65 bins the chance that a correct pmf fails is ≤ 5e-3, and the seeds are fixed (the
// test is deterministic). A light whose pmf is 0 must never be drawn.
TEST(LightTreeSplit, PmfMatchesTheFrequenciesOfTheCutsChoices) {
    LightSet set;
    add_lights(set, 64, 11, false);
    set.finalize(10.0f);
    const LightTree& tree = set.tree();
    Random rng(12);
    constexpr int kTrials = 200000;
    uint32_t split_points = 0;
    for (int k = 0; k < 4; ++k) {
        const Vec3 p = rng.point(3.0f), n = rng.direction();
        LightTree::Cut cut;
        tree.cut(p, n, kMaxCut, &cut);
        if (cut.size > 1) ++split_points;
        std::vector<int> counts(set.size(), 0);
        for (int t = 0; t < kTrials; ++t) {
            for (uint32_t c = 0; c < cut.size; ++c) {
                float pmf = 0.0f;
                const uint32_t light = tree.choose_in_cut(cut.node[c], p, n, rng.uniform(0.0f, 1.0f), &pmf);
                if (light == LightTree::kNone) continue;
                ++counts[light];
                // The probability the choice reports is the pmf bit for bit (MIS weighs by both).
                ASSERT_EQ(pmf, tree.pmf(p, n, light, kMaxCut)) << "light " << light;
                ASSERT_EQ(pmf, set.probability(light, p, n, LightSelection::Tree, kMaxCut));
            }
        }
        double pooled_expected = 0.0, pooled_variance = 0.0, pooled_observed = 0.0;
        int bins = 0;
        for (uint32_t i = 0; i < set.size(); ++i) {
            const double pmf = tree.pmf(p, n, i, kMaxCut);
            if (pmf == 0.0) {
                EXPECT_EQ(counts[i], 0) << "light " << i << " has pmf 0 but was drawn, shading point " << k;
                continue;
            }
            const double expected = kTrials * pmf, variance = kTrials * pmf * (1.0 - pmf);
            if (expected < 25.0) {
                pooled_expected += expected;
                pooled_variance += variance;
                pooled_observed += counts[i];
                continue;
            }
            ++bins;
            EXPECT_NEAR(counts[i], expected, 5.0 * std::sqrt(variance))
                << "light " << i << ", shading point " << k << ", cut of " << cut.size;
        }
        if (pooled_expected >= 25.0) {
            ++bins;
            EXPECT_NEAR(pooled_observed, pooled_expected, 5.0 * std::sqrt(pooled_variance))
                << "pooled lights, shading point " << k;
        }
        EXPECT_GE(bins, 8) << "shading point " << k;
    }
    // The test is about splitting: the shading points must have cuts of more than one node.
    EXPECT_EQ(split_points, 4u);
}

// With lights that shine every way the descent below a node never dead-ends (test_light_tree.cpp),
// so each cut node's sub-estimator is a distribution over the lights below it: Σ_i pmf(i) is the
// cut's size. Rounding: each light's pmf is a product of ≤ depth rounded branch probabilities,
// within depth·2^-22.5 of its exact sum per node (test_light_tree.cpp's sum_tolerance), so the
// sum is within size·(depth + 2)·2^-22.
TEST(LightTreeSplit, PmfSumsToTheCutSize) {
    LightSet set;
    add_lights(set, 64, 13, true);
    set.finalize(10.0f);
    const LightTree& tree = set.tree();
    Random rng(14);
    for (int k = 0; k < 100; ++k) {
        const Vec3 p = rng.point(3.0f);
        const Vec3 n = k % 4 == 0 ? Vec3(0.0f, 0.0f, 0.0f) : rng.direction();
        for (const uint32_t max_cut : {1u, 2u, kMaxCut, LightTree::kMaxCut}) {
            LightTree::Cut cut;
            tree.cut(p, n, max_cut, &cut);
            ASSERT_GE(cut.size, 1u);
            ASSERT_LE(cut.size, max_cut);
            double sum = 0.0;
            for (uint32_t i = 0; i < set.size(); ++i) sum += tree.pmf(p, n, i, max_cut);
            const double tolerance = cut.size * (tree.depth() + 2) * std::ldexp(1.0, -22);
            EXPECT_NEAR(sum, cut.size, tolerance) << "shading point " << k << ", max_cut " << max_cut;
        }
    }
}

// Without splitting the cut is the root and pmf() is the unsplit tree's, bit for bit; a node is
// split only where its bounding sphere looks wider than kSplitThreshold from p, so far from every
// light the cut stays one node.
TEST(LightTreeSplit, NoSplitFarAwayOrWithACapOfOne) {
    LightSet set;
    add_lights(set, 64, 15, false);
    set.finalize(10.0f);
    const LightTree& tree = set.tree();
    Random rng(16);
    for (int k = 0; k < 20; ++k) {
        const Vec3 p = rng.point(3.0f), n = rng.direction();
        LightTree::Cut cut;
        tree.cut(p, n, 1, &cut);
        EXPECT_EQ(cut.size, 1u);
        for (uint32_t i = 0; i < set.size(); ++i) ASSERT_EQ(tree.pmf(p, n, i, 1), tree.pmf(p, n, i));
        // The lights fill a sphere of radius ≤ 4√3 + 0.5 < 7.5 about the origin; from 1000 away
        // the root's r/d is under 0.0075.
        const Vec3 far = p + Vec3(1000.0f, 0.0f, 0.0f);
        tree.cut(far, n, kMaxCut, &cut);
        EXPECT_EQ(cut.size, 1u);
    }
}
