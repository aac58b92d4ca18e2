// Light Falloff (shading/nodes/light_falloff_node.cpp) through the C ABI: its three outputs on
// given ray lengths in both revisions, and rendered, where the renderer's RAY_LENGTH feeds it.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <cfloat>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "node_types.h"
#include "render_helpers.h"
#include "scene_handle.h"

namespace {

using stratum_test::node_type;

constexpr uint32_t kInputs = STRATUM_SHADER_INPUT_REGISTERS;
constexpr int32_t kBefore44 = 0, kFrom44 = 1;

// One Light Falloff node: strength and smooth constants in kInputs, kInputs + 1, the ray length
// from the renderer's RAY_LENGTH; quadratic, linear, constant in kInputs + 2 .. kInputs + 4.
StratumStatus add_light_falloff(StratumScene* scene, float strength, float smooth, int32_t revision) {
    StratumShaderNode node{};
    node.type = node_type("light_falloff");
    node.modes[0] = revision;
    node.inputs[0] = kInputs;
    node.inputs[1] = kInputs + 1;
    node.inputs[2] = STRATUM_INPUT_RAY_LENGTH;
    for (uint32_t k = 0; k < 3; ++k) node.outputs[k] = kInputs + 2 + k;
    std::vector<float> registers(kInputs + 5, 0.0f);
    registers[kInputs] = strength;
    registers[kInputs + 1] = smooth;
    const StratumShaderProgramDesc desc{&node,   1, registers.data(), static_cast<uint32_t>(registers.size()),
                                        nullptr, 0};
    return stratum_scene_add_shader_program(scene, &desc, nullptr);
}

// {quadratic, linear, constant} at ray length `l`.
std::vector<float> falloff(float strength, float smooth, float l, int32_t revision) {
    stratum_test::SceneHandle h;
    EXPECT_EQ(add_light_falloff(h.scene, strength, smooth, revision), STRATUM_OK) << stratum_last_error();
    std::vector<float> inputs(kInputs, 0.0f);
    inputs[STRATUM_INPUT_RAY_LENGTH] = l;
    std::vector<float> out(3, -9.0f);
    EXPECT_EQ(stratum_scene_evaluate_program(h.scene, 0, inputs.data(), kInputs + 2, 3, out.data()),
              STRATUM_OK);
    return out;
}

TEST(LightFalloffNode, MultipliesTheStrengthByPowersOfTheRayLength) {
    for (int32_t revision : {kBefore44, kFrom44}) {
        EXPECT_EQ(falloff(3.0f, 0.0f, 2.0f, revision), (std::vector<float>{3.0f, 6.0f, 12.0f}));
        // Smooth 4 at l = 2: l² / (smooth + l²) = 1/2.
        EXPECT_EQ(falloff(3.0f, 4.0f, 2.0f, revision), (std::vector<float>{1.5f, 3.0f, 6.0f}));
        // A negative smooth does not smooth.
        EXPECT_EQ(falloff(3.0f, -4.0f, 2.0f, revision), (std::vector<float>{3.0f, 6.0f, 12.0f}));
    }
}

// The world and suns have a ray length of FLT_MAX in Cycles (the renderer writes infinity for
// the world): Cycles before 4.4 multiplies by it (and skips the smoothing, whose l² overflows);
// 4.4 and later give the strength on every output.
TEST(LightFalloffNode, ARayLengthAtInfinityIsCyclesFltMaxInEachRevision) {
    for (float l : {FLT_MAX, std::numeric_limits<float>::infinity()}) {
        for (float smooth : {0.0f, 1.0f}) {
            const std::vector<float> before = falloff(0.5f, smooth, l, kBefore44);
            EXPECT_EQ(before[0], 0.5f);
            EXPECT_EQ(before[1], 0.5f * FLT_MAX);
            EXPECT_EQ(before[2], std::numeric_limits<float>::infinity());
            EXPECT_EQ(falloff(0.5f, smooth, l, kFrom44), (std::vector<float>{0.5f, 0.5f, 0.5f}));
        }
    }
}

TEST(LightFalloffNode, RefusesAnUnknownRevision) {
    stratum_test::SceneHandle h;
    EXPECT_EQ(add_light_falloff(h.scene, 1.0f, 0.0f, 2), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("mode 0 (revision) is 2"), std::string::npos)
        << stratum_last_error();
}

// A square 3 in front of a perspective camera whose emission is the node's outputs for strength
// 1: (1, l, l²) with l the distance from the camera to each pixel's point.
TEST(LightFalloffNode, ReadsTheRenderersRayLengthAtEachPixel) {
    stratum_test::SceneHandle h;
    StratumMaterialDesc m = stratum_test::diffuse_grey(0.0f);
    m.model = STRATUM_MATERIAL_EMISSION;
    ASSERT_EQ(stratum_scene_add_material(h.scene, &m, nullptr), STRATUM_OK);
    ASSERT_TRUE(stratum_test::add_square_instance(h.scene, 0.0f, 10.0f, 0));
    ASSERT_EQ(add_light_falloff(h.scene, 1.0f, 0.0f, kFrom44), STRATUM_OK) << stratum_last_error();
    constexpr int kSize = 8;
    const stratum_test::RenderOutput out = stratum_test::render_pixel_centres(
        h.scene, kInputs + 2, kSize, stratum_test::CentreView::kPerspective);
    ASSERT_TRUE(out.error.empty()) << out.error;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const float* px = &out.rgba[(static_cast<size_t>(y) * kSize + x) * 4];
            // 90 degrees across 8 pixels: the pixel centre's point is 3 (u, v, 1) away,
            // u = (x + 0.5) / 4 - 1. The sample lies within 0.005 px of it in x and y, where l
            // changes by at most 3 x 0.25 per pixel in each (7.5e-3), l² by 2 l times that.
            const double u = (x + 0.5) / 4.0 - 1.0, v = (y + 0.5) / 4.0 - 1.0;
            const double l = 3.0 * std::sqrt(u * u + v * v + 1.0);
            EXPECT_EQ(px[0], 1.0f);
            EXPECT_NEAR(px[1], l, 7.5e-3) << x << "," << y;
            EXPECT_NEAR(px[2], l * l, 2.0 * l * 7.5e-3) << x << "," << y;
            EXPECT_NEAR(px[2], px[1] * px[1], 1e-5 * px[2]) << x << "," << y;
        }
    }
}

}  // namespace
