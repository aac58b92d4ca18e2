// Glossy, Glass, Transparent and closure mixtures (bsdf/glossy.h, glass.h, closure_set.h):
// chi-square of sampling against the reported pdf, weight == value/pdf, white-furnace bounds,
// reciprocity, smooth-glass Fresnel and Snell against closed forms, and the mixture identity.
//
// Chi-square binning as in test_bsdf.cpp (12 x 20 bins over the sphere, theta edges at quantiles,
// expected counts from a fine midpoint grid). Significance alpha = 1% over the kChiSquareTests
// tests of this file, alpha / kChiSquareTests each (Bonferroni).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "bsdf/closure_set.h"
#include "bsdf/glass.h"
#include "bsdf/glossy.h"
#include "chi_square.h"
#include "stratum/stratum.h"

namespace stratum {
namespace {

constexpr int kChiSquareTests = 48;  // 16 closure sets x 3 view directions
constexpr double kSignificance = 0.01 / kChiSquareTests;
constexpr int kSampleCount = 400'000;

Material make(int32_t model, Rgb c, float roughness, float ior = 1.5f,
              MicrofacetDistribution d = MicrofacetDistribution::Ggx) {
    return {model, c, roughness, 0.0f, 0.5f, ior, Rgb(), d};
}
Material lambert(Rgb c) { return make(STRATUM_MATERIAL_DIFFUSE, c, 0.0f); }
Material glossy(Rgb c, float r, MicrofacetDistribution d = MicrofacetDistribution::Ggx) {
    return make(STRATUM_MATERIAL_GLOSSY, c, r, 1.5f, d);
}
Material glass(Rgb c, float r, float eta) { return make(STRATUM_MATERIAL_GLASS, c, r, eta); }

Material principled(int32_t model, Rgb c, float roughness, float metallic, float transmission, float coat,
                    float ior = 1.45f, MicrofacetDistribution d = MicrofacetDistribution::Ggx) {
    Material m = make(model, c, roughness, ior, d);
    m.metallic = metallic;
    m.transmission = transmission;
    m.coat = coat;
    m.coat_roughness = 0.2f;
    m.coat_ior = 1.5f;
    m.coat_tint = Rgb(0.9f, 0.7f, 0.5f);
    return m;
}

SceneMaterial mix(std::initializer_list<WeightedClosure> closures) { return SceneMaterial{closures}; }
SceneMaterial single(const Material& m) { return mix({{Rgb(1.0f), m}}); }

float ch(Rgb c, int i) { return i == 0 ? c.r : (i == 1 ? c.g : c.b); }

Vec3 direction(float theta, float phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}
const float kViewThetas[] = {0.17f, 0.87f, 1.22f};

// Closure sets whose sampling is tested: every new lobe, entering and leaving glass, mixtures
// with a delta closure (whose mass the continuous density does not include).
std::vector<SceneMaterial> chi_square_materials() {
    return {
        single(glossy(Rgb(0.9f, 0.6f, 0.3f), 0.3f)),
        single(glossy(Rgb(0.8f), 0.6f, MicrofacetDistribution::MultiscatterGgx)),
        single(glass(Rgb(1.0f), 0.3f, 1.5f)), single(glass(Rgb(1.0f), 0.6f, 1.5f)),
        single(glass(Rgb(1.0f), 0.3f, 1.0f / 1.5f)),  // leaving the glass
        single(make(STRATUM_MATERIAL_GLASS, Rgb(1.0f), 0.5f, 1.45f, MicrofacetDistribution::MultiscatterGgx)),
        single(glass(Rgb(0.9f, 0.8f, 0.7f), 0.7f, 1.0f / 1.33f)),
        mix({{Rgb(0.5f), lambert(Rgb(0.8f))}, {Rgb(0.5f), glossy(Rgb(1.0f), 0.4f)}}),
        mix({{Rgb(0.3f, 0.5f, 0.7f), lambert(Rgb(0.8f))}, {Rgb(0.7f), glass(Rgb(1.0f), 0.5f, 1.45f)}}),
        mix({{Rgb(0.6f), glossy(Rgb(0.8f), 0.35f)},
             {Rgb(0.4f), make(STRATUM_MATERIAL_TRANSPARENT, Rgb(1), 0)}}),
        // Principled with transmission and coat, both generations, entering and leaving.
        single(principled(STRATUM_MATERIAL_PRINCIPLED_V1, Rgb(0.8f, 0.6f, 0.4f), 0.4f, 0.0f, 0.7f, 0.0f)),
        single(principled(STRATUM_MATERIAL_PRINCIPLED_V1, Rgb(0.8f), 0.5f, 0.2f, 0.0f, 1.0f)),
        single(principled(STRATUM_MATERIAL_PRINCIPLED_V1, Rgb(0.9f), 0.3f, 0.0f, 1.0f, 0.5f, 1.0f / 1.45f)),
        single(principled(STRATUM_MATERIAL_PRINCIPLED_V2, Rgb(0.8f, 0.6f, 0.4f), 0.4f, 0.0f, 0.7f, 0.0f)),
        single(principled(STRATUM_MATERIAL_PRINCIPLED_V2, Rgb(0.8f), 0.5f, 0.3f, 0.0f, 1.0f, 1.45f,
                          MicrofacetDistribution::MultiscatterGgx)),
        single(principled(STRATUM_MATERIAL_PRINCIPLED_V2, Rgb(0.9f), 0.3f, 0.0f, 1.0f, 0.5f, 1.0f / 1.45f))};
}

TEST(Closures, SamplingMatchesPdfChiSquare) {
    uint64_t seed = 300;
    int index = 0;
    for (const SceneMaterial& sm : chi_square_materials()) {
        const ClosureSet set(sm);
        for (const float theta : kViewThetas) {
            const Vec3 wo = direction(theta, 0.3f);
            // Delta picks are "failed" draws for the continuous density: its mass excludes them.
            const chi_square::ChiSquare r = chi_square::chi_square_directions(
                [&](Vec2 u, float u_lobe, Vec3* wi) {
                    BsdfSample s;
                    if (!set.sample(wo, u_lobe, u, &s, HemisphereDistribution::Cosine) || s.delta)
                        return false;
                    *wi = s.wi;
                    return true;
                },
                [&](Vec3 wi) { return set.eval(wo, wi, HemisphereDistribution::Cosine).pdf; }, seed++,
                kSampleCount, 1024, 800);
            EXPECT_GT(r.p_value, kSignificance)
                << "set " << index << " theta_o " << theta << ": chi2 " << r.statistic << ", dof " << r.dof;
            EXPECT_LE(r.density_mass, 1.0 + 2e-3) << "set " << index;
        }
        ++index;
    }
}

TEST(Closures, WeightIsValueOverPdf) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<float> uniform(0.0f, kOneMinusEpsilon);
    for (const SceneMaterial& sm : chi_square_materials()) {
        const ClosureSet set(sm);
        for (const float theta : kViewThetas) {
            const Vec3 wo = direction(theta, 1.1f);
            for (int i = 0; i < 2000; ++i) {
                BsdfSample s;
                // Drawn in sequence: the order of evaluation of function arguments is unspecified
                // (GCC and clang differ), and the test must see the same numbers with either.
                const Vec2 u{uniform(rng), uniform(rng)};
                const float lobe = uniform(rng);
                if (!set.sample(wo, lobe, u, &s, HemisphereDistribution::Cosine) || s.delta) continue;
                const BsdfEval e = set.eval(wo, s.wi, HemisphereDistribution::Cosine);
                ASSERT_NEAR(s.pdf, e.pdf, 1e-3f * e.pdf);
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(ch(s.weight, c), ch(e.value, c) / e.pdf, 1e-3f * (1 + ch(s.weight, c)));
            }
        }
    }
}

// Directional albedo by sampling: mean weight and its standard error (delta picks included).
struct Albedo {
    double mean, std_error;
};
Albedo sampled_albedo(const ClosureSet& set, Vec3 wo, int channel, int n, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> uniform(0.0f, kOneMinusEpsilon);
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
        BsdfSample s;
        double w = 0;
        // Drawn in sequence: the order of evaluation of function arguments is unspecified
        // (GCC and clang differ), and the test must see the same numbers with either.
        const Vec2 u{uniform(rng), uniform(rng)};
        const float lobe = uniform(rng);
        if (set.sample(wo, lobe, u, &s, HemisphereDistribution::Cosine)) w = ch(s.weight, channel);
        sum += w;
        sum2 += w * w;
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(sum2 / n - mean * mean, 0.0) / n)};
}

// White furnace: rough glass reflects + transmits at most everything (each sampled weight is
// G2/G1 <= 1); multiscatter Glossy at most 1. Bound: mean <= 1 + 4 standard errors.
TEST(Closures, WhiteFurnaceBounds) {
    for (const float roughness : {0.05f, 0.3f, 0.6f, 1.0f}) {
        for (const float eta : {1.5f, 1.0f / 1.5f, 1.33f}) {
            const ClosureSet set(single(glass(Rgb(1.0f), roughness, eta)));
            for (const float theta : {0.2f, 0.8f, 1.3f}) {
                const Albedo a = sampled_albedo(set, direction(theta, 0.4f), 0, 200'000, 11);
                EXPECT_LE(a.mean, 1.0 + 4.0 * a.std_error + 1e-6) << "r " << roughness << " eta " << eta;
                // Nearly smooth glass (alpha = 0.0025) loses almost nothing to shadowing-masking:
                // G2/G1 >= 0.99 for views up to 75 degrees (Lambda ~ alpha tan / 2 < 0.005).
                if (roughness == 0.05f) {
                    EXPECT_GT(a.mean, 0.99 - 4.0 * a.std_error) << "eta " << eta << " theta " << theta;
                }
            }
        }
        for (const float eta : {1.45f, 1.0f / 1.45f}) {
            // Multiscatter glass: 1/E_glass from a table of 256 stratified samples per entry,
            // trilinearly interpolated; accepted within 4 standard errors + 0.01 of 1.
            const ClosureSet ms_glass(single(make(STRATUM_MATERIAL_GLASS, Rgb(1.0f), roughness, eta,
                                                  MicrofacetDistribution::MultiscatterGgx)));
            const Albedo a = sampled_albedo(ms_glass, direction(0.7f, 0.0f), 0, 200'000, 14);
            EXPECT_NEAR(a.mean, 1.0, 4.0 * a.std_error + 0.01)
                << "glass roughness " << roughness << " eta " << eta;
        }
        const ClosureSet ms(single(glossy(Rgb(1.0f), roughness, MicrofacetDistribution::MultiscatterGgx)));
        const Albedo a = sampled_albedo(ms, direction(0.7f, 0.0f), 0, 200'000, 12);
        // Multiscatter compensation restores the full albedo: 1 within the table's accuracy
        // (1024 stratified samples per entry, interpolated) and 4 standard errors.
        EXPECT_NEAR(a.mean, 1.0, 4.0 * a.std_error + 0.01) << "roughness " << roughness;
    }
}

// White furnace for the Principled transmission and coat lobes: a white V2 glass (transmission 1)
// with or without a coat, and Cycles 3.4's V1 glass pair (specular 0: no other lobe), reflect and
// transmit at most everything: mean weight <= 1 + 4 standard errors.
TEST(Closures, PrincipledTransmissionAndCoatWhiteFurnace) {
    for (const float roughness : {0.1f, 0.4f, 0.8f}) {
        for (const float eta : {1.45f, 1.0f / 1.45f}) {
            Material v1 =
                principled(STRATUM_MATERIAL_PRINCIPLED_V1, Rgb(1.0f), roughness, 0.0f, 1.0f, 0.0f, eta);
            v1.specular = 0.0f;
            Material v2_coated =
                principled(STRATUM_MATERIAL_PRINCIPLED_V2, Rgb(1.0f), roughness, 0.0f, 1.0f, 1.0f, eta);
            v2_coated.coat_tint = Rgb(1.0f);
            for (const Material& m :
                 {v1, principled(STRATUM_MATERIAL_PRINCIPLED_V2, Rgb(1.0f), roughness, 0.0f, 1.0f, 0.0f, eta),
                  v2_coated}) {
                const ClosureSet set(single(m));
                for (const float theta : {0.2f, 0.8f, 1.3f}) {
                    const Albedo a = sampled_albedo(set, direction(theta, 0.4f), 0, 100'000, 13);
                    EXPECT_LE(a.mean, 1.0 + 4.0 * a.std_error + 1e-6)
                        << "model " << int(m.model) << " coat " << m.coat << " r " << roughness << " eta "
                        << eta << " theta " << theta;
                }
            }
        }
    }
}

// Exact unpolarised Fresnel from Snell's law (Born & Wolf): the mean of the s and p reflectances.
double fresnel_closed_form(double cos_i, double eta) {
    const double sin_t = std::sqrt(1.0 - cos_i * cos_i) / eta;
    if (sin_t >= 1.0) return 1.0;
    const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
    const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5 * (rs * rs + rp * rp);
}

// Smooth glass: a Dirac pair. The reflected fraction of a uniform grid of N lobe choices is F to
// within 1/N; refraction obeys Snell's law; every weight is the tint exactly (energy conserved).
TEST(Closures, SmoothGlassFresnelSnellAndExactEnergy) {
    constexpr int kN = 100'000;
    const Rgb tint(0.9f, 0.7f, 0.5f);
    for (const float eta : {1.5f, 1.0f / 1.5f, 1.33f}) {
        const Material m = glass(tint, 0.0f, eta);
        for (const float theta : {0.0f, 0.3f, 0.7f, 0.9f, 1.2f, 1.5f}) {
            const Vec3 wo = direction(theta, 0.6f);
            int reflected = 0;
            for (int i = 0; i < kN; ++i) {
                BsdfSample s;
                ASSERT_TRUE(bsdf_sample(m, wo, (static_cast<float>(i) + 0.5f) / static_cast<float>(kN),
                                        {0.5f, 0.5f}, &s));
                ASSERT_TRUE(s.delta);
                for (int c = 0; c < 3; ++c) ASSERT_EQ(ch(s.weight, c), ch(tint, c));
                if (s.wi.z > 0.0f) {
                    ++reflected;
                    EXPECT_NEAR(s.wi.z, wo.z, 1e-6f);
                } else {
                    const float sin_i = std::sqrt(1.0f - wo.z * wo.z),
                                sin_t = std::sqrt(1.0f - s.wi.z * s.wi.z);
                    EXPECT_NEAR(sin_t * eta, sin_i, 2e-5f) << "Snell, eta " << eta << " theta " << theta;
                }
            }
            EXPECT_NEAR(double(reflected) / kN, fresnel_closed_form(wo.z, eta), 2.0 / kN)
                << "eta " << eta << " theta " << theta;
        }
    }
}

// Reciprocity: Glossy (single scattering) f(wo, wi) = f(wi, wo); rough glass reflection the
// same; rough glass transmission the generalised form f(wo, wi; eta) / eta^2 = f(wi', wo'; 1/eta)
// with the directions reversed (wi' = -wi, wo' = -wo, seen from the other side).
TEST(Closures, Reciprocity) {
    std::mt19937_64 rng(21);
    std::uniform_real_distribution<float> uniform(0.02f, 1.5f), phi(0.0f, 6.28f);
    for (int i = 0; i < 2000; ++i) {
        const Vec3 a = direction(uniform(rng), phi(rng)), b = direction(uniform(rng), phi(rng));
        const Material g = glossy(Rgb(1.0f), 0.4f);
        const float fab = glossy_eval(g, a, b).value.r / b.z, fba = glossy_eval(g, b, a).value.r / a.z;
        ASSERT_NEAR(fab, fba, 1e-4f * (1 + fab));
        const Material gl = glass(Rgb(1.0f), 0.5f, 1.5f);
        const float rab = glass_eval(gl, a, b).value.r / b.z, rba = glass_eval(gl, b, a).value.r / a.z;
        ASSERT_NEAR(rab, rba, 1e-4f * (1 + rab));
        const Vec3 below(b.x, b.y, -b.z);
        const float t_forward = glass_eval(gl, a, below).value.r / b.z / (1.5f * 1.5f);
        const float t_back = glass_eval(glass(Rgb(1.0f), 0.5f, 1.0f / 1.5f), -below, -a).value.r / a.z;
        ASSERT_NEAR(t_forward, t_back, 1e-3f * (1 + t_forward)) << i;
    }
}

// Mix of two diffuse closures (weights a, b; colours c1, c2) equals one diffuse closure of albedo
// a c1 + b c2: identical value, and both sample to the same albedo within 4 standard errors
// (the mixture's sampled weight is one-sample MIS over the closures, exact for equal lobes).
TEST(Closures, MixtureOfDiffuseIsDiffuseOfMixedAlbedo) {
    const Rgb a(0.3f, 0.5f, 0.2f), b(0.6f, 0.1f, 0.7f), c1(0.8f, 0.4f, 0.9f), c2(0.5f, 0.9f, 0.3f);
    const ClosureSet mixed(mix({{a, lambert(c1)}, {b, lambert(c2)}}));
    const ClosureSet one(single(lambert(a * c1 + b * c2)));
    const Vec3 wo = direction(0.5f, 0.2f);
    for (const float theta : {0.1f, 0.6f, 1.2f}) {
        const Vec3 wi = direction(theta, 2.0f);
        const BsdfEval em = mixed.eval(wo, wi, HemisphereDistribution::Cosine),
                       eo = one.eval(wo, wi, HemisphereDistribution::Cosine);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(ch(em.value, c), ch(eo.value, c), 1e-6f);
        EXPECT_NEAR(em.pdf, eo.pdf, 1e-6f);
    }
    for (int c = 0; c < 3; ++c) {
        const Albedo am = sampled_albedo(mixed, wo, c, 100'000, 5);
        const float expected = ch(a * c1 + b * c2, c);
        // Cosine sampling of a Lambert mixture: every weight is exactly the mixed albedo.
        EXPECT_NEAR(am.mean, expected, 4.0 * am.std_error + 1e-6) << "channel " << c;
    }
}

// The kinds mask NEE uses for light visibility: a light that lights only glossy closures sees a
// glass closure's reflection and not its refraction; one that lights only diffuse closures sees
// neither; the pdf (the BSDF sampling density, for MIS) is the same whatever the mask.
TEST(Closures, EvalKindsMaskSelectsClosuresByScatterKind) {
    const ClosureSet set(mix({{Rgb(0.5f), lambert(Rgb(0.8f))}, {Rgb(0.5f), glass(Rgb(1.0f), 0.4f, 1.5f)}}));
    const Vec3 wo = direction(0.5f, 0.0f), above = direction(0.7f, 2.5f), below = direction(2.6f, 3.0f);
    const auto value = [&](Vec3 wi, uint32_t kinds) {
        return set.eval(wo, wi, HemisphereDistribution::Cosine, kinds).value.r;
    };
    const uint32_t diffuse = scatter_kind_bit(ScatterKind::Diffuse),
                   glossy = scatter_kind_bit(ScatterKind::Glossy),
                   transmission = scatter_kind_bit(ScatterKind::Transmission);
    const float lambert_part = 0.5f * 0.8f * kInvPi * above.z;
    const float glass_reflection = 0.5f * glass_eval(glass(Rgb(1.0f), 0.4f, 1.5f), wo, above).value.r;
    const float glass_refraction = 0.5f * glass_eval(glass(Rgb(1.0f), 0.4f, 1.5f), wo, below).value.r;
    ASSERT_GT(glass_reflection, 0.0f);
    ASSERT_GT(glass_refraction, 0.0f);
    EXPECT_FLOAT_EQ(value(above, diffuse), lambert_part);
    EXPECT_FLOAT_EQ(value(above, glossy), glass_reflection);
    EXPECT_FLOAT_EQ(value(above, diffuse | glossy), lambert_part + glass_reflection);
    EXPECT_EQ(value(below, diffuse | glossy), 0.0f);
    EXPECT_FLOAT_EQ(value(below, transmission), glass_refraction);
    EXPECT_EQ(set.eval(wo, below, HemisphereDistribution::Cosine, diffuse).pdf,
              set.eval(wo, below, HemisphereDistribution::Cosine).pdf);
}

TEST(Closures, SumsEmissionHoldoutAndTransparency) {
    Material e = make(STRATUM_MATERIAL_EMISSION, Rgb(0.0f), 0.0f);
    e.emission = Rgb(2.0f, 4.0f, 6.0f);
    const ClosureSet set(mix({{Rgb(0.5f), e},
                              {Rgb(0.25f), make(STRATUM_MATERIAL_HOLDOUT, Rgb(1.0f), 0.0f)},
                              {Rgb(0.2f), make(STRATUM_MATERIAL_TRANSPARENT, Rgb(0.5f, 1.0f, 0.0f), 0.0f)}}));
    EXPECT_EQ(set.emission().g, 2.0f);
    EXPECT_EQ(set.holdout().r, 0.25f);
    EXPECT_FLOAT_EQ(set.transparency().r, 0.1f);
    EXPECT_FLOAT_EQ(set.transparency().g, 0.2f);
    EXPECT_EQ(set.transparency().b, 0.0f);
    EXPECT_TRUE(set.has_transmission());
    EXPECT_FALSE(set.has_non_delta());
    // Only the transparent closure scatters: every draw passes straight through with weight
    // w c / p, p = 1 (the only closure with a sample weight).
    BsdfSample s;
    ASSERT_TRUE(set.sample(direction(0.4f, 0.0f), 0.7f, {0.1f, 0.9f}, &s, HemisphereDistribution::Cosine));
    EXPECT_TRUE(s.delta);
    EXPECT_EQ(s.kind, ScatterKind::Transparent);
    EXPECT_FLOAT_EQ(s.weight.g, 0.2f);
}

}  // namespace
}  // namespace stratum
