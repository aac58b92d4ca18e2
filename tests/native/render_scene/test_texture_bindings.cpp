// Texture bindings: validation at stratum_scene_bind_texture, and apply_texture_bindings on
// base colour, scalar parameters (Cycles' colour -> float luminance), closure weights and
// tangent-space normal maps (Cycles' Normal Map node, svm/tex_coord.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include "render_scene/material_texturing.h"
#include "scene_handle.h"
#include "stratum/stratum.h"

using namespace stratum;

namespace {

// A 1x1 texture of one RGBA value (closest, repeat): every UV reads it.
std::shared_ptr<const Texture> constant_texture(Rgba v) {
    auto t = std::make_shared<Texture>();
    t->width = t->height = 1;
    t->rgba = {v.r, v.g, v.b, v.a};
    t->interpolation = TextureInterpolation::Closest;
    return t;
}

Material diffuse(Rgb colour) {
    return {STRATUM_MATERIAL_PRINCIPLED_V1, colour, 0.5f, 0.0f, 0.5f, 1.45f, Rgb(0.0f),
            MicrofacetDistribution::Ggx};
}

// One material of two closures, textured by `bindings` against `textures`.
struct Textured {
    Scene scene;
    std::vector<WeightedClosure> closures;
    Vec3 normal{0.0f, 0.0f, 1.0f};

    Textured(std::vector<std::shared_ptr<const Texture>> textures, std::vector<TextureBinding> bindings) {
        scene.materials.push_back({{{Rgb(0.5f), diffuse(Rgb(0.8f))}, {Rgb(0.5f), diffuse(Rgb(0.2f))}}});
        scene.textures = std::move(textures);
        scene.texture_bindings = std::move(bindings);
        closures = scene.materials[0].closures;
    }
    void apply(Vec3 dpdu = {1.0f, 0.0f, 0.0f}, float sign = 1.0f) {
        const TextureBindings data(scene);
        TangentFrame frame;
        frame.dpdu = dpdu;
        frame.bitangent_sign = sign;
        apply_texture_bindings(data, 0, {0.5f, 0.5f}, frame, closures.data(), 2, &normal);
    }
};

TextureBinding bind(MaterialParam param, uint32_t closure = 0, int32_t channel = -1, float scale = 1.0f,
                    float offset = 0.0f) {
    TextureBinding b;
    b.closure_index = closure;
    b.param = param;
    b.channel = channel;
    b.scale = scale;
    b.offset = offset;
    return b;
}

float angle_between(Vec3 a, Vec3 b) { return std::acos(std::clamp(dot(a, b), -1.0f, 1.0f)); }

}  // namespace

TEST(TextureBindings, BaseColourTakesTheTexelOfItsClosureOnly) {
    Textured m({constant_texture({0.1f, 0.6f, 0.3f, 1.0f})}, {bind(MaterialParam::BaseColor, 1)});
    m.apply();
    EXPECT_EQ(m.closures[1].params.base_color.r, 0.1f);
    EXPECT_EQ(m.closures[1].params.base_color.g, 0.6f);
    EXPECT_EQ(m.closures[1].params.base_color.b, 0.3f);
    EXPECT_EQ(m.closures[0].params.base_color.r, 0.8f);
}

TEST(TextureBindings, ScalarsUseLuminanceOrOneChannelWithScaleOffsetAndClamp) {
    const auto tex = constant_texture({0.2f, 0.4f, 0.8f, 0.3f});
    Textured m({tex},
               {bind(MaterialParam::Roughness), bind(MaterialParam::Metallic, 0, 3),
                bind(MaterialParam::Specular, 1, 1, 2.0f, 0.1f), bind(MaterialParam::Roughness, 1, 2, 2.0f)});
    m.apply();
    // Cycles' colour -> float: dot(rgb, rgb_to_y) with Rec.709 luminance weights.
    EXPECT_FLOAT_EQ(m.closures[0].params.roughness,
                    0.2126729f * 0.2f + 0.7151522f * 0.4f + 0.0721750f * 0.8f);
    EXPECT_FLOAT_EQ(m.closures[0].params.metallic, 0.3f);
    EXPECT_FLOAT_EQ(m.closures[1].params.specular, 0.1f + 2.0f * 0.4f);
    EXPECT_EQ(m.closures[1].params.roughness, 1.0f);  // 2 * 0.8 clamped
}

TEST(TextureBindings, WeightMultipliesTheClosureWeight) {
    Textured m({constant_texture({0.0f, 0.0f, 0.0f, 0.25f})}, {bind(MaterialParam::Weight, 1, 3)});
    m.apply();
    EXPECT_EQ(m.closures[1].weight.g, 0.5f * 0.25f);
    EXPECT_EQ(m.closures[0].weight.g, 0.5f);
}

TEST(TextureBindings, FlatNormalMapLeavesTheNormal) {
    Textured m({constant_texture({0.5f, 0.5f, 1.0f, 1.0f})}, {bind(MaterialParam::Normal)});
    m.apply({2.0f, 0.5f, 0.3f});
    EXPECT_NEAR(m.normal.x, 0.0f, 1e-6f);
    EXPECT_NEAR(m.normal.y, 0.0f, 1e-6f);
    EXPECT_NEAR(m.normal.z, 1.0f, 1e-6f);
}

// A texel encoding (sin t, 0, cos t) in tangent space tilts the normal by t toward the
// tangent; dpdu need be neither unit nor orthogonal to the normal. Green tilts toward the
// bitangent cross(N, T) = +y, or -y for mirrored UVs (sign -1).
TEST(TextureBindings, TiltedNormalMapTiltsByItsAngle) {
    const float t = 0.5f;  // radians
    const Rgba tilted_u{0.5f + 0.5f * std::sin(t), 0.5f, 0.5f + 0.5f * std::cos(t), 1.0f};
    Textured m({constant_texture(tilted_u)}, {bind(MaterialParam::Normal)});
    m.apply({3.0f, 0.0f, 0.7f});
    EXPECT_NEAR(angle_between(m.normal, {0.0f, 0.0f, 1.0f}), t, 1e-5f);
    EXPECT_NEAR(m.normal.x, std::sin(t), 1e-5f);
    EXPECT_NEAR(m.normal.y, 0.0f, 1e-6f);

    const Rgba tilted_v{0.5f, 0.5f + 0.5f * std::sin(t), 0.5f + 0.5f * std::cos(t), 1.0f};
    Textured plus({constant_texture(tilted_v)}, {bind(MaterialParam::Normal)});
    plus.apply({1.0f, 0.0f, 0.0f}, 1.0f);
    EXPECT_NEAR(plus.normal.y, std::sin(t), 1e-5f);
    Textured minus({constant_texture(tilted_v)}, {bind(MaterialParam::Normal)});
    minus.apply({1.0f, 0.0f, 0.0f}, -1.0f);
    EXPECT_NEAR(minus.normal.y, -std::sin(t), 1e-5f);
}

// Strength s != 1: N' = normalize(N + s (N_map - N)); for N = z and N_map at angle t in the
// xz plane the result is at atan2(s sin t, 1 - s + s cos t).
TEST(TextureBindings, NormalMapStrengthInterpolatesAsCycles) {
    const float t = 0.8f;
    const Rgba tilted{0.5f + 0.5f * std::sin(t), 0.5f, 0.5f + 0.5f * std::cos(t), 1.0f};
    for (float s : {0.0f, 0.5f, 2.0f, -1.0f}) {
        Textured m({constant_texture(tilted)}, {bind(MaterialParam::Normal, 0, -1, s)});
        m.apply();
        const float sc = std::max(s, 0.0f);
        const float expected = std::atan2(sc * std::sin(t), 1.0f - sc + sc * std::cos(t));
        EXPECT_NEAR(angle_between(m.normal, {0.0f, 0.0f, 1.0f}), std::abs(expected), 1e-5f) << s;
    }
}

TEST(TextureBindings, NoTangentKeepsTheNormal) {
    Textured m({constant_texture({1.0f, 0.5f, 0.5f, 1.0f})}, {bind(MaterialParam::Normal)});
    m.apply({0.0f, 0.0f, 0.0f});
    EXPECT_EQ(m.normal.z, 1.0f);
}

namespace {

struct AbiScene : stratum_test::SceneHandle {
    AbiScene() {
        const StratumMaterialDesc d{
            STRATUM_MATERIAL_DIFFUSE, {0.5f, 0.5f, 0.5f}, 1.0f, 0.0f, 0.0f, 1.5f, {0, 0, 0},
            STRATUM_MICROFACET_GGX};
        EXPECT_EQ(stratum_scene_add_material(scene, &d, nullptr), STRATUM_OK);
        const float px[4] = {0.5f, 0.5f, 1.0f, 1.0f};
        StratumTextureDesc t{};
        t.pixels = px;
        t.width = t.height = 1;
        t.channels = 4;
        t.color_space = "Non-Color";
        uint32_t id = 7;
        EXPECT_EQ(stratum_scene_add_texture(scene, &t, &id), STRATUM_OK) << stratum_last_error();
        EXPECT_EQ(id, 0u);
    }
};

StratumTextureBinding abi_binding(int32_t param) {
    StratumTextureBinding b{};
    b.param = param;
    b.channel = -1;
    b.scale = 1.0f;
    return b;
}

}  // namespace

TEST(TextureBindings, AbiRejectsBadBindingsNamingTheValue) {
    AbiScene s;
    const StratumTextureBinding normal = abi_binding(STRATUM_PARAM_NORMAL);
    ASSERT_EQ(stratum_scene_bind_texture(s.scene, &normal), STRATUM_OK) << stratum_last_error();
    struct Case {
        const char* expect;
        StratumTextureBinding b;
    };
    std::vector<Case> cases;
    StratumTextureBinding b = abi_binding(STRATUM_PARAM_BASE_COLOR);
    b.material_id = 3;
    cases.push_back({"material_id 3", b});
    b = abi_binding(STRATUM_PARAM_BASE_COLOR);
    b.closure_index = 1;
    cases.push_back({"closure_index 1", b});
    b = abi_binding(9);
    cases.push_back({"param 9", b});
    b = abi_binding(STRATUM_PARAM_BASE_COLOR);
    b.texture_id = 1;
    cases.push_back({"texture_id 1", b});
    b = abi_binding(STRATUM_PARAM_ROUGHNESS);
    b.channel = 4;
    cases.push_back({"channel 4", b});
    b = abi_binding(STRATUM_PARAM_NORMAL);
    b.channel = 0;
    cases.push_back({"NORMAL needs channel -1", b});
    b = abi_binding(STRATUM_PARAM_ROUGHNESS);
    b.scale = INFINITY;
    cases.push_back({"scale inf", b});
    b = abi_binding(STRATUM_PARAM_ROUGHNESS);
    b.offset = NAN;
    cases.push_back({"offset nan", b});
    cases.push_back({"EMISSION: textured emission is not supported", abi_binding(STRATUM_PARAM_EMISSION)});
    cases.push_back({"TRANSMISSION", abi_binding(STRATUM_PARAM_TRANSMISSION)});
    b = abi_binding(STRATUM_PARAM_METALLIC);
    b.emission_strength = 2.0f;
    cases.push_back({"emission_strength 2", b});
    for (const Case& c : cases) {
        EXPECT_EQ(stratum_scene_bind_texture(s.scene, &c.b), STRATUM_ERROR_INVALID_ARGUMENT) << c.expect;
        const std::string message = stratum_last_error();
        EXPECT_NE(message.find(c.expect), std::string::npos) << message;
    }
    EXPECT_EQ(stratum_scene_bind_texture(nullptr, &b), STRATUM_ERROR_INVALID_ARGUMENT);
}

// The scene file keeps textures (decoded) and bindings: saving the reloaded scene gives the
// same file.
TEST(TextureBindings, SceneFileRoundTripsTexturesAndBindings) {
    AbiScene s;
    StratumTextureBinding b = abi_binding(STRATUM_PARAM_ROUGHNESS);
    b.channel = 2;
    b.scale = 0.5f;
    b.offset = 0.25f;
    ASSERT_EQ(stratum_scene_bind_texture(s.scene, &b), STRATUM_OK) << stratum_last_error();
    const std::string a = ::testing::TempDir() + "stratum_texture_a.json";
    const std::string c = ::testing::TempDir() + "stratum_texture_b.json";
    ASSERT_EQ(stratum_scene_save(s.scene, a.c_str()), STRATUM_OK) << stratum_last_error();
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(a.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    ASSERT_EQ(stratum_scene_save(loaded, c.c_str()), STRATUM_OK);
    stratum_scene_destroy(loaded);
    std::ifstream fa(a), fc(c);
    const std::string text_a((std::istreambuf_iterator<char>(fa)), std::istreambuf_iterator<char>());
    const std::string text_c((std::istreambuf_iterator<char>(fc)), std::istreambuf_iterator<char>());
    EXPECT_NE(text_a.find("\"textures\""), std::string::npos);
    EXPECT_EQ(text_a, text_c);
}
