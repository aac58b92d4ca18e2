// Shader node programs through the C ABI (stratum/shader_nodes.h): what the checks refuse, what
// a program computes, how its outputs drive a rendered closure, and that a scene file keeps it.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "node_types.h"
#include "render_helpers.h"
#include "scene_handle.h"

using namespace stratum_test;

namespace {

using stratum_test::node_type;

constexpr uint32_t kInputs = STRATUM_SHADER_INPUT_REGISTERS;
// Native math operations used below (Cycles' NodeMathType order).
constexpr int32_t kAdd = 0, kMultiply = 2, kSine = 4;

StratumShaderNode math(int32_t op, uint32_t a, uint32_t b, uint32_t out, int32_t clamp = 0) {
    StratumShaderNode n{};
    n.type = node_type("math");
    n.modes[0] = op;
    n.modes[1] = clamp;
    n.inputs[0] = a;
    n.inputs[1] = b;
    n.inputs[2] = a;
    n.outputs[0] = out;
    return n;
}

// sin(k * generated.x) into register kInputs + 1, k in register kInputs.
struct SineProgram {
    std::vector<StratumShaderNode> nodes;
    std::vector<float> registers;
    explicit SineProgram(float k) : registers(kInputs + 3, 0.0f) {
        registers[kInputs] = k;
        nodes.push_back(math(kMultiply, STRATUM_INPUT_GENERATED, kInputs, kInputs + 2));
        nodes.push_back(math(kSine, kInputs + 2, kInputs + 2, kInputs + 1));
    }
    StratumShaderProgramDesc desc() const {
        return {nodes.data(),     static_cast<uint32_t>(nodes.size()),
                registers.data(), static_cast<uint32_t>(registers.size()),
                nullptr,          0};
    }
};

StratumStatus add(StratumScene* scene, const std::vector<StratumShaderNode>& nodes,
                  std::vector<float> registers, std::vector<float> data = {}) {
    const StratumShaderProgramDesc d{nodes.data(),
                                     static_cast<uint32_t>(nodes.size()),
                                     registers.data(),
                                     static_cast<uint32_t>(registers.size()),
                                     data.empty() ? nullptr : data.data(),
                                     static_cast<uint32_t>(data.size())};
    return stratum_scene_add_shader_program(scene, &d, nullptr);
}

std::string read(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST(ShaderPrograms, EvaluatesAProgramOnGivenInputs) {
    SceneHandle h;
    const SineProgram p(6.0f);
    const StratumShaderProgramDesc d = p.desc();
    uint32_t id = 99;
    ASSERT_EQ(stratum_scene_add_shader_program(h.scene, &d, &id), STRATUM_OK) << stratum_last_error();
    EXPECT_EQ(id, 0u);
    std::vector<float> inputs(kInputs, 0.0f);
    for (float x : {0.0f, 0.1f, 0.37f, 1.0f}) {
        inputs[STRATUM_INPUT_GENERATED] = x;
        float out = -5.0f;
        ASSERT_EQ(stratum_scene_evaluate_program(h.scene, 0, inputs.data(), kInputs + 1, 1, &out),
                  STRATUM_OK);
        EXPECT_FLOAT_EQ(out, std::sin(6.0f * x)) << x;
    }
}

TEST(ShaderPrograms, RefusesBadProgramsNamingTheNodeAndField) {
    SceneHandle h;
    const std::vector<float> regs(kInputs + 4, 0.0f);
    struct Case {
        StratumShaderNode node;
        const char* expected;
    };
    StratumShaderNode unknown = math(kAdd, 0, 0, kInputs);
    unknown.type = 1000;
    StratumShaderNode bad_op = math(999, 0, 0, kInputs);
    StratumShaderNode bad_clamp = math(kAdd, 0, 0, kInputs, 2);
    StratumShaderNode far_input = math(kAdd, 0xFFFFFFFFu, 0, kInputs);
    StratumShaderNode writes_input = math(kAdd, 0, 0, STRATUM_INPUT_NORMAL);
    StratumShaderNode bad_data = math(kAdd, 0, 0, kInputs);
    bad_data.data_offset = 3;
    bad_data.data_count = 2;
    for (const Case& c : {Case{unknown, "unknown type 1000"}, Case{bad_op, "mode 0 (operation) is 999"},
                          Case{bad_clamp, "mode 1 (clamp) is 2"}, Case{far_input, "register 4294967295"},
                          Case{writes_input, "input registers"}, Case{bad_data, "data range"}}) {
        EXPECT_EQ(add(h.scene, {math(kAdd, 0, 0, kInputs), c.node}, regs), STRATUM_ERROR_INVALID_ARGUMENT);
        const std::string error = stratum_last_error();
        EXPECT_NE(error.find("program node 1"), std::string::npos) << error;
        EXPECT_NE(error.find(c.expected), std::string::npos) << error;
    }
    std::vector<float> nan_regs = regs;
    nan_regs[kInputs + 1] = std::nanf("");
    EXPECT_EQ(add(h.scene, {}, nan_regs), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("not finite"), std::string::npos);
    EXPECT_EQ(add(h.scene, {}, std::vector<float>(kInputs - 1, 0.0f)), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_scene_add_shader_program(h.scene, nullptr, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    uint32_t count = 0;
    ASSERT_EQ(stratum_scene_add_shader_program(h.scene, nullptr, &count), STRATUM_ERROR_INVALID_ARGUMENT);
    // None of them was added: the next program is id 0.
    uint32_t id = 7;
    const SineProgram p(1.0f);
    const StratumShaderProgramDesc d = p.desc();
    ASSERT_EQ(stratum_scene_add_shader_program(h.scene, &d, &id), STRATUM_OK);
    EXPECT_EQ(id, 0u);
}

TEST(ShaderPrograms, RefusesBadBindings) {
    SceneHandle h;
    const StratumMaterialDesc m = diffuse_grey(0.5f);
    ASSERT_EQ(stratum_scene_add_material(h.scene, &m, nullptr), STRATUM_OK);
    const SineProgram p(1.0f);
    const StratumShaderProgramDesc d = p.desc();
    ASSERT_EQ(stratum_scene_add_shader_program(h.scene, &d, nullptr), STRATUM_OK);
    const uint32_t last = static_cast<uint32_t>(p.registers.size()) - 1;
    struct Case {
        StratumProgramBinding binding;
        const char* expected;
    };
    for (const Case& c : {Case{{1, 0, STRATUM_PROGRAM_ROUGHNESS, 0, kInputs}, "material_id 1"},
                          Case{{0, 1, STRATUM_PROGRAM_ROUGHNESS, 0, kInputs}, "closure_index 1"},
                          Case{{0, 0, 12, 0, kInputs}, "param 12"},
                          Case{{0, 0, STRATUM_PROGRAM_ROUGHNESS, 1, kInputs}, "program_id 1"},
                          Case{{0, 0, STRATUM_PROGRAM_BASE_COLOR, 0, last}, "3 wide"}}) {
        EXPECT_EQ(stratum_scene_bind_program(h.scene, &c.binding), STRATUM_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(stratum_last_error()).find(c.expected), std::string::npos)
            << stratum_last_error();
    }
    const StratumProgramBinding ok{0, 0, STRATUM_PROGRAM_ROUGHNESS, 0, last};
    EXPECT_EQ(stratum_scene_bind_program(h.scene, &ok), STRATUM_OK) << stratum_last_error();
}

// An emitting square seen straight on by an orthographic camera, 1 sample per pixel at the pixel
// centre (box filter 0.01 px): each pixel is the program's emission at that point.
TEST(ShaderPrograms, DriveTheEmissionSeenByTheCamera) {
    SceneHandle h;
    StratumMaterialDesc m = diffuse_grey(0.0f);
    m.model = STRATUM_MATERIAL_EMISSION;
    ASSERT_EQ(stratum_scene_add_material(h.scene, &m, nullptr), STRATUM_OK);
    ASSERT_TRUE(add_square_instance(h.scene, 0.0f, 1.0f, 0));
    // Emission = (sin(6 x), 2, -0.5) with x the generated coordinate, in registers kInputs + 2..4:
    // a negative channel stays negative, as in Cycles.
    std::vector<float> regs(kInputs + 5, 0.0f);
    regs[kInputs] = 6.0f;
    regs[kInputs + 3] = 2.0f;
    regs[kInputs + 4] = -0.5f;
    const std::vector<StratumShaderNode> nodes = {
        math(kMultiply, STRATUM_INPUT_GENERATED, kInputs, kInputs + 1),
        math(kSine, kInputs + 1, kInputs + 1, kInputs + 2)};
    ASSERT_EQ(add(h.scene, nodes, regs), STRATUM_OK) << stratum_last_error();
    constexpr int kSize = 16;
    const stratum_test::RenderOutput out = stratum_test::render_pixel_centres(
        h.scene, kInputs + 2, kSize, stratum_test::CentreView::kOrthographic);
    ASSERT_TRUE(out.error.empty()) << out.error;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const float* px = &out.rgba[(static_cast<size_t>(y) * kSize + x) * 4];
            // Generated x runs 0..1 over the square, which fills the frame; the sample lies within
            // 0.005 px of the centre: |d sin(6x)/dx| 0.005 / 16 <= 2e-3.
            const float gx = (static_cast<float>(x) + 0.5f) / kSize;
            EXPECT_NEAR(px[0], std::sin(6.0f * gx), 2e-3f) << x << "," << y;
            EXPECT_FLOAT_EQ(px[1], 2.0f);
            EXPECT_FLOAT_EQ(px[2], -0.5f);
        }
    }
}

TEST(ShaderPrograms, SceneFileKeepsProgramsBindingsAndTextureSpaces) {
    const std::string a = ::testing::TempDir() + "programs_a.json",
                      b = ::testing::TempDir() + "programs_b.json";
    {
        SceneHandle h;
        const StratumMaterialDesc m = diffuse_grey(0.5f);
        ASSERT_EQ(stratum_scene_add_material(h.scene, &m, nullptr), STRATUM_OK);
        ASSERT_TRUE(add_square_instance(h.scene, 0.0f, 1.0f, 0));
        const float loc[3] = {0.5f, 0.0f, 0.0f}, size[3] = {2.0f, 0.0f, 1e-7f};
        ASSERT_EQ(stratum_scene_set_mesh_texture_space(h.scene, 0, loc, size), STRATUM_OK);
        const SineProgram p(3.0f);
        const StratumShaderProgramDesc d = p.desc();
        ASSERT_EQ(stratum_scene_add_shader_program(h.scene, &d, nullptr), STRATUM_OK);
        const StratumProgramBinding bind{0, 0, STRATUM_PROGRAM_METALLIC, 0, kInputs + 1};
        ASSERT_EQ(stratum_scene_bind_program(h.scene, &bind), STRATUM_OK);
        ASSERT_EQ(stratum_scene_save(h.scene, a.c_str()), STRATUM_OK) << stratum_last_error();
    }
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(a.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    std::vector<float> inputs(kInputs, 0.0f);
    inputs[STRATUM_INPUT_GENERATED] = 0.25f;
    float out = 0.0f;
    ASSERT_EQ(stratum_scene_evaluate_program(loaded, 0, inputs.data(), kInputs + 1, 1, &out), STRATUM_OK);
    EXPECT_FLOAT_EQ(out, std::sin(0.75f));
    ASSERT_EQ(stratum_scene_save(loaded, b.c_str()), STRATUM_OK);
    stratum_scene_destroy(loaded);
    const std::string text = read(a);
    EXPECT_EQ(text, read(b));
    for (const char* field : {"\"programs\"", "\"bindings\"", "\"texture_spaces\""})
        EXPECT_NE(text.find(field), std::string::npos) << field;
    std::remove(a.c_str());
    std::remove(b.c_str());
}

// The world's program is baked into the environment: a program returning (z, 1, 0) for the
// direction's z gives texels holding the mean of cos(theta) over the texel's 2 x 2 directions.
TEST(ShaderPrograms, BakesTheWorldProgram) {
    SceneHandle h;
    std::vector<StratumShaderNode> nodes = {math(kAdd, STRATUM_INPUT_POSITION + 2, kInputs + 3, kInputs)};
    std::vector<float> regs(kInputs + 4, 0.0f);
    regs[kInputs + 1] = 1.0f;
    ASSERT_EQ(add(h.scene, nodes, regs), STRATUM_OK) << stratum_last_error();
    EXPECT_EQ(stratum_scene_set_background_program(h.scene, 0, kInputs, 8, 4), STRATUM_OK)
        << stratum_last_error();
    EXPECT_EQ(stratum_scene_set_background_program(h.scene, 0, kInputs, 3, 4),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_scene_set_background_program(h.scene, 0, kInputs + 2, 8, 4),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_scene_set_background_program(h.scene, 1, kInputs, 8, 4),
              STRATUM_ERROR_INVALID_ARGUMENT);
    const std::string path = ::testing::TempDir() + "world_program.json";
    ASSERT_EQ(stratum_scene_save(h.scene, path.c_str()), STRATUM_OK);
    const nlohmann::json file = nlohmann::json::parse(read(path));
    std::remove(path.c_str());
    const auto rgb = file.at("environment").at("rgb").get<std::vector<float>>();
    ASSERT_EQ(rgb.size(), 8u * 4u * 3u);
    // Row j holds theta in [j, j + 1] pi / 4, sampled at (j + 1/4) and (j + 3/4) of it; a
    // negative z counts 0, as environment pixels do.
    const double pi = 3.14159265358979;
    for (int row = 0; row < 4; ++row) {
        double expected = 0.0;
        for (double f : {0.25, 0.75}) expected += 0.5 * std::max(std::cos(pi / 4 * (row + f)), 0.0);
        for (int col = 0; col < 8; ++col) {
            const float* texel = &rgb[(static_cast<size_t>(row) * 8 + col) * 3];
            EXPECT_NEAR(texel[0], expected, 1e-6) << row << "," << col;
            EXPECT_FLOAT_EQ(texel[1], 1.0f);
            EXPECT_FLOAT_EQ(texel[2], 0.0f);
        }
    }
}

// Cycles' CPU kernels fuse Wrap's and Floored Modulo's product and difference (one rounding):
// Cycles renders Wrap(1e9, 3, 0) as -32 in Blender 3.4 and 5.0 (measured), where the two-rounding
// formula gives 1.
TEST(ShaderPrograms, MathWrapRoundsOnceAsCyclesDoes) {
    SceneHandle h;
    constexpr int32_t kWrap = 34, kFlooredModulo = 40;
    std::vector<float> regs(kInputs + 6, 0.0f);
    regs[kInputs] = 1e9f;
    regs[kInputs + 1] = 3.0f;
    StratumShaderNode wrap = math(kWrap, kInputs, kInputs + 1, kInputs + 3);
    wrap.inputs[2] = kInputs + 2;
    const std::vector<StratumShaderNode> nodes = {wrap,
                                                  math(kFlooredModulo, kInputs, kInputs + 1, kInputs + 4)};
    ASSERT_EQ(add(h.scene, nodes, regs), STRATUM_OK) << stratum_last_error();
    std::vector<float> inputs(kInputs, 0.0f);
    float out[2] = {0.0f, 0.0f};
    ASSERT_EQ(stratum_scene_evaluate_program(h.scene, 0, inputs.data(), kInputs + 3, 2, out), STRATUM_OK);
    EXPECT_EQ(out[0], -32.0f);
    EXPECT_EQ(out[1], std::fma(-std::floor(1e9f / 3.0f), 3.0f, 1e9f));
}
