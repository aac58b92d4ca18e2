// The colour nodes (mix_node.cpp, color_adjust_nodes.cpp, color_convert_nodes.cpp, ramp_node.cpp)
// run through the C ABI on one-node programs, against values computed here from the blends'
// definitions (Cycles' color_util.h, written out per channel) and closed forms of colours whose
// HSV/HSL are known: (0.8, 0.4, 0.2) is hue 20 degrees (1/18), HSV saturation 0.75, value 0.8,
// HSL saturation 0.6, lightness 0.5.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "node_types.h"
#include "scene_handle.h"

namespace {

using stratum_test::node_type;

using stratum_test::SceneHandle;

constexpr uint32_t kIn = STRATUM_SHADER_INPUT_REGISTERS;

// A one-node program: registers kIn.. hold `values`, the outputs follow them.
struct OneNode {
    StratumShaderNode node{};
    std::vector<float> registers = std::vector<float>(kIn, 0.0f);
    std::vector<float> data;
    std::vector<float> inputs = std::vector<float>(kIn, 0.0f);  // the renderer's registers

    uint32_t value(std::initializer_list<float> v) {
        const auto at = static_cast<uint32_t>(registers.size());
        registers.insert(registers.end(), v);
        return at;
    }
    uint32_t output(uint32_t width) {
        const auto at = static_cast<uint32_t>(registers.size());
        registers.resize(registers.size() + width, -7.0f);
        return at;
    }
    StratumStatus add(SceneHandle& h, uint32_t* id) {
        node.data_offset = 0;
        node.data_count = static_cast<uint32_t>(data.size());
        const StratumShaderProgramDesc d{&node,
                                         1,
                                         registers.data(),
                                         static_cast<uint32_t>(registers.size()),
                                         data.empty() ? nullptr : data.data(),
                                         static_cast<uint32_t>(data.size())};
        return stratum_scene_add_shader_program(h.scene, &d, id);
    }
    // Runs the node and returns `count` registers from `first`.
    std::vector<float> run(uint32_t first, uint32_t count) {
        SceneHandle h;
        uint32_t id = 0;
        EXPECT_EQ(add(h, &id), STRATUM_OK) << stratum_last_error();
        std::vector<float> out(count, 0.0f);
        EXPECT_EQ(stratum_scene_evaluate_program(h.scene, id, inputs.data(), first, count, out.data()),
                  STRATUM_OK)
            << stratum_last_error();
        return out;
    }
    std::string rejected() {
        SceneHandle h;
        uint32_t id = 0;
        EXPECT_NE(add(h, &id), STRATUM_OK);
        return stratum_last_error();
    }
};

void expect_near3(const std::vector<float>& got, std::array<double, 3> want, double tol = 1e-6) {
    ASSERT_EQ(got.size(), 3u);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], tol) << "component " << k;
}

// ---- Mix ---------------------------------------------------------------------------------------

enum { kFloat = 0, kVector = 1, kNonUniform = 2, kColor = 3 };

std::vector<float> mix_color(int blend, float t, std::array<float, 3> a, std::array<float, 3> b,
                             bool clamp_factor = true, bool clamp_result = false) {
    OneNode p;
    p.node.type = node_type("mix");
    p.node.modes[0] = kColor;
    p.node.modes[1] = blend;
    p.node.modes[2] = clamp_factor;
    p.node.modes[3] = clamp_result;
    p.node.inputs[0] = p.value({t});
    p.node.inputs[1] = p.value({a[0], a[1], a[2]});
    p.node.inputs[2] = p.value({b[0], b[1], b[2]});
    p.node.outputs[0] = p.output(3);
    return p.run(p.node.outputs[0], 3);
}

TEST(ColorNodes, MixPerChannelBlends) {
    // Channels chosen to take both branches of Overlay (a below / above 0.5), of Divide (b = 0)
    // and the limits of Dodge and Burn.
    const std::array<float, 3> ca{0.2f, 0.6f, 0.9f}, cb{0.5f, 0.0f, 0.8f};
    const double fac = 0.4;
    struct Case {
        int blend;
        const char* name;
        double (*f)(double t, double a, double b);
    };
    const Case cases[] = {
        {0, "mix", [](double t, double a, double b) { return a + t * (b - a); }},
        {1, "add", [](double t, double a, double b) { return a + t * b; }},
        {2, "multiply", [](double t, double a, double b) { return a * (1 - t + t * b); }},
        {3, "subtract", [](double t, double a, double b) { return a - t * b; }},
        {4, "screen", [](double t, double a, double b) { return 1 - (1 - t * b) * (1 - a); }},
        {5, "divide", [](double t, double a, double b) { return b == 0 ? a : (1 - t) * a + t * a / b; }},
        {6, "difference", [](double t, double a, double b) { return a + t * (std::fabs(a - b) - a); }},
        {7, "darken", [](double t, double a, double b) { return a + t * (std::min(a, b) - a); }},
        {8, "lighten", [](double t, double a, double b) { return a + t * (std::max(a, b) - a); }},
        {9, "overlay",
         [](double t, double a, double b) {
             return a < 0.5 ? a * (1 - t + 2 * t * b) : 1 - (1 - t + 2 * t * (1 - b)) * (1 - a);
         }},
        {10, "dodge", [](double t, double a, double b) { return std::min(1.0, a / (1 - t * b)); }},
        {11, "burn",
         [](double t, double a, double b) { return std::clamp(1 - (1 - a) / (1 - t + t * b), 0.0, 1.0); }},
        {16, "soft light",
         [](double t, double a, double b) {
             return (1 - t) * a + t * ((1 - a) * b * a + a * (1 - (1 - b) * (1 - a)));
         }},
        {17, "linear light", [](double t, double a, double b) { return a + t * (2 * b - 1); }},
        {18, "exclusion",
         [](double t, double a, double b) { return std::max(0.0, a + t * (b - 2 * a * b)); }},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.name);
        const auto got = mix_color(c.blend, static_cast<float>(fac), ca, cb);
        expect_near3(got, {c.f(fac, ca[0], cb[0]), c.f(fac, ca[1], cb[1]), c.f(fac, ca[2], cb[2])});
    }
}

TEST(ColorNodes, MixBlendLimits) {
    // Dodge: 1 - t b <= 0 gives 1; a channel of 0 stays 0. Burn: 1 - t + t b <= 0 gives 0, and
    // the result is clamped to [0, 1]. Exclusion is clamped below at 0.
    expect_near3(mix_color(10, 1.0f, {0.5f, 0.0f, 0.3f}, {1.0f, 1.0f, 0.5f}), {1.0, 0.0, 0.6});
    expect_near3(mix_color(11, 1.0f, {0.5f, 1.5f, 0.2f}, {0.0f, 1.0f, 0.5f}), {0.0, 1.0, 0.0});
    expect_near3(mix_color(18, 1.0f, {2.0f, 0.5f, 0.0f}, {2.0f, 0.5f, 0.0f}), {0.0, 0.5, 0.0});
}

TEST(ColorNodes, MixHsvBlends) {
    const std::array<float, 3> a{0.8f, 0.4f, 0.2f};     // hue 1/18, s 0.75, v 0.8
    const std::array<float, 3> blue{0.2f, 0.2f, 0.8f};  // hue 2/3, s 0.75, v 0.8
    const std::array<float, 3> pale{0.5f, 0.5f, 1.0f};  // hue 2/3, s 0.5, v 1
    const std::array<float, 3> grey{0.3f, 0.3f, 0.3f};  // s 0
    const double t = 0.4;
    const auto towards = [&](std::array<double, 3> target) {
        return std::array<double, 3>{a[0] + t * (target[0] - a[0]), a[1] + t * (target[1] - a[1]),
                                     a[2] + t * (target[2] - a[2])};
    };
    // Hue: a's saturation and value with blue's hue is blue itself.
    expect_near3(mix_color(12, 0.4f, a, blue), towards({0.2, 0.2, 0.8}));
    // Color: blue's hue and saturation, a's value: blue again.
    expect_near3(mix_color(15, 0.4f, a, blue), towards({0.2, 0.2, 0.8}));
    // A grey B has no hue: Hue and Color leave A.
    expect_near3(mix_color(12, 0.4f, a, grey), {0.8, 0.4, 0.2});
    expect_near3(mix_color(15, 0.4f, a, grey), {0.8, 0.4, 0.2});
    // Saturation 0.6 * 0.75 + 0.4 * 0.5 = 0.65 at hue 20 degrees (f = 1/3 of sector 0), value 0.8.
    const double sat = 0.65;
    expect_near3(mix_color(13, 0.4f, a, pale), {0.8, 0.8 * (1 - sat * 2.0 / 3.0), 0.8 * (1 - sat)}, 1e-5);
    // Value 0.6 * 0.8 + 0.4 * 1 = 0.88: a scaled by 1.1.
    expect_near3(mix_color(14, 0.4f, a, pale), {0.88, 0.44, 0.22}, 1e-5);
    // A grey A has no saturation to change.
    expect_near3(mix_color(13, 0.4f, grey, pale), {0.3, 0.3, 0.3});
}

TEST(ColorNodes, MixClampFactorAndResult) {
    const std::array<float, 3> a{0.2f, 0.6f, 0.9f}, b{0.5f, 1.0f, 0.8f};
    // Factor 1.5 clamped to 1 (MixRGB always, Mix when Clamp Factor) gives the Add of b.
    expect_near3(mix_color(1, 1.5f, a, b), {0.7, 1.6, 1.7});
    // Unclamped factor: a + 1.5 b.
    expect_near3(mix_color(1, 1.5f, a, b, false), {0.95, 2.1, 2.1});
    // Clamp Result saturates the sum.
    expect_near3(mix_color(1, 1.5f, a, b, true, true), {0.7, 1.0, 1.0});
    // Clamp Result sends a negative result to 0.
    expect_near3(mix_color(3, 1.0f, a, b, true, true), {0.0, 0.0, 0.1});
}

TEST(ColorNodes, MixFloatAndVectors) {
    for (const int clamp : {0, 1}) {
        OneNode p;
        p.node.type = node_type("mix");
        p.node.modes[0] = kFloat;
        p.node.modes[2] = clamp;
        p.node.inputs[0] = p.value({1.25f});
        p.node.inputs[1] = p.value({2.0f});
        p.node.inputs[2] = p.value({6.0f});
        p.node.outputs[0] = p.output(1);
        EXPECT_NEAR(p.run(p.node.outputs[0], 1)[0], clamp ? 6.0 : 7.0, 1e-6);
    }
    {
        OneNode p;
        p.node.type = node_type("mix");
        p.node.modes[0] = kVector;
        p.node.modes[2] = 0;
        p.node.inputs[0] = p.value({-0.5f});
        p.node.inputs[1] = p.value({1.0f, 2.0f, 3.0f});
        p.node.inputs[2] = p.value({3.0f, 2.0f, -1.0f});
        p.node.outputs[0] = p.output(3);
        expect_near3(p.run(p.node.outputs[0], 3), {0.0, 2.0, 5.0});
    }
    {
        OneNode p;
        p.node.type = node_type("mix");
        p.node.modes[0] = kNonUniform;
        p.node.modes[2] = 1;  // each factor clamped
        p.node.inputs[0] = p.value({0.25f, -1.0f, 2.0f});
        p.node.inputs[1] = p.value({1.0f, 2.0f, 3.0f});
        p.node.inputs[2] = p.value({3.0f, 2.0f, -1.0f});
        p.node.outputs[0] = p.output(3);
        expect_near3(p.run(p.node.outputs[0], 3), {1.5, 2.0, -1.0});
    }
}

// ---- Adjustments -------------------------------------------------------------------------------

TEST(ColorNodes, InvertGammaBrightContrast) {
    {
        OneNode p;
        p.node.type = node_type("invert");
        p.node.inputs[0] = p.value({0.25f});
        p.node.inputs[1] = p.value({0.2f, 1.0f, 2.0f});
        p.node.outputs[0] = p.output(3);
        // 0.25 (1 - c) + 0.75 c = 0.25 + 0.5 c
        expect_near3(p.run(p.node.outputs[0], 3), {0.35, 0.75, 1.25});
    }
    for (const float gamma : {2.2f, 0.0f}) {
        OneNode p;
        p.node.type = node_type("gamma");
        p.node.inputs[0] = p.value({0.5f, -0.5f, 0.0f});
        p.node.inputs[1] = p.value({gamma});
        p.node.outputs[0] = p.output(3);
        if (gamma == 0.0f)
            expect_near3(p.run(p.node.outputs[0], 3), {1.0, 1.0, 1.0});
        else
            expect_near3(p.run(p.node.outputs[0], 3), {std::pow(0.5, 2.2), -0.5, 0.0});
    }
    {
        OneNode p;
        p.node.type = node_type("bright_contrast");
        p.node.inputs[0] = p.value({0.5f, 0.1f, 0.9f});
        p.node.inputs[1] = p.value({0.1f});
        p.node.inputs[2] = p.value({1.0f});
        p.node.outputs[0] = p.output(3);
        // 2 c + 0.1 - 0.5, at least 0
        expect_near3(p.run(p.node.outputs[0], 3), {0.6, 0.0, 1.4});
    }
}

std::vector<float> hsv(float hue, float sat, float val, float fac, std::array<float, 3> c, int wrap) {
    OneNode p;
    p.node.type = node_type("hsv");
    p.node.modes[0] = wrap;
    p.node.inputs[0] = p.value({hue});
    p.node.inputs[1] = p.value({sat});
    p.node.inputs[2] = p.value({val});
    p.node.inputs[3] = p.value({fac});
    p.node.inputs[4] = p.value({c[0], c[1], c[2]});
    p.node.outputs[0] = p.output(3);
    return p.run(p.node.outputs[0], 3);
}

TEST(ColorNodes, HueSaturationValue) {
    const std::array<float, 3> c{0.8f, 0.4f, 0.2f};
    // Neutral settings give the colour back.
    expect_near3(hsv(0.5f, 1.0f, 1.0f, 1.0f, c, 0), {0.8, 0.4, 0.2}, 1e-6);
    // Hue + 0.5 turns 20 degrees to 200: sector 3 (f = 1/3), s 0.75, v 0.8:
    // (p, q, v) = (0.2, 0.8 (1 - 0.75 / 3), 0.8).
    expect_near3(hsv(1.0f, 1.0f, 1.0f, 1.0f, c, 0), {0.2, 0.6, 0.8}, 1e-5);
    // Saturation x2 is limited to 1, value x0.5: (v, v (1 - s (1 - f)), v (1 - s)) with f = 1/3.
    expect_near3(hsv(0.5f, 2.0f, 0.5f, 1.0f, c, 0), {0.4, 0.4 / 3.0, 0.0}, 1e-5);
    // Half the factor: halfway to that from the input.
    expect_near3(hsv(0.5f, 2.0f, 0.5f, 0.5f, c, 0), {0.6, 0.2 + 0.2 / 3.0, 0.1}, 1e-5);
    // Hue -1: the sum 1/18 - 0.5 = -4/9. fract gives 5/9 (200 degrees), sector 3 with f = 1/3
    // again; 3.4's fmod leaves -4/9, whose sector floor(-8/3) = -3 is not 0..4: (v, p, q).
    expect_near3(hsv(-1.0f, 1.0f, 1.0f, 1.0f, c, 0), {0.2, 0.6, 0.8}, 1e-5);
    expect_near3(hsv(-1.0f, 1.0f, 1.0f, 1.0f, c, 1),
                 {0.8, 0.2, 0.8 * (1 - 0.75 * (-8.0 / 3.0 - std::floor(-8.0 / 3.0)))}, 1e-5);
}

TEST(ColorNodes, RgbToBwHasTheLuminanceWeightsOfEachColourConfiguration) {
    // Mode 0: Blender 3.x, 1: 4.0-4.5, 2: 5.0 and later; the weights Cycles 3.4, 4.2/4.5 and 5.0
    // render for unit red, green and blue, exactly (node_registry.h).
    const float weights[3][3] = {{0.212672979f, 0.715152621f, 0.0721754432f},
                                 {0.212674037f, 0.715151608f, 0.0721754208f},
                                 {0.212639123f, 0.715169132f, 0.0721927583f}};
    for (int mode = 0; mode < 3; ++mode) {
        for (int k = 0; k < 3; ++k) {
            OneNode p;
            p.node.type = node_type("rgb_to_bw");
            p.node.modes[0] = mode;
            p.node.inputs[0] = p.value({k == 0 ? 1.0f : 0.0f, k == 1 ? 1.0f : 0.0f, k == 2 ? 1.0f : 0.0f});
            p.node.outputs[0] = p.output(1);
            EXPECT_EQ(p.run(p.node.outputs[0], 1)[0], weights[mode][k]) << mode << " " << k;
        }
    }
    OneNode bad;
    bad.node.type = node_type("rgb_to_bw");
    bad.node.modes[0] = 3;
    bad.node.inputs[0] = bad.value({1.0f, 0.5f, 0.25f});
    bad.node.outputs[0] = bad.output(1);
    SceneHandle h;
    uint32_t id = 0;
    EXPECT_NE(bad.add(h, &id), STRATUM_OK);
    EXPECT_NE(std::string(stratum_last_error()).find("luminance weights"), std::string::npos)
        << stratum_last_error();
}

// ---- Separate / Combine ------------------------------------------------------------------------

std::vector<float> convert(int type, int model, std::array<float, 3> v) {
    OneNode p;
    p.node.type = type;
    p.node.modes[0] = model;
    if (type == node_type("separate_color")) {
        p.node.inputs[0] = p.value({v[0], v[1], v[2]});
    } else {
        // Scattered input registers: Combine reads three floats.
        p.node.inputs[2] = p.value({v[2]});
        p.node.inputs[0] = p.value({v[0]});
        p.node.inputs[1] = p.value({v[1]});
    }
    p.node.outputs[0] = p.output(3);
    return p.run(p.node.outputs[0], 3);
}

TEST(ColorNodes, SeparateAndCombine) {
    const int sep = node_type("separate_color"), comb = node_type("combine_color");
    expect_near3(convert(sep, 0, {0.8f, 0.4f, 0.2f}), {0.8, 0.4, 0.2});
    expect_near3(convert(sep, 1, {0.8f, 0.4f, 0.2f}), {1.0 / 18.0, 0.75, 0.8});
    expect_near3(convert(sep, 2, {0.8f, 0.4f, 0.2f}), {1.0 / 18.0, 0.6, 0.5});
    // A hue in the blue sector, and HSL above lightness 0.5: (0.5, 0.5, 1) is hue 2/3,
    // l = 0.75, s = 0.5 / (2 - 1.5) = 1.
    expect_near3(convert(sep, 1, {0.5f, 0.5f, 1.0f}), {2.0 / 3.0, 0.5, 1.0});
    expect_near3(convert(sep, 2, {0.5f, 0.5f, 1.0f}), {2.0 / 3.0, 1.0, 0.75});
    // Grey: hue and saturation 0.
    expect_near3(convert(sep, 1, {0.3f, 0.3f, 0.3f}), {0.0, 0.0, 0.3});
    expect_near3(convert(sep, 2, {0.3f, 0.3f, 0.3f}), {0.0, 0.0, 0.3});
    expect_near3(convert(comb, 0, {0.1f, 0.2f, 0.3f}), {0.1, 0.2, 0.3});
    expect_near3(convert(comb, 1, {1.0f / 18.0f, 0.75f, 0.8f}), {0.8, 0.4, 0.2}, 1e-5);
    expect_near3(convert(comb, 2, {1.0f / 18.0f, 0.6f, 0.5f}), {0.8, 0.4, 0.2}, 1e-5);
    expect_near3(convert(comb, 2, {2.0f / 3.0f, 1.0f, 0.75f}), {0.5, 0.5, 1.0}, 1e-5);
    // HSV hue 1 is hue 0 (red).
    expect_near3(convert(comb, 1, {1.0f, 1.0f, 0.5f}), {0.5, 0.0, 0.0});
}

// ---- Color Ramp and curves ---------------------------------------------------------------------

std::vector<float> ramp(float fac, int interpolate) {
    OneNode p;
    p.node.type = node_type("color_ramp");
    p.node.modes[0] = interpolate;
    p.data = {0, 0, 0, 1, 1, 0.5f, 0, 0.5f, 0, 1, 1, 0};  // 3 entries (r, g, b, a)
    // The factor comes from an input register: a constant cannot be NaN.
    p.node.inputs[0] = STRATUM_INPUT_RAY_LENGTH;
    p.inputs[STRATUM_INPUT_RAY_LENGTH] = fac;
    p.node.outputs[0] = p.output(3);
    p.node.outputs[1] = p.output(1);
    return p.run(p.node.outputs[0], 4);
}

TEST(ColorNodes, ColorRampLookup) {
    // fac 0.25 is position 0.5 of the table: halfway between entries 0 and 1.
    auto v = ramp(0.25f, 1);
    EXPECT_NEAR(v[0], 0.5, 1e-6);
    EXPECT_NEAR(v[1], 0.25, 1e-6);
    EXPECT_NEAR(v[2], 0.0, 1e-6);
    EXPECT_NEAR(v[3], 0.75, 1e-6);
    // Constant: entry floor(0.9 * 2) = 1.
    v = ramp(0.9f, 0);
    EXPECT_NEAR(v[0], 1.0, 1e-6);
    EXPECT_NEAR(v[3], 0.5, 1e-6);
    // fac 0.9 interpolated: 0.8 of the way from entry 1 to entry 2.
    v = ramp(0.9f, 1);
    EXPECT_NEAR(v[0], 0.2, 1e-5);
    EXPECT_NEAR(v[1], 0.9, 1e-5);
    EXPECT_NEAR(v[2], 0.8, 1e-5);
    EXPECT_NEAR(v[3], 0.1, 1e-5);
    // Outside [0, 1] and NaN: clamped (NaN to the first entry).
    EXPECT_NEAR(ramp(-3.0f, 1)[3], 1.0, 1e-6);
    EXPECT_NEAR(ramp(7.0f, 1)[1], 1.0, 1e-6);
    EXPECT_NEAR(ramp(std::nanf(""), 1)[3], 1.0, 1e-6);
}

// An RGB curve table on x in [min_x, max_x] = [-1, 1] of 3 entries: r = x^2 sampled (1, 0, 1),
// g = 2x (-2, 0, 2), b = 0.5 constant.
std::vector<float> curves(int kind, int extrapolate, float fac, std::array<float, 3> v) {
    OneNode p;
    p.node.type = node_type("curves");
    p.node.modes[0] = kind;
    p.node.modes[1] = extrapolate;
    if (kind == 2)
        p.data = {-1.0f, 1.0f, 1.0f, 0.0f, 1.0f};
    else
        p.data = {-1.0f, 1.0f, 1.0f, -2.0f, 0.5f, 0.0f, 0.0f, 0.5f, 1.0f, 2.0f, 0.5f};
    p.node.inputs[0] = p.value({fac});
    p.node.inputs[1] = kind == 2 ? p.value({v[0]}) : p.value({v[0], v[1], v[2]});
    p.node.outputs[0] = p.output(kind == 2 ? 1 : 3);
    return p.run(p.node.outputs[0], kind == 2 ? 1 : 3);
}

TEST(ColorNodes, CurvesLookupAndExtrapolation) {
    for (const int kind : {0, 1}) {
        SCOPED_TRACE(kind);
        // x = 0.5 is position 1.5: halfway between entries 1 and 2.
        expect_near3(curves(kind, 1, 1.0f, {0.5f, 0.5f, 0.5f}), {0.5, 1.0, 0.5});
        // x = 2 is f = 1.5: extrapolated from the last two entries, slope per entry (1, 2, 0).
        expect_near3(curves(kind, 1, 1.0f, {2.0f, 2.0f, 2.0f}), {2.0, 4.0, 0.5});
        // x = -2 likewise from the first two.
        expect_near3(curves(kind, 1, 1.0f, {-2.0f, -2.0f, -2.0f}), {2.0, -4.0, 0.5});
        // Without extrapolation the ends hold.
        expect_near3(curves(kind, 0, 1.0f, {2.0f, -2.0f, 2.0f}), {1.0, -2.0, 0.5});
        // Fac 0.25 blends with the input.
        expect_near3(curves(kind, 1, 0.25f, {0.5f, 0.5f, 0.5f}), {0.5, 0.625, 0.5});
    }
    EXPECT_NEAR(curves(2, 1, 1.0f, {0.5f})[0], 0.5, 1e-6);
    EXPECT_NEAR(curves(2, 1, 1.0f, {3.0f})[0], 3.0, 1e-6);
    EXPECT_NEAR(curves(2, 0, 1.0f, {3.0f})[0], 1.0, 1e-6);
    EXPECT_NEAR(curves(2, 1, 0.5f, {-0.5f})[0], 0.0, 1e-6);
}

// ---- Checks ------------------------------------------------------------------------------------

TEST(ColorNodes, BadModesAndDataAreRejectedByName) {
    {
        OneNode p;
        p.node.type = node_type("mix");
        p.node.modes[0] = kColor;
        p.node.modes[1] = 19;
        p.node.outputs[0] = p.output(3);
        EXPECT_NE(p.rejected().find("(mix): mode 1 (blend) is 19"), std::string::npos);
    }
    {
        // A colour mix whose result register is the last one (not 3 wide).
        OneNode p;
        p.node.type = node_type("mix");
        p.node.modes[0] = kColor;
        p.node.inputs[1] = p.node.inputs[2] = p.value({0, 0, 0});
        p.node.outputs[0] = p.output(1);
        EXPECT_NE(p.rejected().find("output 0 (result) register is not 3 wide"), std::string::npos);
    }
    {
        OneNode p;
        p.node.type = node_type("hsv");
        p.node.modes[0] = 2;
        p.node.inputs[4] = p.value({0, 0, 0});
        p.node.outputs[0] = p.output(3);
        EXPECT_NE(p.rejected().find("(hsv): mode 0 (hue wrap) is 2"), std::string::npos);
    }
    {
        OneNode p;
        p.node.type = node_type("separate_color");
        p.node.modes[0] = -1;
        p.node.inputs[0] = p.value({0, 0, 0});
        p.node.outputs[0] = p.output(3);
        EXPECT_NE(p.rejected().find("(separate_color): mode 0 (model) is -1"), std::string::npos);
    }
    {
        OneNode p;
        p.node.type = node_type("color_ramp");
        p.data = {1, 2, 3};
        p.node.outputs[0] = p.output(3);
        p.node.outputs[1] = p.output(1);
        EXPECT_NE(p.rejected().find("(color_ramp): data count 3"), std::string::npos);
    }
    {
        OneNode p;
        p.node.type = node_type("curves");
        p.node.modes[0] = 0;
        p.data = {0, 1, 0, 0, 0};  // one entry: extrapolation needs two
        p.node.inputs[1] = p.value({0, 0, 0});
        p.node.outputs[0] = p.output(3);
        EXPECT_NE(p.rejected().find("(curves): data count 5"), std::string::npos);
    }
    {
        OneNode p;
        p.node.type = node_type("curves");
        p.node.modes[0] = 3;
        p.node.outputs[0] = p.output(1);
        EXPECT_NE(p.rejected().find("(curves): mode 0 (kind) is 3"), std::string::npos);
    }
}

}  // namespace
