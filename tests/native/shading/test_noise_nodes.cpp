// The Noise and Musgrave textures (shading/nodes/noise_texture.cpp, musgrave_texture.cpp) and
// the noise they are built on (shading/cycles_hash.h, perlin_noise.h, fractal_noise.h), checked
// against values derived independently: lookup3 hashes from the published algorithm (computed
// apart, in Python), Perlin noise at lattice points and cell centres from its definition, the
// fractal sums re-added octave by octave, and values Blender 3.4 and 5.0 rendered with Cycles.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "node_types.h"
#include "scene_handle.h"
#include "shading/cycles_hash.h"
#include "shading/fractal_noise.h"
#include "shading/perlin_noise.h"

namespace {

using stratum_test::node_type;

using stratum::perlin::Precision;
namespace perlin = stratum::perlin;
namespace hash = stratum::cycles_hash;

constexpr float kInf = std::numeric_limits<float>::infinity();

// ---- the program harness ------------------------------------------------------------------------

// Registers: the renderer's inputs (0..79; the point in GENERATED), then the node's constant
// inputs and its outputs.
constexpr uint32_t kFirst = STRATUM_SHADER_INPUT_REGISTERS;

struct NoiseSetup {
    int dimensions = 3;  // 1..4
    int type = 1;        // fBM
    int normalize = 1;
    int generation = 3;
    float w = 0.0f, scale = 1.0f, detail = 0.0f, roughness = 0.5f, lacunarity = 2.0f, offset = 0.0f,
          gain = 1.0f, distortion = 0.0f;
};

struct Result {
    StratumStatus status;
    float fac;
    std::array<float, 3> color;
};

std::vector<float> registers_with(const std::vector<float>& constants, uint32_t outputs) {
    std::vector<float> r(kFirst, 0.0f);
    r.insert(r.end(), constants.begin(), constants.end());
    r.resize(r.size() + outputs, 0.0f);
    return r;
}

// `extra`: more renderer inputs to write (a non-finite value can only come from there).
Result run(const StratumShaderNode& node, const std::vector<float>& registers, std::array<float, 3> point,
           uint32_t out_first, const std::vector<std::pair<uint32_t, float>>& extra = {}) {
    stratum_test::SceneHandle h;
    StratumShaderProgramDesc desc{&node,   1, registers.data(), static_cast<uint32_t>(registers.size()),
                                  nullptr, 0};
    uint32_t id = 0;
    Result res{stratum_scene_add_shader_program(h.scene, &desc, &id), 0.0f, {}};
    if (res.status != STRATUM_OK) return res;
    std::vector<float> inputs(kFirst, 0.0f);
    for (int i = 0; i < 3; ++i) inputs[STRATUM_INPUT_GENERATED + i] = point[i];
    for (const auto& [index, value] : extra) inputs[index] = value;
    float out[4] = {};
    EXPECT_EQ(stratum_scene_evaluate_program(h.scene, id, inputs.data(), out_first, 4, out), STRATUM_OK);
    res.fac = out[0];
    res.color = {out[1], out[2], out[3]};
    return res;
}

// With `hostile`, Detail and Roughness are read from renderer inputs holding NaN.
Result noise_texture(const NoiseSetup& s, std::array<float, 3> point, bool color = true,
                     bool hostile = false) {
    StratumShaderNode node{};
    node.type = node_type("noise");
    const int32_t modes[6] = {s.dimensions - 1, s.type, s.normalize, s.generation, color ? 1 : 0, 0};
    std::copy(modes, modes + 6, node.modes);
    node.inputs[0] = STRATUM_INPUT_GENERATED;
    for (uint32_t i = 1; i < 9; ++i) node.inputs[i] = kFirst + i - 1;
    node.outputs[0] = kFirst + 8;
    node.outputs[1] = kFirst + 9;
    const auto r = registers_with(
        {s.w, s.scale, s.detail, s.roughness, s.lacunarity, s.offset, s.gain, s.distortion}, 4);
    if (!hostile) return run(node, r, point, kFirst + 8);
    node.inputs[3] = STRATUM_INPUT_RAY_LENGTH;
    node.inputs[4] = STRATUM_INPUT_OBJECT_RANDOM;
    const float nan = std::nanf("");
    return run(node, r, point, kFirst + 8,
               {{STRATUM_INPUT_RAY_LENGTH, nan}, {STRATUM_INPUT_OBJECT_RANDOM, nan}});
}

struct MusgraveSetup {
    int dimensions = 3;
    int type = 1;
    float w = 0.0f, scale = 1.0f, detail = 2.0f, dimension = 2.0f, lacunarity = 2.0f, offset = 0.0f,
          gain = 1.0f;
};

Result musgrave_texture(const MusgraveSetup& s, std::array<float, 3> point) {
    StratumShaderNode node{};
    node.type = node_type("musgrave");
    node.modes[0] = s.dimensions - 1;
    node.modes[1] = s.type;
    node.inputs[0] = STRATUM_INPUT_GENERATED;
    for (uint32_t i = 1; i < 8; ++i) node.inputs[i] = kFirst + i - 1;
    node.outputs[0] = kFirst + 7;
    const auto r = registers_with({s.w, s.scale, s.detail, s.dimension, s.lacunarity, s.offset, s.gain}, 4);
    return run(node, r, point, kFirst + 7);
}

float snoise3(float x, float y, float z, Precision p = Precision::Wrapped) {
    return perlin::snoise<3>({x, y, z}, p);
}

// ---- the hash -----------------------------------------------------------------------------------

TEST(NoiseNodesHash, Lookup3MatchesTheAlgorithm) {
    // Bob Jenkins' hashword with initval 13 (Cycles' seed), computed apart from this code.
    EXPECT_EQ(hash::hash_uint(0u), 0x9519dc65u);
    EXPECT_EQ(hash::hash_uint(1u), 0x4ad7c6a0u);
    EXPECT_EQ(hash::hash_uint(0xdeadbeefu), 0xf385ca09u);
    EXPECT_EQ(hash::hash_uint2(1u, 2u), 0x1037cb9du);
    EXPECT_EQ(hash::hash_uint3(1u, 2u, 3u), 0xb8d17a0au);
    EXPECT_EQ(hash::hash_uint4(1u, 2u, 3u, 4u), 0x0584dec1u);
    EXPECT_EQ(hash::hash_uint4(0xffffffffu, 0u, 7u, 0x3f800000u), 0x0d3673e1u);
    // A float key hashes its bits; the unit value divides by 2^32 - 1.
    EXPECT_FLOAT_EQ(hash::hash_float(1.0f), static_cast<float>(hash::hash_uint(0x3f800000u)) / 4294967295.0f);
}

// ---- Perlin noise -------------------------------------------------------------------------------

TEST(NoiseNodesPerlin, ZeroAtLatticePoints) {
    for (float a : {-3.0f, 0.0f, 1.0f, 17.0f}) {
        for (float b : {-1.0f, 2.0f, 40.0f}) {
            EXPECT_EQ(perlin::perlin_1d(a), 0.0f);
            EXPECT_EQ(perlin::perlin_2d(a, b), 0.0f);
            EXPECT_EQ(perlin::perlin_3d(a, b, a - b), 0.0f);
            EXPECT_EQ(perlin::perlin_4d(b, a, a + b, 5.0f), 0.0f);
        }
    }
}

// Slope of OSL's 1D gradient for a hash: 1..8, negative when bit 3 is set.
float slope(uint32_t h) { return ((h & 8u) ? -1.0f : 1.0f) * static_cast<float>(1u + (h & 7u)); }

TEST(NoiseNodesPerlin, CellCentresFromTheGradients) {
    // 1D at X + 1/2: fade(1/2) = 1/2, so (g0 / 2 + g1 (-1/2)) / 2.
    for (int x : {-7, 0, 3, 1000}) {
        const uint32_t X = static_cast<uint32_t>(x);
        const float expected = 0.25f * (slope(hash::hash_uint(X)) - slope(hash::hash_uint(X + 1u)));
        EXPECT_FLOAT_EQ(perlin::perlin_1d(static_cast<float>(x) + 0.5f), expected) << x;
    }
    // 2D at (1/2, 1/2): the mean of the four corner gradients at (+-1/2, +-1/2); gradient h & 7
    // is (u, 2v) with u = x, v = y for h < 4, else u = y, v = x, signs by bits 0 and 1.
    const auto g2 = [](uint32_t h, float x, float y) {
        h &= 7u;
        const float u = h < 4 ? x : y, v = 2.0f * (h < 4 ? y : x);
        return ((h & 1u) ? -u : u) + ((h & 2u) ? -v : v);
    };
    const float expected =
        0.25f * (g2(hash::hash_uint2(0, 0), 0.5f, 0.5f) + g2(hash::hash_uint2(1, 0), -0.5f, 0.5f) +
                 g2(hash::hash_uint2(0, 1), 0.5f, -0.5f) + g2(hash::hash_uint2(1, 1), -0.5f, -0.5f));
    EXPECT_FLOAT_EQ(perlin::perlin_2d(0.5f, 0.5f), expected);
}

TEST(NoiseNodesPerlin, RangeAndScale) {
    // |perlin_1d| <= 4 (slopes <= 8, at most half a cell from a corner), so |snoise_1d| <= 1;
    // |grad3| <= 2, so |snoise_3d| <= 2 x 0.982. The OSL scales make each reach well past 0.7.
    std::array<float, 4> most{};
    uint32_t state = 1;
    const auto next = [&] {
        state = state * 1664525u + 1013904223u;
        return static_cast<float>(state >> 8) / 16777216.0f * 64.0f - 32.0f;
    };
    for (int i = 0; i < 20000; ++i) {
        const float a = next(), b = next(), c = next(), d = next();
        const float v[4] = {perlin::snoise<1>({a}, Precision::Finite),
                            perlin::snoise<2>({a, b}, Precision::Finite),
                            perlin::snoise<3>({a, b, c}, Precision::Finite),
                            perlin::snoise<4>({a, b, c, d}, Precision::Finite)};
        for (int k = 0; k < 4; ++k) most[k] = std::max(most[k], std::fabs(v[k]));
    }
    EXPECT_LE(most[0], 1.0f);
    EXPECT_LE(most[2], 2.0f * 0.982f);
    for (int k = 0; k < 4; ++k) {
        EXPECT_GT(most[k], 0.7f) << k + 1 << "D";
        EXPECT_LT(most[k], 1.2f) << k + 1 << "D";
    }
}

TEST(NoiseNodesPerlin, PrecisionGenerations) {
    // 4.2+: a coordinate >= 1e6 in magnitude is taken modulo 1e5 and shifted by 1/2.
    EXPECT_EQ(perlin::snoise<1>({1234567.0f}, Precision::Wrapped), 0.25f * perlin::perlin_1d(34567.5f));
    EXPECT_EQ(perlin::snoise<1>({234567.25f}, Precision::Wrapped), 0.25f * perlin::perlin_1d(34567.25f));
    EXPECT_EQ(perlin::snoise<1>({234567.25f}, Precision::Finite), 0.25f * perlin::perlin_1d(234567.25f));
    // Not finite: 0 before 4.2, NaN after; and a huge coordinate never reaches undefined casts.
    EXPECT_EQ(perlin::snoise<3>({kInf, 0.5f, 0.5f}, Precision::Finite), 0.0f);
    EXPECT_TRUE(std::isnan(perlin::snoise<3>({kInf, 0.5f, 0.5f}, Precision::Wrapped)));
    EXPECT_TRUE(std::isfinite(perlin::snoise<4>({3e9f, -3e9f, 1e30f, 0.5f}, Precision::Finite)));
    EXPECT_EQ(perlin::floor_to_lattice(3e9f), std::numeric_limits<int32_t>::min());
    EXPECT_EQ(perlin::floor_to_lattice(std::nanf("")), std::numeric_limits<int32_t>::min());
    EXPECT_EQ(perlin::floor_to_lattice(-5.0f), -5);
}

TEST(NoiseNodesPerlin, Continuous) {
    for (float x = -3.0f; x < 3.0f; x += 0.173f) {
        const float a = snoise3(x, 0.3f * x, 1.7f), b = snoise3(x + 1e-4f, 0.3f * x, 1.7f);
        EXPECT_LT(std::fabs(a - b), 1e-3f) << x;
    }
}

// ---- the Noise texture --------------------------------------------------------------------------

TEST(NoiseNodesTexture, DetailZeroIsOneOctave) {
    const std::array<float, 3> p{0.37f, 1.91f, -0.42f};
    for (int generation = 0; generation < 4; ++generation) {
        NoiseSetup s;
        s.generation = generation;
        s.scale = 2.5f;
        const Result r = noise_texture(s, p);
        ASSERT_EQ(r.status, STRATUM_OK);
        const Precision prec = generation == 3 ? Precision::Wrapped : Precision::Finite;
        EXPECT_NEAR(r.fac, 0.5f * snoise3(0.925f, 4.775f, -1.05f, prec) + 0.5f, 1e-6f) << generation;
    }
    // Not normalised (4.0+): the signed noise itself.
    NoiseSetup s;
    s.normalize = 0;
    EXPECT_NEAR(noise_texture(s, p).fac, snoise3(p[0], p[1], p[2]), 1e-6f);
}

TEST(NoiseNodesTexture, OctavesAddUp) {
    const std::array<float, 3> p{0.37f, 1.91f, -0.42f};
    const float s0 = snoise3(p[0], p[1], p[2]), s1 = snoise3(3 * p[0], 3 * p[1], 3 * p[2]);
    const float s2 = snoise3(9 * p[0], 9 * p[1], 9 * p[2]);
    NoiseSetup s;
    s.detail = 1.0f;
    s.roughness = 0.7f;
    s.lacunarity = 3.0f;
    // Normalised: ((s0 + r s1) / (1 + r)) / 2 + 1/2.
    const float one = 0.5f * (s0 + 0.7f * s1) / 1.7f + 0.5f;
    EXPECT_NEAR(noise_texture(s, p).fac, one, 1e-6f);
    s.detail = 2.0f;
    const float two = 0.5f * (s0 + 0.7f * s1 + 0.49f * s2) / 2.19f + 0.5f;
    EXPECT_NEAR(noise_texture(s, p).fac, two, 1e-6f);
    // A fractional detail blends the two sums.
    s.detail = 1.25f;
    EXPECT_NEAR(noise_texture(s, p).fac, one + 0.25f * (two - one), 1e-6f);
    // 3.x: lacunarity 2 whatever the socket says, roughness clamped to 1.
    s.generation = 0;
    s.detail = 1.0f;
    s.roughness = 4.0f;
    const float t0 = 0.5f * s0 + 0.5f;
    const float t1 = 0.5f * snoise3(2 * p[0], 2 * p[1], 2 * p[2], Precision::Finite) + 0.5f;
    EXPECT_NEAR(noise_texture(s, p).fac, (t0 + t1) / 2.0f, 1e-6f);
    // 4.1+: roughness above 1 is kept.
    s.generation = 3;
    s.normalize = 0;
    s.lacunarity = 3.0f;
    EXPECT_NEAR(noise_texture(s, p).fac, s0 + 4.0f * s1, 1e-5f);
}

TEST(NoiseNodesTexture, MultifractalTypesFromTheirDefinitions) {
    const std::array<float, 3> p{0.61f, -0.23f, 2.13f};
    const float s0 = snoise3(p[0], p[1], p[2]), s1 = snoise3(2 * p[0], 2 * p[1], 2 * p[2]);
    NoiseSetup s;
    s.detail = 1.0f;
    s.roughness = 0.6f;
    s.offset = 0.8f;
    s.gain = 1.3f;
    s.type = 0;  // multifractal
    EXPECT_NEAR(noise_texture(s, p).fac, (1.0f + s0) * (1.0f + 0.6f * s1), 1e-5f);
    s.type = 4;  // heterogeneous terrain
    const float h0 = 0.8f + s0;
    EXPECT_NEAR(noise_texture(s, p).fac, h0 + (s1 + 0.8f) * 0.6f * h0, 1e-5f);
    s.type = 2;  // hybrid
    const float signal0 = s0 + 0.8f, weight = std::fmin(1.3f * signal0, 1.0f);
    const float hybrid = signal0 + (weight > 0.001f ? weight * (s1 + 0.8f) * 0.6f : 0.0f);
    EXPECT_NEAR(noise_texture(s, p).fac, hybrid, 1e-5f);
    s.type = 3;  // ridged
    const float r0 = (0.8f - std::fabs(s0)) * (0.8f - std::fabs(s0));
    const float w1 = std::clamp(r0 * 1.3f, 0.0f, 1.0f);
    const float r1 = (0.8f - std::fabs(s1)) * (0.8f - std::fabs(s1)) * w1;
    EXPECT_NEAR(noise_texture(s, p).fac, r0 + r1 * 0.6f, 1e-5f);
    // Ridged ignores the fraction of detail; the others blend it in.
    s.detail = 1.5f;
    EXPECT_NEAR(noise_texture(s, p).fac, r0 + r1 * 0.6f, 1e-5f);
}

TEST(NoiseNodesTexture, DistortionAndColourUseSeededOffsets) {
    const auto offset = [](int seed, int k) {
        return 100.0f + 100.0f * hash::hash_float2(float(seed), float(k));
    };
    const std::array<float, 3> p{0.2f, 0.4f, 0.9f};
    NoiseSetup s;
    s.distortion = 0.7f;
    const Result r = noise_texture(s, p);
    std::array<float, 3> q = p;
    for (int k = 0; k < 3; ++k)
        q[k] += snoise3(p[0] + offset(k, 0), p[1] + offset(k, 1), p[2] + offset(k, 2)) * 0.7f;
    // The library and this test are separate translation units, which a compiler may contract
    // differently (clang's sanitized build fuses the distortion's multiply-add): q can differ by
    // an ulp, and the colour channels look noise up at q + offset, where an ulp of |q| ~ 200 is
    // 1.5e-5, times noise's gradient (below 1.1 for snoise's scale) and the 0.5 of the output.
    constexpr float kUlpAt200 = 1.5e-5f, kTolerance = 0.5f * 1.1f * kUlpAt200;
    EXPECT_NEAR(r.fac, 0.5f * snoise3(q[0], q[1], q[2]) + 0.5f, kTolerance);
    EXPECT_EQ(r.color[0], r.fac);
    EXPECT_NEAR(r.color[1],
                0.5f * snoise3(q[0] + offset(3, 0), q[1] + offset(3, 1), q[2] + offset(3, 2)) + 0.5f,
                kTolerance);
    EXPECT_NEAR(r.color[2],
                0.5f * snoise3(q[0] + offset(4, 0), q[1] + offset(4, 1), q[2] + offset(4, 2)) + 0.5f,
                kTolerance);
    // 1D hashes the seed alone; W is scaled like the vector.
    NoiseSetup one;
    one.dimensions = 1;
    one.w = 0.3f;
    one.scale = 3.0f;
    one.distortion = 0.5f;
    const float d = perlin::snoise<1>({0.9f + 100.0f + 100.0f * hash::hash_float(0.0f)}, Precision::Wrapped);
    EXPECT_NEAR(noise_texture(one, p).fac,
                0.5f * perlin::snoise<1>({0.9f + d * 0.5f}, Precision::Wrapped) + 0.5f, 1e-6f);
}

TEST(NoiseNodesTexture, DimensionsReadTheirCoordinates) {
    const std::array<float, 3> p{0.2f, 0.4f, 0.9f};
    NoiseSetup s;
    s.w = 0.35f;
    s.dimensions = 2;
    EXPECT_NEAR(noise_texture(s, p).fac, 0.5f * perlin::snoise<2>({0.2f, 0.4f}, Precision::Wrapped) + 0.5f,
                1e-6f);
    s.dimensions = 4;
    EXPECT_NEAR(noise_texture(s, p).fac,
                0.5f * perlin::snoise<4>({0.2f, 0.4f, 0.9f, 0.35f}, Precision::Wrapped) + 0.5f, 1e-6f);
}

TEST(NoiseNodesTexture, ChecksEveryMode) {
    NoiseSetup s;
    s.dimensions = 5;
    EXPECT_EQ(noise_texture(s, {}).status, STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("dimensions"), std::string::npos);
    s = {};
    s.type = 5;
    EXPECT_EQ(noise_texture(s, {}).status, STRATUM_ERROR_INVALID_ARGUMENT);
    s = {};
    s.generation = 4;
    EXPECT_EQ(noise_texture(s, {}).status, STRATUM_ERROR_INVALID_ARGUMENT);
    s = {};
    s.normalize = -1;
    EXPECT_EQ(noise_texture(s, {}).status, STRATUM_ERROR_INVALID_ARGUMENT);
    // Multifractal types came with Blender 4.1.
    s = {};
    s.generation = 1;
    s.type = 0;
    EXPECT_EQ(noise_texture(s, {}).status, STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("type"), std::string::npos);
    s.generation = 2;
    EXPECT_EQ(noise_texture(s, {}).status, STRATUM_OK);
}

TEST(NoiseNodesTexture, HostileValuesStayQuiet) {
    NoiseSetup s;
    s.generation = 2;
    const Result r = noise_texture(s, {0.3f, 0.1f, 0.7f}, true, true);
    ASSERT_EQ(r.status, STRATUM_OK);
    EXPECT_NEAR(r.fac, 0.5f * snoise3(0.3f, 0.1f, 0.7f, Precision::Finite) + 0.5f, 1e-6f);  // detail NaN -> 0
    s.detail = 1e30f;  // clamped to 15 octaves
    s.scale = 1e30f;
    EXPECT_TRUE(std::isfinite(noise_texture(s, {0.3f, 0.1f, 0.7f}).fac));
    // A point at infinity: 0 noise (one half) before 4.2, NaN from 4.2 on, as Cycles.
    s = {};
    s.generation = 2;
    EXPECT_EQ(noise_texture(s, {kInf, 0.1f, 0.7f}).fac, 0.5f);
    s.generation = 3;
    EXPECT_TRUE(std::isnan(noise_texture(s, {kInf, 0.1f, 0.7f}).fac));
}

// ---- the Musgrave texture -----------------------------------------------------------------------

TEST(NoiseNodesMusgrave, TypesFromTheirDefinitions) {
    const std::array<float, 3> p{0.61f, -0.23f, 2.13f};
    const auto sn = [&](float f) { return snoise3(f * p[0], f * p[1], f * p[2], Precision::Finite); };
    MusgraveSetup s;
    s.dimension = 1.5f;
    s.lacunarity = 2.5f;
    s.offset = 0.9f;
    s.gain = 1.2f;
    const float pw = std::pow(2.5f, -1.5f);
    s.detail = 2.0f;  // two whole octaves (Noise would sum three)
    EXPECT_NEAR(musgrave_texture(s, p).fac, sn(1) + pw * sn(2.5f), 1e-5f);
    s.detail = 2.5f;
    EXPECT_NEAR(musgrave_texture(s, p).fac, sn(1) + pw * sn(2.5f) + 0.5f * sn(6.25f) * pw * pw, 1e-5f);
    s.detail = 2.0f;
    s.type = 0;
    EXPECT_NEAR(musgrave_texture(s, p).fac, (1 + sn(1)) * (1 + pw * sn(2.5f)), 1e-5f);
    s.type = 4;
    const float h0 = 0.9f + sn(1);
    EXPECT_NEAR(musgrave_texture(s, p).fac, h0 + (sn(2.5f) + 0.9f) * pw * h0, 1e-5f);
    s.type = 3;
    const float r0 = (0.9f - std::fabs(sn(1))) * (0.9f - std::fabs(sn(1)));
    const float w1 = std::clamp(r0 * 1.2f, 0.0f, 1.0f);
    EXPECT_NEAR(musgrave_texture(s, p).fac,
                r0 + (0.9f - std::fabs(sn(2.5f))) * (0.9f - std::fabs(sn(2.5f))) * w1 * pw, 1e-5f);
    s.type = 2;
    const float sig0 = sn(1) + 0.9f, weight = std::fmin(1.2f * sig0, 1.0f);
    EXPECT_NEAR(musgrave_texture(s, p).fac, sig0 + (weight > 0.001f ? weight * (sn(2.5f) + 0.9f) * pw : 0.0f),
                1e-5f);
    // Detail 0: no octave at all for fBM and multifractal, the first for the terrains.
    s.detail = 0.0f;
    s.type = 1;
    EXPECT_EQ(musgrave_texture(s, p).fac, 0.0f);
    s.type = 0;
    EXPECT_EQ(musgrave_texture(s, p).fac, 1.0f);
    s.type = 4;
    EXPECT_NEAR(musgrave_texture(s, p).fac, 0.9f + sn(1), 1e-6f);
}

TEST(NoiseNodesMusgrave, ChecksItsModes) {
    MusgraveSetup s;
    s.dimensions = 0;
    EXPECT_EQ(musgrave_texture(s, {}).status, STRATUM_ERROR_INVALID_ARGUMENT);
    s.dimensions = 4;
    s.type = 7;
    EXPECT_EQ(musgrave_texture(s, {}).status, STRATUM_ERROR_INVALID_ARGUMENT);
    s.type = 4;
    s.dimension = -3.0f;  // clamped to 1e-5
    s.lacunarity = 0.0f;  // clamped to 1e-5
    EXPECT_EQ(musgrave_texture(s, {0.1f, 0.2f, 0.3f}).status, STRATUM_OK);
}

}  // namespace

// ---- against Cycles ------------------------------------------------------------------------------

// Values Cycles rendered (scripts/cycles_reference/noise.py: one pixel of each configuration, an
// Emission plane at an exact point) in Blender 3.4.1 and 5.0. Over all 16 x 16 points of 28
// configurations the worst difference was 3.2e-5 (distortion amplifies Cycles' fused
// multiply-adds); 1e-4 bounds it with room to spare and stays 10x inside the 1e-3 target.
constexpr std::array<float, 3> kCyclesPoint{3.545f, -1.785f, 0.73f};  // W = its X

void expect_cycles(const Result& r, std::array<float, 3> expected, const char* what) {
    ASSERT_EQ(r.status, STRATUM_OK) << what;
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(r.color[k], expected[k], 1e-4f * std::max(1.0f, std::fabs(expected[k])))
            << what << " " << k;
}
void expect_cycles(const Result& r, float expected, const char* what) {
    ASSERT_EQ(r.status, STRATUM_OK) << what;
    EXPECT_NEAR(r.fac, expected, 1e-4f * std::max(1.0f, std::fabs(expected))) << what;
}

TEST(NoiseNodesCycles, Blender34Noise) {
    NoiseSetup s;
    s.generation = 0;
    s.scale = 3.0f;
    s.detail = 4.5f;
    s.roughness = 0.6f;
    s.distortion = 1.3f;
    expect_cycles(noise_texture(s, kCyclesPoint), {0.51313305f, 0.55655050f, 0.53533697f}, "3D");
    s.dimensions = 4;
    s.w = kCyclesPoint[0];
    s.scale = 2.0f;
    s.detail = 6.0f;
    s.roughness = 0.45f;
    s.distortion = 0.8f;
    expect_cycles(noise_texture(s, kCyclesPoint), {0.43614089f, 0.55184978f, 0.52614933f}, "4D");
    s.dimensions = 1;
    s.scale = 4.0f;
    s.detail = 3.3f;
    s.roughness = 0.7f;
    s.distortion = 0.4f;
    expect_cycles(noise_texture(s, kCyclesPoint), {0.49901682f, 0.56508547f, 0.43406504f}, "1D");
}

TEST(NoiseNodesCycles, Blender34Musgrave) {
    MusgraveSetup s;
    s.scale = 4.0f;
    s.detail = 3.5f;
    s.dimension = 1.2f;
    s.lacunarity = 2.1f;
    s.offset = 1.0f;
    s.gain = 1.1f;
    s.type = 4;
    expect_cycles(musgrave_texture(s, kCyclesPoint), 1.82471836f, "hetero terrain");
    s.type = 2;
    expect_cycles(musgrave_texture(s, kCyclesPoint), 1.60772371f, "hybrid");
    s.type = 1;
    expect_cycles(musgrave_texture(s, kCyclesPoint), 0.08461980f, "fBM");
    s = {};
    s.dimensions = 4;
    s.type = 3;
    s.w = kCyclesPoint[0];
    s.scale = 3.0f;
    s.detail = 5.0f;
    s.dimension = 0.8f;
    s.lacunarity = 2.5f;
    s.offset = 1.0f;
    s.gain = 2.0f;
    expect_cycles(musgrave_texture(s, kCyclesPoint), 1.35198796f, "4D ridged");
}

TEST(NoiseNodesCycles, Blender50Noise) {
    NoiseSetup s;
    s.scale = 3.0f;
    s.detail = 3.5f;
    s.roughness = 0.6f;
    s.normalize = 0;
    expect_cycles(noise_texture(s, kCyclesPoint), {0.26377919f, -0.31804252f, 0.02538009f},
                  "fBM not normalised");
    s.normalize = 1;
    s.detail = 4.5f;
    s.lacunarity = 2.3f;
    s.distortion = 1.3f;
    expect_cycles(noise_texture(s, kCyclesPoint), {0.50580227f, 0.49983114f, 0.56105709f}, "fBM distorted");
    s = {};
    s.scale = 4.0f;
    s.detail = 3.5f;
    s.roughness = 0.6f;
    s.lacunarity = 2.1f;
    s.offset = 1.0f;
    s.gain = 1.1f;
    s.type = 4;
    expect_cycles(noise_texture(s, kCyclesPoint), 3.00474501f, "hetero terrain");
    s.type = 2;
    expect_cycles(noise_texture(s, kCyclesPoint), 2.00665021f, "hybrid");
    s.dimensions = 2;
    s.type = 3;
    expect_cycles(noise_texture(s, kCyclesPoint), 1.24673414f, "2D ridged");
    s.type = 0;
    expect_cycles(noise_texture(s, kCyclesPoint), 0.79624403f, "2D multifractal");
    // Coordinates past 1e6: wrapped and shifted as 4.2+ does.
    s = {};
    s.detail = 1.0f;
    expect_cycles(noise_texture(s, {2500000.5f, -1250000.375f, 3000000.0f}), 0.52773190f,
                  "large coordinates");
}
