// The Diffuse, Glossy and Transmission Color passes (DiffCol, GlossCol, TransCol) against closed
// forms: each model's colours (ClosureModel::colors) against Cycles' rules computed here
// independently, and rendered passes of quads seen by an orthographic camera along −Z, so that
// every camera ray meets a quad at the same, known angle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bsdf/bsdf.h"
#include "render_helpers.h"

using namespace stratum;
using namespace stratum_test;

namespace {

constexpr int kSize = 8;
const Rgb kColor(0.2f, 0.5f, 0.8f);
const Rgb kTint(0.9f, 0.6f, 0.3f);

// The dielectric Fresnel reflectance of unpolarised light at cos_i, relative IOR eta (1 on total
// internal reflection): Cycles' fresnel_dielectric_cos, from the Fresnel equations (Walter 2007
// eq. 22), written out here rather than taken from bsdf/microfacet_ggx.h.
double fresnel(double cos_i, double eta) {
    const double c = std::abs(cos_i);
    const double g2 = eta * eta - 1.0 + c * c;
    if (g2 <= 0.0) return 1.0;
    const double g = std::sqrt(g2);
    const double a = (g - c) / (g + c);
    const double b = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    return 0.5 * a * a * (1.0 + b * b);
}

Material material(int32_t model, Rgb color) {
    return Material{model, color, 0.0f, 0.0f, 0.5f, 1.5f, Rgb(0.0f), MicrofacetDistribution::Ggx};
}

Vec3 view_at(double cos_o) {
    return Vec3(static_cast<float>(std::sqrt(1.0 - cos_o * cos_o)), 0.0f, static_cast<float>(cos_o));
}

void expect_rgb_near(Rgb actual, Rgb expected, float tolerance, const std::string& what) {
    EXPECT_NEAR(actual.r, expected.r, tolerance) << what;
    EXPECT_NEAR(actual.g, expected.g, tolerance) << what;
    EXPECT_NEAR(actual.b, expected.b, tolerance) << what;
}

// Cycles 3.4's closure weights of its Principled BSDF (svm/closure.h, svm_node_closure_principled,
// distribution GGX, no subsurface or sheen), summed by closure type as surface_shader_diffuse/
// glossy/transmission do: the Principled diffuse closure base (1 − m)(1 − t); the specular
// closure 1 − t(1 − m) when specular or metallic exceeds the cutoff; the glass pair's
// reflection t(1 − m) F and refraction base t(1 − m) max(1 − F, 1e-4); the clearcoat closure 1.
struct Colors3 {
    double diffuse[3], glossy, transmission[3];
};
Colors3 cycles34_principled(const Material& m, double cos_o) {
    constexpr double cutoff = 1e-5;
    const double metallic = m.metallic, transmission = m.transmission;
    const double glass = transmission * (1.0 - metallic);
    const double f = fresnel(cos_o, m.ior);
    Colors3 c{};
    c.glossy = (m.specular > cutoff || metallic > cutoff) && 1.0 - glass > cutoff ? 1.0 - glass : 0.0;
    if (glass > cutoff) c.glossy += glass * f;
    if (m.coat > cutoff) c.glossy += 1.0;
    const float base[3] = {m.base_color.r, m.base_color.g, m.base_color.b};
    for (int i = 0; i < 3; ++i) {
        c.diffuse[i] = base[i] * (1.0 - metallic) * (1.0 - transmission);
        c.transmission[i] = glass > cutoff ? base[i] * glass * std::max(1.0 - f, 1e-4) : 0.0;
    }
    return c;
}

// Quads of half-size 4 centred on the view axis: depth z, turned by `tilt` about +y (the normal
// (sin tilt, 0, cos tilt) faces the camera).
struct Quad {
    float z, tilt;
    StratumMaterialDesc material;
};

StratumScene* make_scene(const std::vector<Quad>& quads) {
    StratumScene* scene = nullptr;
    if (stratum_scene_create(&scene) != STRATUM_OK) return nullptr;
    StratumCameraDesc camera = camera_at(0, 0, 0);
    camera.type = STRATUM_CAMERA_ORTHOGRAPHIC;
    camera.ortho_scale = 1.0f;
    const float background[3] = {0.3f, 0.6f, 0.9f};
    bool ok = stratum_scene_set_camera(scene, &camera) == STRATUM_OK &&
              stratum_scene_set_background(scene, background) == STRATUM_OK;
    for (const Quad& q : quads) {
        const float c = std::cos(q.tilt), s = std::sin(q.tilt), h = 4.0f;
        // Corners (±h, ±h) along t1 = (cos, 0, −sin) and +y, counter-clockwise from the camera.
        const float positions[] = {-h * c, -h, q.z + h * s, h * c,  -h, q.z - h * s,
                                   h * c,  h,  q.z - h * s, -h * c, h,  q.z + h * s};
        const uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
        uint32_t mat = 0, mesh_id = 0;
        ok = ok && stratum_scene_add_material(scene, &q.material, &mat) == STRATUM_OK;
        const uint32_t mats[] = {mat, mat};
        const StratumMeshDesc mesh{positions, 4, triangles, 2, nullptr, nullptr, mats};
        ok = ok && stratum_scene_add_mesh(scene, &mesh, &mesh_id) == STRATUM_OK &&
             stratum_scene_add_instance(scene, mesh_id, kIdentity) == STRATUM_OK;
    }
    if (!ok) {
        stratum_scene_destroy(scene);
        return nullptr;
    }
    return scene;
}

StratumMaterialDesc desc(int32_t model, Rgb color, float roughness = 0.0f) {
    return StratumMaterialDesc{model,     {color.r, color.g, color.b}, roughness, 0, 0.5f, 1.5f,
                               {0, 0, 0}, STRATUM_MICROFACET_GGX};
}

struct ColorPasses {
    std::vector<float> rgba, diffuse, glossy, transmission, albedo;  // albedo: Denoising Albedo
};

ColorPasses render(StratumScene* scene, const char* passes, const char* integrator = "path") {
    ColorPasses out;
    StratumRenderer* r = nullptr;
    EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    for (const char* name : {"width", "height"})
        EXPECT_EQ(stratum_renderer_set_int(r, name, kSize), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_int(r, "samples", 4), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_string(r, "integrator", integrator), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_string(r, "passes", passes), STRATUM_OK) << stratum_last_error();
    const StratumStatus started = stratum_renderer_start(r);
    EXPECT_EQ(started, STRATUM_OK) << stratum_last_error();
    int32_t done = started != STRATUM_OK;
    while (!done) EXPECT_EQ(stratum_renderer_wait(r, 1000, &done), STRATUM_OK);
    out.rgba.resize(kSize * kSize * 4);
    EXPECT_EQ(stratum_renderer_read_pixels(r, out.rgba.data(), out.rgba.size()), STRATUM_OK);
    if (std::string(passes).find("DiffCol") != std::string::npos) {
        for (auto [name, v] : {std::pair{"DiffCol", &out.diffuse}, std::pair{"GlossCol", &out.glossy},
                               std::pair{"TransCol", &out.transmission}}) {
            v->resize(kSize * kSize * 3);
            EXPECT_EQ(stratum_renderer_read_pass(r, name, v->data(), v->size()), STRATUM_OK)
                << stratum_last_error();
        }
    }
    if (std::string(passes).find("Denoising Albedo") != std::string::npos) {
        out.albedo.resize(kSize * kSize * 3);
        EXPECT_EQ(stratum_renderer_read_pass(r, "Denoising Albedo", out.albedo.data(), out.albedo.size()),
                  STRATUM_OK)
            << stratum_last_error();
    }
    stratum_renderer_destroy(r);
    return out;
}

// Every pixel of `pass` equals `expected` within `tolerance`.
void expect_everywhere(const std::vector<float>& pass, Rgb expected, float tolerance, const char* what) {
    ASSERT_EQ(pass.size(), static_cast<size_t>(kSize * kSize * 3));
    for (size_t i = 0; i < pass.size() / 3; ++i) {
        EXPECT_NEAR(pass[3 * i], expected.r, tolerance) << what << " pixel " << i;
        EXPECT_NEAR(pass[3 * i + 1], expected.g, tolerance) << what << " pixel " << i;
        EXPECT_NEAR(pass[3 * i + 2], expected.b, tolerance) << what << " pixel " << i;
    }
}

const char* const kColorPasses = "DiffCol,GlossCol,TransCol";

}  // namespace

TEST(ColorPasses, OneLobeModelsReportTheirColourByCyclesClosureType) {
    const Vec3 wo = view_at(0.6);
    const auto colors = [&](int32_t model) {
        const Material m = material(model, kColor);
        return closure_model(model).colors(m, wo);
    };
    const ClosureColors diffuse = colors(STRATUM_MATERIAL_DIFFUSE);
    expect_rgb_near(diffuse.diffuse, kColor, 0.0f, "Diffuse: diffuse");
    expect_rgb_near(diffuse.glossy + diffuse.transmission, Rgb(0.0f), 0.0f, "Diffuse: others");
    const ClosureColors glossy = colors(STRATUM_MATERIAL_GLOSSY);
    expect_rgb_near(glossy.glossy, kColor, 0.0f, "Glossy: glossy");
    expect_rgb_near(glossy.diffuse + glossy.transmission, Rgb(0.0f), 0.0f, "Glossy: others");
    // Glass: F(0.6, 1.5) = 0.0684... to glossy, the rest to transmission.
    const ClosureColors glass = colors(STRATUM_MATERIAL_GLASS);
    const float f = static_cast<float>(fresnel(0.6, 1.5));
    expect_rgb_near(glass.glossy, kColor * f, 1e-6f, "Glass: glossy");
    expect_rgb_near(glass.transmission, kColor * (1.0f - f), 1e-6f, "Glass: transmission");
    expect_rgb_near(glass.diffuse, Rgb(0.0f), 0.0f, "Glass: diffuse");
    for (const int32_t model :
         {STRATUM_MATERIAL_TRANSPARENT, STRATUM_MATERIAL_EMISSION, STRATUM_MATERIAL_HOLDOUT}) {
        const ClosureColors none = colors(model);
        expect_rgb_near(none.diffuse + none.glossy + none.transmission, Rgb(0.0f), 0.0f,
                        "model " + std::to_string(model));
    }
}

TEST(ColorPasses, PrincipledV1ReportsCycles34ClosureWeights) {
    struct Case {
        float metallic, specular, transmission, coat, ior;
        double cos_o;
    };
    const Case cases[] = {
        {0.0f, 0.5f, 0.0f, 0.0f, 1.45f, 0.8},  // plastic: diffuse base, specular 1
        {1.0f, 0.5f, 0.0f, 0.0f, 1.45f, 0.5},  // metal: no diffuse, specular 1
        {0.0f, 0.0f, 0.0f, 0.0f, 1.45f, 0.5},  // specular 0: no specular closure
        {0.3f, 0.5f, 0.6f, 0.5f, 1.45f, 0.7},  // all closures at once
        {0.0f, 0.5f, 1.0f, 0.0f, 1.5f, 0.3},   // glass: specular weight 0
        {0.0f, 0.5f, 0.8f, 0.0f, 0.6f, 0.3},   // inside, beyond the critical angle: F = 1
    };
    for (const Case& k : cases) {
        Material m = material(STRATUM_MATERIAL_PRINCIPLED_V1, kColor);
        m.roughness = 0.4f;
        m.metallic = k.metallic;
        m.specular = k.specular;
        m.transmission = k.transmission;
        m.coat = k.coat;
        m.ior = k.ior;
        const ClosureColors c = closure_model(STRATUM_MATERIAL_PRINCIPLED_V1).colors(m, view_at(k.cos_o));
        const Colors3 expected = cycles34_principled(m, k.cos_o);
        const std::string what = "metallic " + std::to_string(k.metallic) + " transmission " +
                                 std::to_string(k.transmission) + " ior " + std::to_string(k.ior);
        expect_rgb_near(c.diffuse,
                        Rgb(static_cast<float>(expected.diffuse[0]), static_cast<float>(expected.diffuse[1]),
                            static_cast<float>(expected.diffuse[2])),
                        1e-6f, what + ": diffuse");
        expect_rgb_near(c.glossy, Rgb(static_cast<float>(expected.glossy)), 1e-6f, what + ": glossy");
        expect_rgb_near(
            c.transmission,
            Rgb(static_cast<float>(expected.transmission[0]), static_cast<float>(expected.transmission[1]),
                static_cast<float>(expected.transmission[2])),
            1e-6f, what + ": transmission");
    }
}

TEST(ColorPasses, PrincipledV2SplitsByLayer) {
    // Specular IOR Level 0 and no metal, coat or transmission: the diffuse closure alone, whole.
    Material m = material(STRATUM_MATERIAL_PRINCIPLED_V2, kColor);
    m.roughness = 0.5f;
    m.specular = 0.0f;
    const ClosureModel& v2 = closure_model(STRATUM_MATERIAL_PRINCIPLED_V2);
    ClosureColors c = v2.colors(m, view_at(0.7));
    expect_rgb_near(c.diffuse, kColor, 1e-6f, "no specular: diffuse");
    expect_rgb_near(c.glossy + c.transmission, Rgb(0.0f), 0.0f, "no specular: others");
    // A smooth metal seen at cos_o: Schlick's F0 + (1 − F0)(1 − cos_o)^5, all glossy.
    m.specular = 0.5f;
    m.metallic = 1.0f;
    m.roughness = 0.0f;
    c = v2.colors(m, view_at(0.5));
    const float sw = std::pow(0.5f, 5.0f);
    expect_rgb_near(c.glossy, kColor * (1.0f - sw) + Rgb(sw), 1e-6f, "metal: glossy");
    expect_rgb_near(c.diffuse + c.transmission, Rgb(0.0f), 0.0f, "metal: others");
    // A dielectric: what the specular layer takes (glossy) the diffuse below loses, so white
    // diffuse + glossy is 1 whatever the angle.
    m.metallic = 0.0f;
    m.roughness = 0.3f;
    m.base_color = Rgb(1.0f);
    for (const double cos_o : {0.2, 0.6, 1.0}) {
        c = v2.colors(m, view_at(cos_o));
        expect_rgb_near(c.diffuse + c.glossy, Rgb(1.0f), 1e-6f, "dielectric " + std::to_string(cos_o));
        EXPECT_GT(c.glossy.r, 0.0f);
    }
}

TEST(ColorPasses, ALambertQuadIsItsColourInDiffuseAndTheImageIsUnchanged) {
    StratumScene* scene = make_scene({{-3.0f, 0.5f, desc(STRATUM_MATERIAL_DIFFUSE, kColor)}});
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    const ColorPasses p = render(scene, kColorPasses);
    expect_everywhere(p.diffuse, kColor, 1e-6f, "DiffCol");
    expect_everywhere(p.glossy, Rgb(0.0f), 0.0f, "GlossCol");
    expect_everywhere(p.transmission, Rgb(0.0f), 0.0f, "TransCol");
    // The passes change nothing of the image.
    EXPECT_EQ(p.rgba, render(scene, "").rgba);
    // The AO integrator's surfaces are white diffuse.
    expect_everywhere(render(scene, kColorPasses, "ao").diffuse, Rgb(1.0f), 0.0f, "AO DiffCol");
    stratum_scene_destroy(scene);
}

TEST(ColorPasses, AGlossyQuadIsItsColourInGlossyAndAMixSplitsByWeight) {
    StratumScene* scene = make_scene({{-3.0f, 0.5f, desc(STRATUM_MATERIAL_GLOSSY, kColor, 0.3f)}});
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    ColorPasses p = render(scene, kColorPasses);
    expect_everywhere(p.glossy, kColor, 1e-6f, "GlossCol");
    expect_everywhere(p.diffuse, Rgb(0.0f), 0.0f, "DiffCol");
    expect_everywhere(p.transmission, Rgb(0.0f), 0.0f, "TransCol");
    stratum_scene_destroy(scene);
    // 0.3 Diffuse(kColor) + 0.7 Glossy(kTint): each pass holds its closure's weighted colour.
    scene = make_scene({});
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    const StratumClosureDesc closures[] = {{{0.3f, 0.3f, 0.3f}, desc(STRATUM_MATERIAL_DIFFUSE, kColor)},
                                           {{0.7f, 0.7f, 0.7f}, desc(STRATUM_MATERIAL_GLOSSY, kTint, 0.3f)}};
    uint32_t mat = 0, mesh_id = 0;
    ASSERT_EQ(stratum_scene_add_closure_material(scene, closures, 2, &mat), STRATUM_OK)
        << stratum_last_error();
    const float positions[] = {-4, -4, -3, 4, -4, -3, 4, 4, -3, -4, 4, -3};
    const uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
    const uint32_t mats[] = {mat, mat};
    const StratumMeshDesc mesh{positions, 4, triangles, 2, nullptr, nullptr, mats};
    ASSERT_EQ(stratum_scene_add_mesh(scene, &mesh, &mesh_id), STRATUM_OK);
    ASSERT_EQ(stratum_scene_add_instance(scene, mesh_id, kIdentity), STRATUM_OK);
    p = render(scene, kColorPasses);
    expect_everywhere(p.diffuse, kColor * 0.3f, 1e-6f, "mix DiffCol");
    expect_everywhere(p.glossy, kTint * 0.7f, 1e-6f, "mix GlossCol");
    stratum_scene_destroy(scene);
}

TEST(ColorPasses, SmoothGlassSplitsItsColourByTheFresnelOfTheViewAngle) {
    // Turned by 60°: every camera ray meets the glass at cos_o = 0.5. The refracted path is no
    // longer camera-visible, so the quad behind adds nothing.
    StratumScene* scene = make_scene({{-3.0f, 1.0471975511965976f, desc(STRATUM_MATERIAL_GLASS, kColor)},
                                      {-6.0f, 0.0f, desc(STRATUM_MATERIAL_DIFFUSE, kTint)}});
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    const ColorPasses p = render(scene, kColorPasses);
    const float f = static_cast<float>(fresnel(0.5, 1.5));
    expect_everywhere(p.glossy, kColor * f, 1e-5f, "GlossCol");
    expect_everywhere(p.transmission, kColor * (1.0f - f), 1e-5f, "TransCol");
    expect_everywhere(p.diffuse, Rgb(0.0f), 0.0f, "DiffCol");
    stratum_scene_destroy(scene);
}

TEST(ColorPasses, ATransparentQuadInFrontTintsWhatLiesBehind) {
    // Cycles adds the colours of every surface met through transparency, times the throughput:
    // the Diffuse quad behind the Transparent(kTint) one is seen as kTint × kColor.
    StratumScene* scene = make_scene({{-2.0f, 0.0f, desc(STRATUM_MATERIAL_TRANSPARENT, kTint)},
                                      {-4.0f, 0.3f, desc(STRATUM_MATERIAL_DIFFUSE, kColor)}});
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    const ColorPasses p = render(scene, kColorPasses);
    expect_everywhere(p.diffuse, kTint * kColor, 1e-6f, "DiffCol");
    expect_everywhere(p.glossy, Rgb(0.0f), 0.0f, "GlossCol");
    expect_everywhere(p.transmission, Rgb(0.0f), 0.0f, "TransCol");
    stratum_scene_destroy(scene);
}

TEST(ColorPasses, APrincipledV1QuadRendersCycles34Weights) {
    // Metallic 0.3, transmission 0.6, clearcoat 0.5, IOR 1.45, seen at cos_o = cos 40°.
    const float tilt = 0.6981317007977318f;
    StratumMaterialDesc d = desc(STRATUM_MATERIAL_PRINCIPLED_V1, kColor, 0.4f);
    d.metallic = 0.3f;
    d.ior = 1.45f;
    d.transmission = 0.6f;
    d.coat = 0.5f;
    d.coat_roughness = 0.1f;
    d.coat_ior = 1.5f;
    d.coat_tint[0] = d.coat_tint[1] = d.coat_tint[2] = 1.0f;
    StratumScene* scene = make_scene({{-3.0f, tilt, d}});
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    const ColorPasses p = render(scene, kColorPasses);
    Material m = material(STRATUM_MATERIAL_PRINCIPLED_V1, kColor);
    m.metallic = 0.3f;
    m.ior = 1.45f;
    m.transmission = 0.6f;
    m.coat = 0.5f;
    const Colors3 e = cycles34_principled(m, std::cos(static_cast<double>(tilt)));
    const auto rgb = [](const double* v) {
        return Rgb(static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2]));
    };
    expect_everywhere(p.diffuse, rgb(e.diffuse), 1e-5f, "DiffCol");
    expect_everywhere(p.glossy, Rgb(static_cast<float>(e.glossy)), 1e-5f, "GlossCol");
    expect_everywhere(p.transmission, rgb(e.transmission), 1e-5f, "TransCol");
    stratum_scene_destroy(scene);
}

TEST(ColorPasses, PrincipledV2DenoisingAlbedoIsTheSumOfItsColours) {
    // Cycles 4.x writes Σ bsdf_albedo of the closures to the Denoising Albedo, the same albedos
    // its colour passes hold (bsdf/bsdf.h: denoising_albedo_from_colors); here on a quad with
    // every layer present, seen at cos_o = cos 40°, the first surface of every camera ray.
    const float tilt = 0.6981317007977318f;
    StratumMaterialDesc d = desc(STRATUM_MATERIAL_PRINCIPLED_V2, kColor, 0.4f);
    d.metallic = 0.3f;
    d.transmission = 0.2f;
    d.coat = 0.5f;
    d.coat_roughness = 0.1f;
    d.coat_ior = 1.5f;
    d.coat_tint[0] = d.coat_tint[1] = d.coat_tint[2] = 1.0f;
    StratumScene* scene = make_scene({{-3.0f, tilt, d}});
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    const ColorPasses p = render(scene, "DiffCol,GlossCol,TransCol,Denoising Albedo");
    ASSERT_EQ(p.albedo.size(), static_cast<size_t>(kSize * kSize * 3));
    for (size_t i = 0; i < p.albedo.size(); ++i) {
        EXPECT_NEAR(p.albedo[i], p.diffuse[i] + p.glossy[i] + p.transmission[i], 1e-5f) << "value " << i;
    }
    stratum_scene_destroy(scene);
}
