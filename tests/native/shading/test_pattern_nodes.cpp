// Pattern textures (Checker, Gradient, Brick, Magic) and the Image node in programs
// (shading/nodes/*_texture.cpp, image_node.cpp): every mode against values worked out here
// independently (by hand, or the formula re-derived from Cycles' svm/*.h in double precision),
// and the checks that reject bad modes and data.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "node_types.h"
#include "scene_handle.h"

namespace {

using stratum_test::node_type;

using stratum_test::SceneHandle;

constexpr uint32_t kIn = STRATUM_SHADER_INPUT_REGISTERS;

// One node whose inputs are constants: input k is given `values[k]` (1 or 3 floats) and gets
// registers in order after the renderer's; outputs follow.
struct OneNode {
    SceneHandle handle;
    std::vector<float> registers = std::vector<float>(kIn, 0.0f);
    StratumShaderNode node{};
    std::vector<float> data;
    uint32_t output_first = 0;

    OneNode(int32_t type, std::vector<int32_t> modes, const std::vector<std::vector<float>>& values,
            std::vector<uint32_t> output_widths, std::vector<float> data_ = {})
        : data(std::move(data_)) {
        node.type = type;
        for (size_t k = 0; k < modes.size(); ++k) node.modes[k] = modes[k];
        for (size_t k = 0; k < values.size(); ++k) {
            node.inputs[k] = static_cast<uint32_t>(registers.size());
            registers.insert(registers.end(), values[k].begin(), values[k].end());
        }
        output_first = static_cast<uint32_t>(registers.size());
        for (size_t k = 0; k < output_widths.size(); ++k) {
            node.outputs[k] = static_cast<uint32_t>(registers.size());
            registers.insert(registers.end(), output_widths[k], 0.0f);
        }
        node.data_offset = 0;
        node.data_count = static_cast<uint32_t>(data.size());
    }

    StratumShaderProgramDesc desc() const {
        return {&node,
                1,
                registers.data(),
                static_cast<uint32_t>(registers.size()),
                data.empty() ? nullptr : data.data(),
                static_cast<uint32_t>(data.size())};
    }

    // The outputs' registers after one evaluation.
    std::vector<float> run(const std::vector<float>& inputs = std::vector<float>(kIn, 0.0f)) {
        uint32_t id = 0;
        const StratumShaderProgramDesc d = desc();
        EXPECT_EQ(stratum_scene_add_shader_program(handle.scene, &d, &id), STRATUM_OK)
            << stratum_last_error();
        std::vector<float> out(registers.size() - output_first);
        EXPECT_EQ(stratum_scene_evaluate_program(handle.scene, id, inputs.data(), output_first,
                                                 static_cast<uint32_t>(out.size()), out.data()),
                  STRATUM_OK);
        return out;
    }

    // The error adding the program gives ("" if it is accepted).
    std::string error() {
        uint32_t id = 0;
        const StratumShaderProgramDesc d = desc();
        if (stratum_scene_add_shader_program(handle.scene, &d, &id) == STRATUM_OK) return "";
        return stratum_last_error();
    }
};

std::vector<float> v3(double x, double y, double z) {
    return {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z)};
}
std::vector<float> v1(double x) { return {static_cast<float>(x)}; }

// ---- Checker --------------------------------------------------------------------------------

std::vector<float> checker(std::vector<float> p, float scale) {
    OneNode n(node_type("checker"), {}, {p, v3(0.8, 0.7, 0.6), v3(0.1, 0.2, 0.3), v1(scale)}, {3, 1});
    return n.run();
}

TEST(PatternNodes, CheckerCellsByHand) {
    // Cell (0,0,0): x, y same parity (1) against z even (0): fac 0, colour 2.
    EXPECT_EQ(checker(v3(0.5, 0.5, 0.5), 1.0f), (std::vector<float>{0.1f, 0.2f, 0.3f, 0.0f}));
    // Cell (1,0,0): x, y differ (0) == z even (0): fac 1, colour 1.
    EXPECT_EQ(checker(v3(1.5, 0.5, 0.5), 1.0f), (std::vector<float>{0.8f, 0.7f, 0.6f, 1.0f}));
    // Negative coordinates: floor(-0.5) = -1, odd by its absolute value.
    EXPECT_EQ(checker(v3(-0.5, 0.5, 0.5), 1.0f)[3], 1.0f);
    EXPECT_EQ(checker(v3(-0.5, -0.5, 0.5), 1.0f)[3], 0.0f);
    // Scale multiplies first: 0.3 x 5 = 1.5 in cell (1,1,1): same parity (1) == z odd (1).
    EXPECT_EQ(checker(v3(0.3, 0.3, 0.3), 5.0f)[3], 1.0f);
    EXPECT_EQ(checker(v3(0.3, 0.3, 0.1), 5.0f)[3], 0.0f);
    // Just below a cell edge stays in the lower cell only when the nudge does not lift it over:
    // (0.9999 + 1e-6) x 0.999999 < 1.
    EXPECT_EQ(checker(v3(0.9999, 0.5, 0.5), 1.0f)[3], 0.0f);
}

// Non-finite values reach a node only through the renderer's inputs (constants are finite).
std::vector<float> geometry_input(float x, float y, float z) {
    std::vector<float> inputs(kIn, 0.0f);
    inputs[STRATUM_INPUT_GENERATED] = x;
    inputs[STRATUM_INPUT_GENERATED + 1] = y;
    inputs[STRATUM_INPUT_GENERATED + 2] = z;
    return inputs;
}

TEST(PatternNodes, CheckerNeverFailsOnBadValues) {
    const float nan = std::nanf(""), inf = INFINITY;
    OneNode n(node_type("checker"), {}, {v3(0, 0, 0), v3(0.8, 0.7, 0.6), v3(0.1, 0.2, 0.3), v1(1.0)}, {3, 1});
    n.node.inputs[0] = STRATUM_INPUT_GENERATED;
    // NaN and huge coordinates read as INT_MIN: even, like 0: cell (0, 0, 0) gives fac 0.
    EXPECT_EQ(n.run(geometry_input(nan, 1e30f, -inf))[3], 0.0f);
    EXPECT_EQ(n.run(geometry_input(1.5f, nan, 0.5f))[3], 1.0f);
}

// ---- Gradient -------------------------------------------------------------------------------

double gradient_reference(int type, double x, double y, double z) {
    const double pi = 3.14159265358979323846;
    double f = 0.0;
    const double len = std::sqrt(x * x + y * y + z * z);
    const double r = std::max(0.999999 - len, 0.0);
    switch (type) {
        case 0:
            f = x;
            break;
        case 1:
            f = x > 0 ? x * x : 0.0;
            break;
        case 2: {
            const double t = std::min(std::max(x, 0.0), 1.0);
            f = t * t * (3.0 - 2.0 * t);
            break;
        }
        case 3:
            f = 0.5 * (x + y);
            break;
        case 4:
            f = 0.5 + std::atan2(y, x) / (2.0 * pi);
            break;
        case 5:
            f = r * r;
            break;
        default:
            f = r;
            break;
    }
    return std::min(std::max(f, 0.0), 1.0);
}

TEST(PatternNodes, GradientEveryType) {
    // By hand at (0.25, 0.5, 0.1): linear 0.25, quadratic 0.0625, easing 0.15625, diagonal 0.375.
    const std::array<float, 4> by_hand = {0.25f, 0.0625f, 0.15625f, 0.375f};
    for (int type = 0; type < 4; ++type) {
        OneNode n(node_type("gradient"), {type}, {v3(0.25, 0.5, 0.1)}, {3, 1});
        const std::vector<float> out = n.run();
        EXPECT_FLOAT_EQ(out[3], by_hand[type]) << type;
        EXPECT_EQ(out[0], out[3]);
        EXPECT_EQ(out[2], out[3]);
    }
    const std::vector<std::array<double, 3>> points = {{0.25, 0.5, 0.1},   {-0.3, 0.2, 0.4},
                                                       {1.7, -0.6, 0.0},   {-2.0, -1.0, 0.5},
                                                       {0.1, -0.05, -0.2}, {0.6, 0.8, 0.0}};
    for (int type = 0; type < 7; ++type) {
        for (const auto& p : points) {
            OneNode n(node_type("gradient"), {type}, {v3(p[0], p[1], p[2])}, {3, 1});
            EXPECT_NEAR(n.run()[3], gradient_reference(type, p[0], p[1], p[2]), 2e-6)
                << "type " << type << " at " << p[0] << ", " << p[1] << ", " << p[2];
        }
    }
    // A unit vector is exactly 0 for the spherical types (the 0.999999 bias).
    OneNode n(node_type("gradient"), {6}, {v3(0.6, 0.8, 0.0)}, {3, 1});
    EXPECT_EQ(n.run()[3], 0.0f);
}

// ---- Magic ----------------------------------------------------------------------------------

// Cycles' svm_magic re-derived as a table: after the first level, level k replaces component
// target[k] by sign[k] * f[k](a x + b y + c z) * d. In float, as the node: at depth 10 with
// distortion 3 each level triples the rounding errors of the last, so a double reference would
// part from any float evaluation by more than the rounding of one step.
std::array<float, 3> magic_reference(float px, float py, float pz, float scale, int depth, float d) {
    const float two_pi = 6.283185307f;
    px = std::fmod(px, two_pi), py = std::fmod(py, two_pi), pz = std::fmod(pz, two_pi);
    std::array<float, 3> v = {std::sin((px + py + pz) * 5.0f * scale),
                              std::cos((-px + py - pz) * 5.0f * scale),
                              -std::cos((-px - py + pz) * 5.0f * scale)};
    struct Step {
        int target;
        float sign;
        bool use_sin;
        float a, b, c;
    };
    const std::array<Step, 10> steps = {{{1, -1, false, 1, -1, 1},
                                         {0, 1, false, 1, -1, -1},
                                         {2, 1, true, -1, -1, -1},
                                         {0, -1, false, -1, 1, -1},
                                         {1, -1, true, -1, 1, 1},
                                         {1, -1, false, -1, 1, 1},
                                         {0, 1, false, 1, 1, 1},
                                         {2, 1, true, 1, 1, -1},
                                         {0, -1, false, -1, -1, 1},
                                         {1, -1, true, 1, -1, 1}}};
    if (depth > 0)
        for (float& c : v) c *= d;
    for (int k = 0; k < depth; ++k) {
        const Step& s = steps[k];
        const float arg = s.a * v[0] + s.b * v[1] + s.c * v[2];
        v[s.target] = s.sign * (s.use_sin ? std::sin(arg) : std::cos(arg)) * d;
    }
    if (d != 0.0f)
        for (float& c : v) c /= 2.0f * d;
    return {0.5f - v[0], 0.5f - v[1], 0.5f - v[2]};
}

TEST(PatternNodes, MagicByHandAtDepthZero) {
    // sin(3), cos(-1), -cos(0) halved: (0.5 - 0.0705600, 0.5 - 0.2701512, 1).
    OneNode n(node_type("magic"), {0}, {v3(0.1, 0.2, 0.3), v1(1.0), v1(1.0)}, {3, 1});
    const std::vector<float> out = n.run();
    EXPECT_NEAR(out[0], 0.4294400, 1e-6);
    EXPECT_NEAR(out[1], 0.2298488, 1e-6);
    EXPECT_NEAR(out[2], 1.0, 1e-6);
    EXPECT_NEAR(out[3], (0.4294400 + 0.2298488 + 1.0) / 3.0, 1e-6);
}

TEST(PatternNodes, MagicEveryDepth) {
    const std::vector<std::array<float, 5>> cases = {{0.1f, 0.2f, 0.3f, 5.0f, 1.0f},
                                                     {0.7f, -0.4f, 0.25f, 5.0f, 2.0f},
                                                     {-0.3f, 0.9f, 0.6f, 2.5f, 0.5f},
                                                     {20.0f, 3.0f, -7.0f, 1.0f, 3.0f}};
    for (int depth = 0; depth <= 10; ++depth) {
        for (const auto& c : cases) {
            OneNode n(node_type("magic"), {depth}, {v3(c[0], c[1], c[2]), v1(c[3]), v1(c[4])}, {3, 1});
            const std::vector<float> out = n.run();
            const auto want = magic_reference(c[0], c[1], c[2], c[3], depth, c[4]);
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(out[k], want[k], 1e-5f * std::max(1.0f, std::fabs(want[k])))
                    << "depth " << depth << " component " << k;
            EXPECT_NEAR(out[3], (want[0] + want[1] + want[2]) / 3.0f, 1e-5f);
        }
    }
    // No distortion: the colour is not divided (1/2 - (x, y, z) with x, y, z scaled to 0 past depth 0).
    OneNode n(node_type("magic"), {2}, {v3(0.1, 0.2, 0.3), v1(5.0), v1(0.0)}, {3, 1});
    const std::vector<float> out = n.run();
    EXPECT_FLOAT_EQ(out[0], 0.5f - static_cast<float>(std::cos(0.0) * 0.0));
    EXPECT_FLOAT_EQ(out[1], 0.5f);
}

// ---- Brick ----------------------------------------------------------------------------------

// Cycles' brick noise, re-derived in 64-bit arithmetic reduced modulo 2^32 where Cycles' uint
// wraps.
double brick_noise_reference(int64_t key) {
    uint64_t n = (static_cast<uint64_t>(key) + 1013) & 0x7fffffffULL;
    n = (n >> 13) ^ n;
    const uint64_t inner = (n * n % (1ULL << 32)) * 60493 % (1ULL << 32);
    const uint64_t nn =
        ((n * ((inner + 19990303) % (1ULL << 32))) % (1ULL << 32) + 1376312589) & 0x7fffffffULL;
    return 0.5 * static_cast<double>(nn) / 1073741824.0;
}

struct BrickCase {
    std::array<double, 3> co;
    double scale, mortar_size, mortar_smooth, bias, width, row_height;
    double offset_amount, squash_amount;
    int offset_frequency, squash_frequency;
};

const std::vector<float> kColor1 = {0.8f, 0.2f, 0.1f}, kColor2 = {0.2f, 0.6f, 0.9f},
                         kMortar = {0.05f, 0.1f, 0.15f};

std::vector<float> brick(const BrickCase& b, int smoothing) {
    OneNode n(node_type("brick"), {b.offset_frequency, b.squash_frequency, smoothing},
              {v3(b.co[0], b.co[1], b.co[2]), kColor1, kColor2, kMortar, v1(b.scale), v1(b.mortar_size),
               v1(b.mortar_smooth), v1(b.bias), v1(b.width), v1(b.row_height)},
              {3, 1}, {static_cast<float>(b.offset_amount), static_cast<float>(b.squash_amount)});
    return n.run();
}

void expect_brick_colour(const std::vector<float>& out, double tint, double fac) {
    for (int k = 0; k < 3; ++k) {
        const double c1 = fac == 1.0 ? kColor1[k] : (1.0 - tint) * kColor1[k] + tint * kColor2[k];
        EXPECT_NEAR(out[k], c1 * (1.0 - fac) + kMortar[k] * fac, 1e-6) << k;
    }
    EXPECT_NEAR(out[3], fac, 1e-6);
}

TEST(PatternNodes, BrickInsideABrickByHand) {
    // Blender's defaults; p = (0.65, 0.35): row 1 (odd: no offset or squash), brick 1,
    // x = 0.15, y = 0.1, nearest edge 0.1 >= mortar size: no mortar; tint of key 1 << 16 | 1.
    const BrickCase b{{0.13, 0.07, 0.0}, 5.0, 0.02, 0.1, 0.0, 0.5, 0.25, 0.5, 1.0, 2, 2};
    const double tint = brick_noise_reference((1 << 16) + 1);
    ASSERT_GT(tint, 0.0);
    ASSERT_LT(tint, 1.0);
    expect_brick_colour(brick(b, 1), tint, 0.0);
    // Bias pushes the tint to 1 (saturated): colour 2.
    BrickCase biased = b;
    biased.bias = 1.0;
    expect_brick_colour(brick(biased, 1), 1.0, 0.0);
}

TEST(PatternNodes, BrickOffsetAndSquashOnEvenRows) {
    // Row 0 (even): width 0.5 x squash 2 = 1, offset 1 x 0.5; p = (0.3, 0.1): brick floor(0.8) = 0,
    // x = 0.8, y = 0.1: nearest edge min(0.8, 0.1, 0.2, 0.15) = 0.1.
    const BrickCase b{{0.06, 0.02, 0.0}, 5.0, 0.02, 0.1, 0.0, 0.5, 0.25, 0.5, 2.0, 2, 2};
    expect_brick_colour(brick(b, 1), brick_noise_reference(0), 0.0);
    // p = (0.9, 0.1): 0.9 + 0.5 = 1.4 is brick 1 of row 0.
    BrickCase next = b;
    next.co = {0.18, 0.02, 0.0};
    expect_brick_colour(brick(next, 1), brick_noise_reference(1), 0.0);
    // Row -1 (odd: -1 % 2 = -1): the key's row part wraps as an unsigned shift.
    BrickCase below = b;
    below.co = {0.02, -0.02, 0.0};  // p = (0.1, -0.1): row -1, brick 0
    expect_brick_colour(brick(below, 1), brick_noise_reference(static_cast<int64_t>(0xFFFF0000u)), 0.0);
    // A zero frequency turns both off: row 0 unshifted, brick floor(0.3 / 0.5) = 0.
    BrickCase off = b;
    off.offset_frequency = 0;
    expect_brick_colour(brick(off, 1), brick_noise_reference(0), 0.0);
}

TEST(PatternNodes, BrickMortarBothGenerations) {
    // p = (0.65, 0.251): y = 0.001 from the row's edge: 1 - 0.001 / 0.02 = 0.95.
    BrickCase b{{0.13, 0.0502, 0.0}, 5.0, 0.02, 1.0, 0.0, 0.5, 0.25, 0.5, 1.0, 2, 2};
    const double t = 1.0 - (0.0502f * 5.0f - 0.25) / 0.02;  // from p.y as the node computes it
    const double smooth = t * t * (3.0 - 2.0 * t);
    for (int generation = 0; generation < 2; ++generation) {
        const std::vector<float> out = brick(b, generation);
        EXPECT_NEAR(out[3], smooth, 2e-4) << generation;
    }
    // Smoothing 0: mortar is 1 inside the mortar size.
    b.mortar_smooth = 0.0;
    EXPECT_EQ(brick(b, 0)[3], 1.0f);
    EXPECT_EQ(brick(b, 1)[3], 1.0f);
    // A smoothing smaller than 0.95: 3.4 gives 1 (outside its band), 3.5 smoothstep(9.5) = 1.
    b.mortar_smooth = 0.1;
    EXPECT_EQ(brick(b, 0)[3], 1.0f);
    EXPECT_EQ(brick(b, 1)[3], 1.0f);
    // Negative smoothing: 3.4 gives 1 (0.95 >= -0.5), 3.5 smoothstep(-1.9) clamped to 0.
    b.mortar_smooth = -0.5;
    EXPECT_EQ(brick(b, 0)[3], 1.0f);
    EXPECT_EQ(brick(b, 1)[3], 0.0f);
}

TEST(PatternNodes, BrickNeverFailsOnBadValues) {
    const BrickCase zero_rows{{0.13, 0.07, 0.0}, 5.0, 0.02, 0.1, 0.0, 0.0, 0.0, 0.5, 1.0, 2, 2};
    const std::vector<float> out = brick(zero_rows, 1);
    EXPECT_EQ(out.size(), 4u);
    const BrickCase huge{{1e30, -1e30, 0.0}, 1e10, 0.02, 0.1, 0.0, 0.5, 0.25, 0.5, 1.0, 7, 3};
    EXPECT_EQ(brick(huge, 0).size(), 4u);
    // NaN coordinates (from the renderer's inputs): row and brick INT_MIN, no crash, and the
    // mortar NaN as Cycles' (the distance comparisons fail, the smoothstep of NaN is NaN).
    OneNode n(node_type("brick"), {2, 2, 1},
              {v3(0, 0, 0), kColor1, kColor2, kMortar, v1(1), v1(0.02), v1(0.1), v1(0), v1(0.5), v1(0.25)},
              {3, 1}, {0.5f, 1.0f});
    n.node.inputs[0] = STRATUM_INPUT_GENERATED;
    EXPECT_TRUE(std::isnan(n.run(geometry_input(std::nanf(""), std::nanf(""), 0.0f))[3]));
}

// ---- Image ----------------------------------------------------------------------------------

// A 2 x 1 RGBA texture: left texel (0.8, 0.4, 0.2, a0), right (0.2, 0.6, 1.0, a1).
uint32_t add_texture(StratumScene* scene, const char* space, int32_t interpolation, float a0, float a1) {
    const std::vector<float> px = {0.8f, 0.4f, 0.2f, a0, 0.2f, 0.6f, 1.0f, a1};
    StratumTextureDesc t{};
    t.pixels = px.data();
    t.width = 2;
    t.height = 1;
    t.channels = 4;
    t.color_space = space;
    t.interpolation = interpolation;
    t.extension = STRATUM_TEXTURE_EXTEND;
    uint32_t id = 0;
    EXPECT_EQ(stratum_scene_add_texture(scene, &t, &id), STRATUM_OK) << stratum_last_error();
    return id;
}

std::vector<float> image(int32_t interpolation, const char* space, int alpha_mode, double u, float a0 = 0.5f,
                         float a1 = 0.25f) {
    OneNode n(node_type("image"), {0, alpha_mode}, {v3(u, 0.5, 0.7)}, {3, 1});
    EXPECT_EQ(add_texture(n.handle.scene, space, interpolation, a0, a1), 0u);
    return n.run();
}

double srgb_decode(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

TEST(PatternNodes, ImageAlphaModesClosest) {
    // Left texel, alpha 0.5: straight, associated (x 0.5) and associated-then-divided.
    const std::vector<float> straight = image(STRATUM_TEXTURE_CLOSEST, "Non-Color", 0, 0.25);
    const std::vector<float> assoc = image(STRATUM_TEXTURE_CLOSEST, "Non-Color", 1, 0.25);
    const std::vector<float> unassoc = image(STRATUM_TEXTURE_CLOSEST, "Non-Color", 2, 0.25);
    const std::array<float, 3> c = {0.8f, 0.4f, 0.2f};
    for (int k = 0; k < 3; ++k) {
        EXPECT_FLOAT_EQ(straight[k], c[k]);
        EXPECT_FLOAT_EQ(assoc[k], c[k] * 0.5f);
        EXPECT_FLOAT_EQ(unassoc[k], c[k]);
    }
    EXPECT_FLOAT_EQ(straight[3], 0.5f);
    EXPECT_FLOAT_EQ(assoc[3], 0.5f);
    EXPECT_FLOAT_EQ(unassoc[3], 0.5f);
    // Alpha 0 is not divided by: the associated colour (0) stays.
    const std::vector<float> clear = image(STRATUM_TEXTURE_CLOSEST, "Non-Color", 2, 0.25, 0.0f, 1.0f);
    EXPECT_EQ(clear[0], 0.0f);
}

TEST(PatternNodes, ImageAlphaModesLinear) {
    // u = 0.5 lies halfway between the texel centres 0.25 and 0.75.
    const double a = 0.5 * (0.5 + 0.25);
    const std::array<double, 3> left = {0.8, 0.4, 0.2}, right = {0.2, 0.6, 1.0};
    const std::vector<float> straight = image(STRATUM_TEXTURE_LINEAR, "Non-Color", 0, 0.5);
    const std::vector<float> assoc = image(STRATUM_TEXTURE_LINEAR, "Non-Color", 1, 0.5);
    const std::vector<float> unassoc = image(STRATUM_TEXTURE_LINEAR, "Non-Color", 2, 0.5);
    for (int k = 0; k < 3; ++k) {
        const double premul = 0.5 * (left[k] * 0.5 + right[k] * 0.25);
        EXPECT_NEAR(straight[k], 0.5 * (left[k] + right[k]), 1e-6);
        EXPECT_NEAR(assoc[k], premul, 1e-6);
        EXPECT_NEAR(unassoc[k], premul / a, 1e-6);
    }
    EXPECT_NEAR(assoc[3], a, 1e-6);
}

TEST(PatternNodes, ImageSrgbAssociatesBeforeDecoding) {
    // An sRGB texture given as pixels is stored encoded; Cycles multiplies the encoded values.
    const std::vector<float> assoc = image(STRATUM_TEXTURE_CLOSEST, "sRGB", 1, 0.25);
    const std::vector<float> unassoc = image(STRATUM_TEXTURE_CLOSEST, "sRGB", 2, 0.25);
    const std::array<double, 3> c = {0.8, 0.4, 0.2};
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(assoc[k], srgb_decode(c[k] * 0.5), 1e-5) << k;
        EXPECT_NEAR(unassoc[k], srgb_decode(c[k]), 1e-5) << k;
    }
}

// ---- Wave -----------------------------------------------------------------------------------

std::vector<float> wave(std::array<int32_t, 5> modes, std::vector<float> p, float scale, float distortion,
                        float detail, float detail_scale, float roughness, float phase) {
    OneNode n(node_type("wave"), {modes[0], modes[1], modes[2], modes[3], modes[4]},
              {p, v1(scale), v1(distortion), v1(detail), v1(detail_scale), v1(roughness), v1(phase)}, {3, 1});
    return n.run();
}

// Without distortion, from svm/wave.h re-derived in double: the nudged point, the band or ring
// coordinate, the phase and the profile.
double wave_reference(int type, int direction, int profile, std::array<double, 3> p, double phase) {
    const double pi = 3.14159265358979323846;
    for (double& c : p) c = (c + 1e-6) * 0.999999;
    double n;
    if (type == 0) {
        n = direction < 3 ? 20.0 * p[direction] : 10.0 * (p[0] + p[1] + p[2]);
    } else {
        if (direction < 3) p[direction] = 0.0;
        n = 20.0 * std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    }
    n += phase;
    if (profile == 0) return 0.5 - 0.5 * std::cos(n);  // 1/2 + sin(n - pi/2) / 2
    const double t = n / (2.0 * pi);
    if (profile == 1) return t - std::floor(t);
    return 2.0 * std::fabs(t - std::floor(t + 0.5));
}

TEST(PatternNodes, WaveEveryTypeDirectionAndProfile) {
    const std::vector<std::array<double, 3>> points = {
        {0.13, 0.41, 0.07}, {-0.32, 0.18, 0.55}, {0.9, -0.6, 0.2}};
    for (int type = 0; type < 2; ++type)
        for (int direction = 0; direction < 4; ++direction)
            for (int profile = 0; profile < 3; ++profile)
                for (const auto& q : points) {
                    const std::array<int32_t, 5> modes = {type, type == 0 ? direction : 0,
                                                          type == 1 ? direction : 0, profile, 3};
                    const std::vector<float> out =
                        wave(modes, v3(q[0], q[1], q[2]), 1.5f, 0.0f, 2.0f, 1.0f, 0.5f, 0.3f);
                    const double want =
                        wave_reference(type, direction, profile, {q[0] * 1.5, q[1] * 1.5, q[2] * 1.5}, 0.3);
                    // Saw and triangle wrap: compare on the circle.
                    const double d = std::fabs(out[3] - want);
                    EXPECT_LT(profile == 0 ? d : std::min(d, std::fabs(d - 1.0)), 2e-5)
                        << "type " << type << " direction " << direction << " profile " << profile;
                    EXPECT_EQ(out[0], out[3]);
                }
}

TEST(PatternNodes, WaveDistortionNoiseByGeneration) {
    const std::vector<float> p = v3(0.37, 0.21, 0.64);
    const auto fac = [&](int generation, float roughness) {
        return wave({0, 0, 0, 1, generation}, p, 3.0f, 2.0f, 3.5f, 1.3f, roughness, 0.0f)[3];
    };
    const float undistorted = wave({0, 0, 0, 1, 3}, p, 3.0f, 0.0f, 3.5f, 1.3f, 0.5f, 0.0f)[3];
    for (int generation = 0; generation < 4; ++generation) EXPECT_NE(fac(generation, 0.5f), undistorted);
    // 3.x normalises a sum of unsigned noise, 4.x of signed noise: the same field, rounded apart;
    // 4.2's wrapping of the coordinates matters only beyond 100000.
    EXPECT_NEAR(fac(0, 0.5f), fac(1, 0.5f), 1e-5);
    EXPECT_NEAR(fac(2, 0.5f), fac(3, 0.5f), 1e-6);
    // 4.0 clamps the roughness to [0, 1], 4.1 does not: equal at 0.5, not at 1.7.
    EXPECT_EQ(fac(1, 0.5f), fac(2, 0.5f));
    EXPECT_NE(fac(1, 1.7f), fac(2, 1.7f));
    EXPECT_EQ(fac(1, 1.7f), fac(1, 1.0f));
    // The noise is normalised to [0, 1]: a distortion d moves n by at most d.
    for (int generation = 0; generation < 4; ++generation) {
        const std::vector<float> out =
            wave({0, 0, 0, 1, generation}, p, 3.0f, 0.001f, 3.5f, 1.3f, 0.5f, 0.0f);
        const double shift = (out[3] - undistorted) * 2.0 * 3.14159265358979323846;
        EXPECT_LE(std::fabs(shift), 0.001 + 1e-5) << generation;
    }
}

// ---- checks ---------------------------------------------------------------------------------

TEST(PatternNodes, ChecksNameNodeAndField) {
    {
        OneNode n(node_type("gradient"), {7}, {v3(0, 0, 0)}, {3, 1});
        const std::string e = n.error();
        EXPECT_NE(e.find("gradient"), std::string::npos) << e;
        EXPECT_NE(e.find("type"), std::string::npos) << e;
    }
    const std::vector<std::pair<std::array<int32_t, 5>, const char*>> bad_wave = {
        {{2, 0, 0, 0, 0}, "type"},
        {{0, 4, 0, 0, 0}, "bands direction"},
        {{0, 0, -1, 0, 0}, "rings direction"},
        {{0, 0, 0, 3, 0}, "profile"},
        {{0, 0, 0, 0, 4}, "noise generation"}};
    for (const auto& [m, field] : bad_wave) {
        OneNode n(node_type("wave"), {m[0], m[1], m[2], m[3], m[4]},
                  {v3(0, 0, 0), v1(1), v1(0), v1(2), v1(1), v1(0.5), v1(0)}, {3, 1});
        const std::string e = n.error();
        EXPECT_NE(e.find("wave"), std::string::npos) << e;
        EXPECT_NE(e.find(field), std::string::npos) << e;
    }
    {
        OneNode n(node_type("magic"), {11}, {v3(0, 0, 0), v1(1), v1(1)}, {3, 1});
        const std::string e = n.error();
        EXPECT_NE(e.find("magic"), std::string::npos) << e;
        EXPECT_NE(e.find("turbulence depth"), std::string::npos) << e;
    }
    const std::vector<std::vector<float>> brick_inputs = {v3(0, 0, 0), kColor1, kColor2, kMortar, v1(5),
                                                          v1(0.02),    v1(0.1), v1(0),   v1(0.5), v1(0.25)};
    const std::vector<std::pair<std::vector<int32_t>, const char*>> bad = {
        {{-1, 2, 0}, "offset frequency"}, {{2, 256, 0}, "squash frequency"}, {{2, 2, 2}, "smoothing"}};
    for (const auto& [modes, field] : bad) {
        OneNode n(node_type("brick"), modes, brick_inputs, {3, 1}, {0.5f, 1.0f});
        const std::string e = n.error();
        EXPECT_NE(e.find("brick"), std::string::npos) << e;
        EXPECT_NE(e.find(field), std::string::npos) << e;
    }
    {
        OneNode n(node_type("brick"), {2, 2, 0}, brick_inputs, {3, 1}, {0.5f});
        EXPECT_NE(n.error().find("data_count"), std::string::npos);
    }
    {
        OneNode n(node_type("image"), {0, 3}, {v3(0, 0, 0)}, {3, 1});
        add_texture(n.handle.scene, "Non-Color", 0, 1.0f, 1.0f);
        EXPECT_NE(n.error().find("alpha"), std::string::npos);
    }
    {
        OneNode n(node_type("image"), {1, 0}, {v3(0, 0, 0)}, {3, 1});
        add_texture(n.handle.scene, "Non-Color", 0, 1.0f, 1.0f);
        EXPECT_NE(n.error().find("texture 1"), std::string::npos);
    }
    {
        // A vector input two registers short of the end.
        OneNode n(node_type("checker"), {}, {v3(0, 0, 0), v3(0, 0, 0), v3(0, 0, 0), v1(1)}, {3, 1});
        n.node.inputs[2] = static_cast<uint32_t>(n.registers.size() - 2);
        EXPECT_NE(n.error().find("checker"), std::string::npos);
    }
}

}  // namespace
