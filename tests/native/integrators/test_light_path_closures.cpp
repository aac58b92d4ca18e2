// Filter Glossy and the caustics switches (integrators/light_path_closures.h): Cycles' blur
// radius from the path's least scattering pdf, what a path carries to its next hit, and the
// lobes each closure model keeps under a ClosureFilter. Exact: no sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "bsdf/closure_set.h"
#include "integrators/light_path_closures.h"
#include "render_helpers.h"
#include "stratum/stratum.h"

using namespace stratum;
using namespace stratum_test;

namespace {

Material model(int32_t m, Rgb color, float roughness, float metallic = 0.0f, float ior = 1.5f) {
    return {m, color, roughness, metallic, 0.5f, ior, Rgb(), MicrofacetDistribution::Ggx};
}

ClosureSet filtered(const Material& m, const ClosureFilter& filter) {
    ClosureSet set(SceneMaterial{{WeightedClosure{Rgb(1.0f), m}}});
    set.apply(filter);
    set.finalize();
    return set;
}

const Vec3 kWo = normalize(Vec3(0.3f, 0.1f, 0.9f));
const Vec3 kMirror = Vec3(-kWo.x, -kWo.y, kWo.z);
const Vec3 kBelow = normalize(Vec3(-0.2f, 0.0f, -0.95f));

}  // namespace

TEST(FilterGlossy, BlurRadiusIsCyclesSurfaceShaderPrepareClosures) {
    const float inf = std::numeric_limits<float>::infinity();
    // r = 0.5 sqrt(1 - min_ray_pdf / blur_glossy) below blur_glossy, else no blur.
    EXPECT_FLOAT_EQ(filter_glossy_alpha(1.0f, 1.0f / kPi), 0.5f * std::sqrt(1.0f - 1.0f / kPi));
    EXPECT_FLOAT_EQ(filter_glossy_alpha(2.0f, 0.5f), 0.5f * std::sqrt(0.75f));
    EXPECT_FLOAT_EQ(filter_glossy_alpha(1.0f, 0.0f), 0.5f);
    EXPECT_EQ(filter_glossy_alpha(1.0f, 1.0f), 0.0f);
    EXPECT_EQ(filter_glossy_alpha(1.0f, 3.0f), 0.0f);
    EXPECT_EQ(filter_glossy_alpha(1.0f, inf), 0.0f);    // the camera hit
    EXPECT_EQ(filter_glossy_alpha(0.0f, 0.01f), 0.0f);  // off
}

TEST(PathClosureState, TracksTheLeastNonDeltaPdfAndTheLastRealScattering) {
    LightPathLimits limits;
    limits.filter_glossy = 1.0f;
    limits.caustics_refractive = false;
    PathClosureState state;
    EXPECT_FALSE(state.filter(limits).active());  // camera hit: no blur, not after diffuse
    state.scatter(ScatterKind::Diffuse, 0.25f, false);
    ClosureFilter f = state.filter(limits);
    EXPECT_FLOAT_EQ(f.min_alpha, 0.5f * std::sqrt(0.75f));
    EXPECT_FALSE(f.drop_reflection);
    EXPECT_TRUE(f.drop_refraction);
    // A transparent pass-through keeps both; a delta sample's pdf lowers nothing.
    state.scatter(ScatterKind::Transparent, 0.01f, true);
    EXPECT_TRUE(state.after_diffuse());
    state.scatter(ScatterKind::Glossy, 1e-3f, true);
    EXPECT_FLOAT_EQ(state.min_ray_pdf(), 0.25f);
    EXPECT_FALSE(state.filter(limits).drop_refraction);
    state.scatter(ScatterKind::Transmission, 0.05f, false);
    EXPECT_FLOAT_EQ(state.min_ray_pdf(), 0.05f);
}

TEST(ClosureFilter, BlurRaisesEveryMicrofacetAlphaAndMakesMirrorsRough) {
    const float min_alpha = 0.25f;  // roughness 0.5
    // A mirror becomes the GGX lobe of roughness sqrt(min_alpha), exactly.
    const ClosureSet mirror = filtered(model(STRATUM_MATERIAL_GLOSSY, Rgb(0.8f), 0.0f), {min_alpha});
    const ClosureSet rough = filtered(model(STRATUM_MATERIAL_GLOSSY, Rgb(0.8f), 0.5f), {});
    EXPECT_TRUE(mirror.has_non_delta());
    const Vec3 wi = normalize(Vec3(-0.2f, 0.1f, 0.8f));
    EXPECT_EQ(mirror.eval(kWo, wi, HemisphereDistribution::Cosine).value.r,
              rough.eval(kWo, wi, HemisphereDistribution::Cosine).value.r);
    // A lobe rougher than the blur keeps its own alpha.
    const ClosureSet rougher = filtered(model(STRATUM_MATERIAL_GLOSSY, Rgb(0.8f), 0.9f), {min_alpha});
    const ClosureSet unfiltered = filtered(model(STRATUM_MATERIAL_GLOSSY, Rgb(0.8f), 0.9f), {});
    EXPECT_EQ(rougher.eval(kWo, wi, HemisphereDistribution::Cosine).value.r,
              unfiltered.eval(kWo, wi, HemisphereDistribution::Cosine).value.r);
    // Glass and the Principled models blur too; a sharp glass stops being a Dirac.
    EXPECT_TRUE(filtered(model(STRATUM_MATERIAL_GLASS, Rgb(1.0f), 0.0f), {min_alpha}).has_non_delta());
    const ClosureSet v2 = filtered(model(STRATUM_MATERIAL_PRINCIPLED_V2, Rgb(0.5f), 0.0f, 1.0f), {min_alpha});
    const ClosureSet v2_rough = filtered(model(STRATUM_MATERIAL_PRINCIPLED_V2, Rgb(0.5f), 0.5f, 1.0f), {});
    EXPECT_EQ(v2.eval(kWo, wi, HemisphereDistribution::Cosine).value.g,
              v2_rough.eval(kWo, wi, HemisphereDistribution::Cosine).value.g);
}

TEST(ClosureFilter, CausticsSwitchesDropGlossyReflectionAndRefractionLobes) {
    const auto value = [](const ClosureSet& set, Vec3 wi) {
        return set.eval(kWo, wi, HemisphereDistribution::Cosine).value;
    };
    const Vec3 near_mirror = normalize(kMirror + Vec3(0.02f, 0.0f, 0.0f));
    // Glossy: the closure goes.
    EXPECT_FALSE(filtered(model(STRATUM_MATERIAL_GLOSSY, Rgb(1.0f), 0.3f), {0.0f, true, false}).scatters());
    EXPECT_TRUE(filtered(model(STRATUM_MATERIAL_GLOSSY, Rgb(1.0f), 0.3f), {0.0f, false, true}).scatters());
    // Glass: each side alone; both dropped, the closure goes.
    const Material glass = model(STRATUM_MATERIAL_GLASS, Rgb(1.0f), 0.3f);
    const ClosureSet no_refraction = filtered(glass, {0.0f, false, true});
    EXPECT_TRUE(value(no_refraction, kBelow).is_black());
    EXPECT_FALSE(value(no_refraction, near_mirror).is_black());
    const ClosureSet no_reflection = filtered(glass, {0.0f, true, false});
    EXPECT_TRUE(value(no_reflection, near_mirror).is_black());
    EXPECT_FALSE(value(no_reflection, kBelow).is_black());
    EXPECT_FALSE(filtered(glass, {0.0f, true, true}).scatters());
    // Smooth glass: a sampled dropped side ends the path (nothing to carry).
    const ClosureSet sharp = filtered(model(STRATUM_MATERIAL_GLASS, Rgb(1.0f), 0.0f), {0.0f, false, true});
    BsdfSample s;
    EXPECT_FALSE(sharp.sample(kWo, 0.99f, Vec2{0.5f, 0.5f}, &s, HemisphereDistribution::Cosine));
    ASSERT_TRUE(sharp.sample(kWo, 0.0f, Vec2{0.5f, 0.5f}, &s, HemisphereDistribution::Cosine));
    EXPECT_GT(s.wi.z, 0.0f);
    // Principled 4.x: a metal reflects nothing; a dielectric is its diffuse base alone, no longer
    // darkened by the specular layer it lost (Cycles 5.0 skips the layer and its attenuation).
    const ClosureSet metal =
        filtered(model(STRATUM_MATERIAL_PRINCIPLED_V2, Rgb(0.9f), 0.3f, 1.0f), {0.0f, true, false});
    EXPECT_TRUE(value(metal, near_mirror).is_black());
    const Rgb base(0.2f, 0.4f, 0.6f);
    const ClosureSet dielectric =
        filtered(model(STRATUM_MATERIAL_PRINCIPLED_V2, base, 0.3f), {0.0f, true, false});
    const Vec3 up(0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(value(dielectric, up).b, base.b / kPi, 1e-6f);
    // Principled 3.x: the specular lobe goes, the Burley diffuse stays.
    const ClosureSet v1_metal =
        filtered(model(STRATUM_MATERIAL_PRINCIPLED_V1, Rgb(0.9f), 0.3f, 1.0f), {0.0f, true, false});
    EXPECT_TRUE(value(v1_metal, near_mirror).is_black());
    const ClosureSet v1 = filtered(model(STRATUM_MATERIAL_PRINCIPLED_V1, base, 0.3f), {0.0f, true, true});
    EXPECT_FALSE(value(v1, up).is_black());
}

// A particle cannot know what the camera path before its vertex did: the light tracer says once
// that it applies neither, and only when one of them is set.
TEST(PathClosureState, TheLightTracerSaysItAppliesNeither) {
    IntegratingSphere s = make_closed_sphere(0.5f, 1.0f);
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    const Setting light("integrator", "light");
    const RenderOutput plain = render(s.scene, {{"width", 4}, {"height", 4}, {"samples", 1}, light});
    ASSERT_TRUE(plain.error.empty()) << plain.error;
    EXPECT_EQ(plain.notices.find("filter_glossy"), std::string::npos) << plain.notices;
    for (const Setting& set : {Setting("filter_glossy", 1.0), Setting("caustics_reflective", 0),
                               Setting("caustics_refractive", 0)}) {
        const RenderOutput out = render(s.scene, {{"width", 4}, {"height", 4}, {"samples", 1}, light, set});
        ASSERT_TRUE(out.error.empty()) << out.error;
        EXPECT_NE(out.notices.find("does not apply filter_glossy or the caustics switches"),
                  std::string::npos)
            << set.name << ": " << out.notices;
    }
    stratum_scene_destroy(s.scene);
}
