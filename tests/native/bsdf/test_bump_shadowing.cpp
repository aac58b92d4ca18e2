// Bump shadowing (bsdf/bump_shadowing.h): the terms against their papers' formulas written out
// here independently, their reach (which lobes, eval vs sample) in a ClosureSet, and the field
// through the C ABI. Local frame: z = the closure's (perturbed) normal N.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <cmath>
#include <string>

#include "bsdf/bump_shadowing.h"
#include "bsdf/closure_set.h"

using namespace stratum;

namespace {

// The smooth normal Ns tilted from N by `angle` about the y axis.
Vec3 tilted(float angle) { return {std::sin(angle), 0.0f, std::cos(angle)}; }

Vec3 direction(float theta, float phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// Chiang, Li, Burley 2019, eq. 4 with Ns for Ng: g = (Ns.wi) / ((N.wi)(Ns.N)).
float chiang_reference(Vec3 ns, Vec3 wi) {
    const float g = dot(ns, wi) / (wi.z * ns.z);
    if (g >= 1.0f) return 1.0f;
    if (g < 0.0f) return 0.0f;
    return -g * g * g + g * g + g;
}

// Conty Estevez et al. 2019: Smith G1 of GGX, G1 = 2 / (1 + sqrt(1 + alpha^2 tan^2 theta)), with
// alpha^2 = tan^2(angle between N and Ns) / 8, at the angle between Ns and wi.
float conty_reference(Vec3 ns, Vec3 wi) {
    const float tan2_d = 1.0f / (ns.z * ns.z) - 1.0f;
    const float alpha2 = std::min(tan2_d / 8.0f, 1.0f);
    const float c = std::abs(dot(ns, wi));
    const float tan2 = (1.0f - c * c) / (c * c);
    return 2.0f / (1.0f + std::sqrt(1.0f + alpha2 * tan2));
}

Material model_material(int32_t model, BumpShadowing bump) {
    Material m{};
    m.model = model;
    m.base_color = Rgb(0.6f, 0.5f, 0.4f);
    m.roughness = 0.5f;
    m.specular = 0.5f;
    m.ior = 1.45f;
    m.distribution = MicrofacetDistribution::Ggx;
    m.bump_shadowing = bump;
    return m;
}

ClosureSet one_closure(const Material& m) {
    SceneMaterial scene_material;
    scene_material.closures.push_back({Rgb(1.0f), m});
    return ClosureSet(scene_material);
}

}  // namespace

TEST(BumpShadowing, ChiangMatchesThePaperOnDiffuseLobesOnly) {
    const Vec3 ns = tilted(0.4f);
    int zero = 0, smoothed = 0, one = 0;
    for (float theta = 0.05f; theta < 1.55f; theta += 0.1f) {
        for (float phi = 0.0f; phi < 6.28f; phi += 0.5f) {
            const Vec3 wi = direction(theta, phi);
            const BumpShadowingFactors f = bump_shadowing(BumpShadowing::Chiang, ns, wi, false);
            const float expected = chiang_reference(ns, wi);
            EXPECT_NEAR(f.diffuse, expected, 1e-5f) << theta << " " << phi;
            EXPECT_EQ(f.all, 1.0f);
            const BumpShadowingFactors u = bump_shadowing(BumpShadowing::ChiangUnsmoothed, ns, wi, false);
            EXPECT_EQ(u.diffuse, expected == 0.0f ? 0.0f : 1.0f);
            zero += expected == 0.0f;
            one += expected == 1.0f;
            smoothed += expected > 0.0f && expected < 1.0f;
        }
    }
    // The sweep crosses all three branches (behind Ns, the terminator band, fully lit).
    EXPECT_GT(zero, 0);
    EXPECT_GT(smoothed, 0);
    EXPECT_GT(one, 0);
}

TEST(BumpShadowing, ContyRejectsLeaksForAllLobesAndSmoothsDiffuse) {
    const Vec3 ns = tilted(0.5f);
    int leaks = 0;
    for (float theta = 0.05f; theta < 1.55f; theta += 0.1f) {
        for (float phi = 0.0f; phi < 6.28f; phi += 0.5f) {
            const Vec3 wi = direction(theta, phi);
            const bool leak = dot(ns, wi) < 0.0f;  // N.wi > 0 and Ns.N > 0 here
            leaks += leak;
            const BumpShadowingFactors eval = bump_shadowing(BumpShadowing::Conty, ns, wi, false);
            const BumpShadowingFactors sampled = bump_shadowing(BumpShadowing::Conty, ns, wi, true);
            EXPECT_EQ(eval.all, leak ? 0.0f : 1.0f);
            EXPECT_EQ(sampled.all, 1.0f) << "a closure's own sample keeps its non-diffuse lobes";
            if (leak) {
                EXPECT_EQ(sampled.diffuse, 0.0f);
            } else {
                EXPECT_NEAR(eval.diffuse, conty_reference(ns, wi), 1e-5f);
                EXPECT_EQ(bump_shadowing(BumpShadowing::ContyUnsmoothed, ns, wi, false).diffuse, 1.0f);
            }
        }
    }
    EXPECT_GT(leaks, 0);
}

TEST(BumpShadowing, NoneAndUnperturbedLeaveTheBsdfAlone) {
    const Vec3 wi = direction(1.3f, 3.0f);
    const BumpShadowingFactors f = bump_shadowing(BumpShadowing::None, tilted(0.5f), wi, false);
    EXPECT_EQ(f.all, 1.0f);
    EXPECT_EQ(f.diffuse, 1.0f);
    // A closure set without set_smooth_normal (normal not perturbed) evaluates the plain BSDF.
    const Material m = model_material(STRATUM_MATERIAL_DIFFUSE, BumpShadowing::Chiang);
    const Vec3 wo = direction(0.3f, 0.0f);
    EXPECT_EQ(one_closure(m).eval(wo, wi, HemisphereDistribution::Cosine).value.r,
              bsdf_eval(m, wo, wi).value.r);
}

TEST(BumpShadowing, ClosureSetScalesTheDiffusePartAndKeepsThePdf) {
    const Vec3 ns = tilted(0.35f), wo = direction(0.4f, 0.3f);
    for (int32_t model : {STRATUM_MATERIAL_DIFFUSE, STRATUM_MATERIAL_PRINCIPLED_V1,
                          STRATUM_MATERIAL_PRINCIPLED_V2, STRATUM_MATERIAL_GLOSSY}) {
        const Material m = model_material(model, BumpShadowing::Chiang);
        ClosureSet set = one_closure(m);
        set.set_smooth_normal(ns);
        for (float theta = 0.1f; theta < 1.5f; theta += 0.2f) {
            const Vec3 wi = direction(theta, 3.1f);  // leaning away from Ns: the terminator band
            const BsdfEval plain = bsdf_eval(m, wo, wi);
            const BsdfEval shadowed = set.eval(wo, wi, HemisphereDistribution::Cosine);
            const float term = chiang_reference(ns, wi);
            const Rgb expected = plain.value - plain.diffuse + plain.diffuse * term;
            EXPECT_NEAR(shadowed.value.g, expected.g, 1e-6f) << static_cast<int>(model) << " " << theta;
            EXPECT_FLOAT_EQ(shadowed.pdf, plain.pdf);
            if (model == STRATUM_MATERIAL_GLOSSY) {
                EXPECT_EQ(plain.diffuse.g, 0.0f);
            }
            if (model == STRATUM_MATERIAL_DIFFUSE) {
                EXPECT_EQ(plain.diffuse.g, plain.value.g);
            }
        }
    }
}

TEST(BumpShadowing, ContySideTestRejectsEvaluatedLeaks) {
    const Vec3 ns = tilted(0.6f), wo = direction(0.2f, 0.0f);
    const Material m = model_material(STRATUM_MATERIAL_GLOSSY, BumpShadowing::Conty);
    ClosureSet set = one_closure(m);
    set.set_smooth_normal(ns);
    // wi above N but below the smooth surface: evaluated (NEE) it is rejected.
    const Vec3 wi = direction(1.2f, 3.14159f);
    ASSERT_LT(dot(ns, wi), 0.0f);
    ASSERT_GT(bsdf_eval(m, wo, wi).value.g, 0.0f);
    EXPECT_EQ(set.eval(wo, wi, HemisphereDistribution::Cosine).value.g, 0.0f);
}

TEST(BumpShadowing, AbiValidatesAndKeepsTheField) {
    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    StratumMaterialDesc d{STRATUM_MATERIAL_DIFFUSE, {0.5f, 0.5f, 0.5f}, 0.5f, 0, 0.5f, 1.45f, {0, 0, 0},
                          STRATUM_MICROFACET_GGX};
    uint32_t id = 0;
    for (int bad : {-1, STRATUM_BUMP_SHADOWING_CONTY_UNSMOOTHED + 1}) {
        d.bump_shadowing = bad;
        EXPECT_EQ(stratum_scene_add_material(scene, &d, &id), STRATUM_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(stratum_last_error()).find("bump_shadowing " + std::to_string(bad)),
                  std::string::npos)
            << stratum_last_error();
    }
    for (int good = STRATUM_BUMP_SHADOWING_NONE; good <= STRATUM_BUMP_SHADOWING_CONTY_UNSMOOTHED; ++good) {
        d.bump_shadowing = good;
        EXPECT_EQ(stratum_scene_add_material(scene, &d, &id), STRATUM_OK) << stratum_last_error();
    }
    stratum_scene_destroy(scene);
}
