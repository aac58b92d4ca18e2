// Vector and converter nodes (shading/nodes/vector_math_node.cpp, map_range_node.cpp,
// mapping_node.cpp, fresnel_node.cpp, blackbody_node.cpp) run through the C ABI, one node per
// program, against values worked out by hand or from closed forms (Snell's law and the Fresnel
// equations, rotation matrices, the CIE tables' published values).
#include <gtest/gtest.h>
#include <stratum/shader_nodes.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "node_types.h"
#include "scene_handle.h"

namespace {

using stratum_test::node_type;

using Values = std::vector<float>;
constexpr float kPiF = 3.14159265358979323846f;

// One node on constant inputs; returns its outputs' registers in order.
struct OneNode {
    int32_t type = 0;
    std::array<int32_t, 6> modes{};
    std::vector<Values> inputs;  // each 1 or 3 floats
    std::vector<int> output_widths;
    Values data;
    // Input 0 reads the renderer's ray-length register instead, holding this value (a NaN, which
    // a program's constants may not hold).
    bool first_from_renderer = false;
    float renderer_value = 0.0f;

    StratumStatus add(StratumScene* scene, uint32_t* id, uint32_t* first_output, uint32_t* total) const {
        std::vector<float> registers(STRATUM_SHADER_INPUT_REGISTERS, 0.0f);
        StratumShaderNode node{};
        node.type = type;
        for (int i = 0; i < 6; ++i) node.modes[i] = modes[i];
        for (size_t i = 0; i < inputs.size(); ++i) {
            node.inputs[i] = static_cast<uint32_t>(registers.size());
            if (i == 0 && first_from_renderer) {
                node.inputs[i] = STRATUM_INPUT_RAY_LENGTH;
                continue;
            }
            registers.insert(registers.end(), inputs[i].begin(), inputs[i].end());
        }
        *first_output = static_cast<uint32_t>(registers.size());
        *total = 0;
        for (size_t i = 0; i < output_widths.size(); ++i) {
            node.outputs[i] = static_cast<uint32_t>(registers.size());
            registers.insert(registers.end(), static_cast<size_t>(output_widths[i]), -7.0f);
            *total += static_cast<uint32_t>(output_widths[i]);
        }
        node.data_count = static_cast<uint32_t>(data.size());
        StratumShaderProgramDesc desc{};
        desc.nodes = &node;
        desc.node_count = 1;
        desc.registers = registers.data();
        desc.register_count = static_cast<uint32_t>(registers.size());
        desc.data = data.empty() ? nullptr : data.data();
        desc.data_count = static_cast<uint32_t>(data.size());
        return stratum_scene_add_shader_program(scene, &desc, id);
    }

    Values run() const {
        stratum_test::SceneHandle h;
        uint32_t id = 0, first = 0, total = 0;
        EXPECT_EQ(add(h.scene, &id, &first, &total), STRATUM_OK) << stratum_last_error();
        std::vector<float> in(STRATUM_SHADER_INPUT_REGISTERS, 0.0f);
        in[STRATUM_INPUT_RAY_LENGTH] = renderer_value;
        Values out(total, -9.0f);
        EXPECT_EQ(stratum_scene_evaluate_program(h.scene, id, in.data(), first, total, out.data()),
                  STRATUM_OK);
        return out;
    }

    std::string rejection() const {
        stratum_test::SceneHandle h;
        uint32_t id = 0, first = 0, total = 0;
        if (add(h.scene, &id, &first, &total) == STRATUM_OK) return "";
        return stratum_last_error();
    }
};

void expect_near(const Values& got, const Values& want, float tol = 1e-5f) {
    ASSERT_EQ(got.size(), want.size());
    for (size_t i = 0; i < got.size(); ++i)
        EXPECT_NEAR(got[i], want[i], tol * std::fmax(1.0f, std::fabs(want[i]))) << "component " << i;
}

// ---- Vector Math ------------------------------------------------------------------------------

enum Op {
    Add,
    Subtract,
    Multiply,
    Divide,
    Cross,
    Project,
    Reflect,
    Dot,
    Distance,
    Length,
    Scale,
    Normalize,
    Snap,
    Floor,
    Ceil,
    Modulo,
    Fraction,
    Absolute,
    Minimum,
    Maximum,
    Wrap,
    Sine,
    Cosine,
    Tangent,
    Refract,
    Faceforward,
    MultiplyAdd,
    Power,
    Sign
};

// Vector and value outputs of a vector math node.
Values vmath(int op, Values a, Values b = {0, 0, 0}, Values c = {0, 0, 0}, float scale = 1.0f,
             int revision = 2) {
    OneNode n{node_type("vector_math"), {op, revision}, {a, b, c, {scale}}, {3, 1}, {}};
    return n.run();
}

const Values kA = {1, -2, 3}, kB = {0.5f, 4, -2}, kC = {2, 1, 0.5f};

TEST(VectorNodes, VectorMathArithmetic) {
    expect_near(vmath(Add, kA, kB), {1.5f, 2, 1, 0});
    expect_near(vmath(Subtract, kA, kB), {0.5f, -6, 5, 0});
    expect_near(vmath(Multiply, kA, kB), {0.5f, -8, -6, 0});
    expect_near(vmath(Divide, kA, {0.5f, 0, -2}), {2, 0, -1.5f, 0});  // x / 0 is 0
    expect_near(vmath(MultiplyAdd, kA, kB, kC), {2.5f, -7, -5.5f, 0});
    expect_near(vmath(Scale, kA, kB, kC, 1.5f), {1.5f, -3, 4.5f, 0});
    expect_near(vmath(Minimum, kA, kB), {0.5f, -2, -2, 0});
    expect_near(vmath(Maximum, kA, kB), {1, 4, 3, 0});
    expect_near(vmath(Absolute, kA), {1, 2, 3, 0});
    expect_near(vmath(Sign, {3, -0.5f, 0}), {1, -1, 0, 0});
    expect_near(vmath(Power, {2, -8, 0}, {3, 1.0f / 3.0f, 0}), {8, 0, 1, 0});  // (-8)^(1/3): 0; 0^0: 1
    expect_near(vmath(Power, {-2, 4, 9}, {3, -1, 0.5f}), {-8, 0.25f, 3, 0});
}

TEST(VectorNodes, VectorMathGeometry) {
    // a x b = (ay bz - az by, az bx - ax bz, ax by - ay bx).
    expect_near(vmath(Cross, kA, kB), {-8, 3.5f, 5, 0});
    // a.b = -13.5, |b|^2 = 20.25: the projection is -2/3 b.
    expect_near(vmath(Project, kA, kB), {-1.0f / 3, -8.0f / 3, 4.0f / 3, 0});
    expect_near(vmath(Project, kA, {0, 0, 0}), {0, 0, 0, 0});
    expect_near(vmath(Dot, kA, kB), {0, 0, 0, -13.5f});
    expect_near(vmath(Distance, kA, kB), {0, 0, 0, std::sqrt(61.25f)});
    expect_near(vmath(Length, kA), {0, 0, 0, std::sqrt(14.0f)});
    const float r14 = 1.0f / std::sqrt(14.0f);
    expect_near(vmath(Normalize, kA), {r14, -2 * r14, 3 * r14, 0});
    expect_near(vmath(Normalize, {0, 0, 0}), {0, 0, 0, 0});
    // Mirror about the plane z = 0 (b is normalised first).
    expect_near(vmath(Reflect, kA, {0, 0, 2}), {1, -2, -3, 0});
    // c.b < 0 keeps a, else -a.
    expect_near(vmath(Faceforward, kA, {0, 0, 1}, {0, 0, -1}), {1, -2, 3, 0});
    expect_near(vmath(Faceforward, kA, {0, 0, 1}, {0, 0, 1}), {-1, 2, -3, 0});
}

TEST(VectorNodes, VectorMathRefractFollowsSnell) {
    // 30 degrees incidence into glass (eta = 1 / 1.5): sin t = 1/3, along the normal's side.
    const float s = 0.5f, c = std::sqrt(3.0f) / 2.0f;
    const float st = s / 1.5f, ct = std::sqrt(1.0f - st * st);
    expect_near(vmath(Refract, {s, -c, 0}, {0, 2, 0}, {0, 0, 0}, 1.0f / 1.5f), {st, -ct, 0, 0});
    // From glass out at 30 degrees with eta 1.5 and beyond the critical angle: total reflection.
    expect_near(vmath(Refract, {s, -c, 0}, {0, 1, 0}, {0, 0, 0}, 3.0f), {0, 0, 0, 0});
}

TEST(VectorNodes, VectorMathRoundingAndPeriodic) {
    // Snap: floor(a / b) b per component: floor(2) 0.5, floor(-0.5) 4, floor(-1.5) -2.
    expect_near(vmath(Snap, kA, kB), {1, -4, 4, 0});
    expect_near(vmath(Floor, {1.5f, -2.5f, 0.2f}), {1, -3, 0, 0});
    expect_near(vmath(Ceil, {1.5f, -2.5f, 0.2f}), {2, -2, 1, 0});
    expect_near(vmath(Fraction, {1.25f, -1.25f, 0}), {0.25f, 0.75f, 0, 0});
    for (int revision : {0, 2}) {
        // Truncated modulo keeps a's sign; b = 0 gives 0.
        expect_near(vmath(Modulo, {5.5f, -5.5f, 7}, {2, 2, 0}, {0, 0, 0}, 1, revision), {1.5f, -1.5f, 0, 0});
        // Wrap into [min, max): 5 -> 1, -1 -> 1; an empty range gives min.
        expect_near(vmath(Wrap, {5, -1, 0.5f}, {2, 2, 2}, {0, 0, 2}, 1, revision), {1, 1, 2, 0});
    }
    expect_near(vmath(Sine, {kPiF / 2, 0, -kPiF / 6}), {1, 0, -0.5f, 0});
    expect_near(vmath(Cosine, {kPiF, 0, kPiF / 3}), {-1, 1, 0.5f, 0});
    expect_near(vmath(Tangent, {kPiF / 4, 0, -kPiF / 4}), {1, 0, -1, 0});
}

TEST(VectorNodes, VectorMathRevisionsDiffer) {
    // A zero normal: 3.x-4.2 normalise it to NaN, 4.3+ keep it (Reflect returns a).
    const Values old_reflect = vmath(Reflect, kA, {0, 0, 0}, {0, 0, 0}, 1, 0);
    EXPECT_TRUE(std::isnan(old_reflect[0]));
    expect_near(vmath(Reflect, kA, {0, 0, 0}, {0, 0, 0}, 1, 1), {1, -2, 3, 0});
    EXPECT_TRUE(std::isnan(vmath(Refract, kA, {0, 0, 0}, {0, 0, 0}, 1.5f, 0)[0]));
    // 1e9 / 3 rounds to the float 333333344, and 333333344 * 3 = 1000000032: a remainder taken
    // with one rounding (Cycles' fused kernels, measured in Blender 3.4 and 5.0) is -32, where
    // fmodf (3.x-4.5's Modulo) gives the exact 1.
    EXPECT_EQ(vmath(Modulo, {1e9f, 0, 0}, {3, 1, 1}, {0, 0, 0}, 1, 0)[0], 1.0f);
    EXPECT_EQ(vmath(Modulo, {1e9f, 0, 0}, {3, 1, 1}, {0, 0, 0}, 1, 2)[0], -32.0f);
    for (int revision : {0, 2})
        EXPECT_EQ(vmath(Wrap, {1e9f, 0, 0}, {3, 1, 1}, {0, 0, 0}, 1, revision)[0], -32.0f);
    // 5.0's Wrap offsets by min before the modulo: 12345.6 in [-0.3, 0.7) is 0.59941 there
    // (12345.9 rounds to 12345.899), 0.59961 in 3.x (12345.6 rounds to 12345.6).
    EXPECT_NEAR(vmath(Wrap, {12345.6f, 0, 0}, {0.7f, 1, 1}, {-0.3f, 0, 0}, 1, 0)[0], 0.5996094f, 1e-6f);
    EXPECT_NEAR(vmath(Wrap, {12345.6f, 0, 0}, {0.7f, 1, 1}, {-0.3f, 0, 0}, 1, 2)[0], 0.5994141f, 1e-6f);
}

// ---- Map Range and Clamp ----------------------------------------------------------------------

float map_float(int interpolation, bool clamp, float v, float fmin, float fmax, float tmin, float tmax,
                float steps = 4) {
    OneNode n{node_type("map_range"),
              {0, interpolation, clamp ? 1 : 0},
              {{v}, {fmin}, {fmax}, {tmin}, {tmax}, {steps}},
              {1},
              {}};
    return n.run()[0];
}

TEST(VectorNodes, MapRangeFloat) {
    EXPECT_NEAR(map_float(0, false, 0.25f, 0, 1, 10, 20), 12.5f, 1e-5f);
    // Stepped, 4 steps: floor(0.3 * 5) / 4 = 0.25.
    EXPECT_NEAR(map_float(1, false, 0.3f, 0, 1, 10, 20), 12.5f, 1e-5f);
    EXPECT_NEAR(map_float(1, false, 0.3f, 0, 1, 10, 20, 0), 10.0f, 1e-5f);  // no steps: factor 0
    // Smoothstep 3t^2 - 2t^3 at 0.25: 0.15625; smootherstep 6t^5 - 15t^4 + 10t^3: 0.103515625.
    EXPECT_NEAR(map_float(2, false, 0.25f, 0, 1, 10, 20), 11.5625f, 1e-5f);
    EXPECT_NEAR(map_float(3, false, 0.25f, 0, 1, 10, 20), 11.03515625f, 1e-5f);
    // Reversed source range: 1 - smoothstep(0, 1, 0.25).
    EXPECT_NEAR(map_float(2, false, 0.25f, 1, 0, 10, 20), 18.4375f, 1e-5f);
    EXPECT_NEAR(map_float(3, false, 0.25f, 1, 0, 10, 20), 20.0f - 1.03515625f, 1e-5f);
    // Clamp to the target range in either order.
    EXPECT_NEAR(map_float(0, false, 1.5f, 0, 1, 10, 20), 25.0f, 1e-5f);
    EXPECT_NEAR(map_float(0, true, 1.5f, 0, 1, 10, 20), 20.0f, 1e-5f);
    EXPECT_NEAR(map_float(0, true, 1.5f, 0, 1, 20, 10), 10.0f, 1e-5f);
    // An empty source range maps to 0, which Cycles' clamp then takes into the target range.
    EXPECT_EQ(map_float(0, false, 0.5f, 1, 1, 10, 20), 0.0f);
    EXPECT_EQ(map_float(0, true, 0.5f, 1, 1, 10, 20), 10.0f);
}

TEST(VectorNodes, MapRangeVector) {
    const auto run = [](int interpolation, bool clamp, Values v) {
        OneNode n{node_type("map_range"),
                  {1, interpolation, clamp ? 1 : 0},
                  {v, {0, 0, 1}, {1, 2, 1}, {10, 0, 5}, {20, -4, 6}, {4, 4, 4}},
                  {3},
                  {}};
        return n.run();
    };
    // Per component: [0,1] -> [10,20], [0,2] -> [0,-4], and an empty range gives To Min.
    expect_near(run(0, false, {0.25f, 3, 7}), {12.5f, -6, 5});
    expect_near(run(0, true, {0.25f, 3, 7}), {12.5f, -4, 5});
    expect_near(run(1, false, {0.3f, 1, 7}), {12.5f, -2, 5});
    // Smooth interpolations clamp the factor, never the result.
    expect_near(run(2, true, {0.25f, 3, 7}), {11.5625f, -4, 5});
    expect_near(run(3, false, {0.25f, -1, 7}), {11.03515625f, 0, 5});
}

TEST(VectorNodes, Clamp) {
    const auto run = [](int type, float v, float lo, float hi) {
        return OneNode{node_type("clamp"), {type}, {{v}, {lo}, {hi}}, {1}, {}}.run()[0];
    };
    EXPECT_EQ(run(0, 2, 0, 1), 1.0f);
    EXPECT_EQ(run(0, -2, 0, 1), 0.0f);
    EXPECT_EQ(run(0, 0.25f, 0, 1), 0.25f);
    EXPECT_EQ(run(0, 5, 3, 1), 1.0f);  // min(max(5, 3), 1)
    EXPECT_EQ(run(1, 5, 3, 1), 3.0f);  // RANGE swaps reversed bounds
    EXPECT_EQ(run(1, 0, 3, 1), 1.0f);
}

// ---- Mapping, Vector Rotate, Vector Transform -------------------------------------------------

Values mapping(int type, Values v, Values loc, Values rot, Values scale) {
    return OneNode{node_type("mapping"), {type}, {v, loc, rot, scale}, {3}, {}}.run();
}

TEST(VectorNodes, MappingTypes) {
    const Values rz90 = {0, 0, kPiF / 2};
    // Point: scale, rotate (z 90 degrees: (x, y) -> (-y, x)), then translate.
    expect_near(mapping(0, {1, 2, 3}, {10, 0, 0}, rz90, {2, 1, 1}), {8, 2, 3});
    // Texture is the inverse of Point.
    expect_near(mapping(1, {8, 2, 3}, {10, 0, 0}, rz90, {2, 1, 1}), {1, 2, 3});
    expect_near(mapping(1, {8, 2, 3}, {10, 0, 0}, rz90, {2, 0, 1}), {1, 0, 3});  // / 0 gives 0
    // Vector ignores the location.
    expect_near(mapping(2, {1, 2, 3}, {10, 0, 0}, rz90, {2, 1, 1}), {-2, 2, 3});
    // Normal divides by the scale and normalises.
    expect_near(mapping(3, {1, 0, 0}, {10, 0, 0}, rz90, {2, 1, 1}), {0, 1, 0});
    expect_near(mapping(3, {0, 0, 0}, {0, 0, 0}, rz90, {1, 1, 1}), {0, 0, 0});
}

TEST(VectorNodes, MappingEulerOrderIsXThenYThenZ) {
    // R = Rz Ry Rx: with x = z = 90 degrees, +Y goes to +Z (Rx) and stays; +Z goes to -Y, then +X.
    const Values r = {kPiF / 2, 0, kPiF / 2};
    expect_near(mapping(2, {0, 1, 0}, {0, 0, 0}, r, {1, 1, 1}), {0, 0, 1});
    expect_near(mapping(2, {0, 0, 1}, {0, 0, 0}, r, {1, 1, 1}), {1, 0, 0});
    // y = 90 degrees: +X goes to -Z.
    expect_near(mapping(2, {1, 0, 0}, {0, 0, 0}, {0, kPiF / 2, 0}, {1, 1, 1}), {0, 0, -1});
}

Values rotate(int type, bool invert, Values v, Values center, Values axis, float angle, Values euler) {
    return OneNode{
        node_type("vector_rotate"), {type, invert ? 1 : 0}, {v, center, axis, {angle}, euler}, {3}, {}}
        .run();
}

TEST(VectorNodes, VectorRotate) {
    const float q = kPiF / 2;
    // About a non-unit axis through a centre.
    expect_near(rotate(0, false, {2, 0, 0}, {1, 0, 0}, {0, 0, 2}, q, {}), {1, 1, 0});
    expect_near(rotate(0, true, {2, 0, 0}, {1, 0, 0}, {0, 0, 2}, q, {}), {1, -1, 0});
    expect_near(rotate(0, false, {2, 5, 0}, {1, 0, 0}, {0, 0, 0}, q, {}), {2, 5, 0});  // zero axis
    // A 120 degree turn about (1,1,1) cycles the axes.
    expect_near(rotate(0, false, {1, 0, 0}, {0, 0, 0}, {1, 1, 1}, 2 * kPiF / 3, {}), {0, 1, 0});
    expect_near(rotate(1, false, {0, 1, 0}, {0, 0, 0}, {0, 0, 1}, q, {}), {0, 0, 1});
    expect_near(rotate(2, false, {0, 0, 1}, {0, 0, 0}, {0, 0, 1}, q, {}), {1, 0, 0});
    expect_near(rotate(3, false, {1, 0, 0}, {0, 0, 0}, {1, 0, 0}, q, {}), {0, 1, 0});
    expect_near(rotate(3, true, {1, 0, 0}, {0, 0, 0}, {1, 0, 0}, q, {}), {0, -1, 0});
    expect_near(rotate(4, false, {2, 0, 0}, {1, 0, 0}, {}, 0, {0, 0, q}), {1, 1, 0});
    expect_near(rotate(4, true, {2, 0, 0}, {1, 0, 0}, {}, 0, {0, 0, q}), {1, -1, 0});
    expect_near(rotate(4, false, {0, 0, 1}, {0, 0, 0}, {}, 0, {q, 0, q}), {1, 0, 0});
}

TEST(VectorNodes, VectorTransformBetweenEqualSpaces) {
    const auto run = [](int type, int space, int revision) {
        return OneNode{node_type("vector_transform"), {type, space, space, revision}, {{0, 0, 2}}, {3}, {}}
            .run();
    };
    for (int space = 0; space < 3; ++space) {
        expect_near(run(0, space, 0), {0, 0, 2});
        expect_near(run(1, space, 1), {0, 0, 2});
        expect_near(run(2, space, 0), {0, 0, 1});  // before 4.0 a normal is normalised
        expect_near(run(2, space, 1), {0, 0, 2});
    }
    const std::string e =
        OneNode{node_type("vector_transform"), {0, 0, 1, 1}, {{0, 0, 2}}, {3}, {}}.rejection();
    EXPECT_NE(e.find("vector_transform"), std::string::npos) << e;
    EXPECT_NE(e.find("mode 1 (from)"), std::string::npos) << e;
}

// ---- Fresnel, Layer Weight, Normal ------------------------------------------------------------

// The Fresnel equations with Snell's law, for a ray from outside (n1 = 1) into n2 = eta.
float fresnel_closed_form(float cos_i, float eta) {
    const float sin_t = std::sqrt(1 - cos_i * cos_i) / eta;
    if (sin_t >= 1) return 1;
    const float cos_t = std::sqrt(1 - sin_t * sin_t);
    const float rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    const float rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    return 0.5f * (rs * rs + rp * rp);
}

float fresnel(float ior, Values normal, Values incoming, float backfacing) {
    return OneNode{node_type("fresnel"), {}, {{ior}, normal, incoming, {backfacing}}, {1}, {}}.run()[0];
}

TEST(VectorNodes, Fresnel) {
    EXPECT_NEAR(fresnel(1.5f, {0, 0, 1}, {0, 0, 1}, 0), 0.04f, 1e-6f);
    EXPECT_NEAR(fresnel(1.5f, {0, 0, 1}, {0, 0, 1}, 1), 0.04f, 1e-6f);  // 1/1.5 at normal incidence
    const float c = 0.5f, s = std::sqrt(0.75f);
    EXPECT_NEAR(fresnel(1.5f, {0, 0, 1}, {s, 0, c}, 0), fresnel_closed_form(c, 1.5f), 1e-6f);
    EXPECT_NEAR(fresnel(1.33f, {0, 0, 2}, {s, 0, c}, 0), fresnel_closed_form(2 * c, 1.33f), 1e-5f)
        << "the node's normal is used as given";
    // Leaving glass at 60 degrees from the normal: total internal reflection.
    EXPECT_EQ(fresnel(1.5f, {0, 0, 1}, {s, 0, c}, 1), 1.0f);
    // IOR below 1e-5 is raised to it: almost total reflection.
    EXPECT_GT(fresnel(-3.0f, {0, 0, 1}, {0, 0, 1}, 0), 0.999f);
}

TEST(VectorNodes, LayerWeight) {
    const auto run = [](float blend, Values incoming, float backfacing) {
        return OneNode{
            node_type("layer_weight"), {}, {{blend}, {0, 0, 1}, incoming, {backfacing}}, {1, 1}, {}}
            .run();
    };
    const float c = 0.5f, s = std::sqrt(0.75f);
    // Blend 0.5: IOR 1 / (1 - 0.5) = 2; at normal incidence ((2 - 1) / 3)^2 = 1/9. Facing 1 - |cos|.
    expect_near(run(0.5f, {0, 0, 1}, 0), {1.0f / 9, 0});
    expect_near(run(0.5f, {s, 0, c}, 0), {fresnel_closed_form(c, 2), 0.5f});
    // Back face: IOR 1 - blend = 0.5, the same at normal incidence.
    expect_near(run(0.5f, {0, 0, 1}, 1), {1.0f / 9, 0});
    // Facing's exponent: 2 blend below 0.5, 0.5 / (1 - blend) above.
    EXPECT_NEAR(run(0.25f, {s, 0, c}, 0)[1], 1 - std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(run(0.75f, {s, 0, c}, 0)[1], 0.75f, 1e-6f);
    EXPECT_NEAR(run(0.0f, {s, 0, c}, 0)[1], 0.0f, 1e-6f);  // exponent 0
}

TEST(VectorNodes, NormalNode) {
    const Values out = OneNode{node_type("normal"), {}, {{0, 3, 3}, {0, 0, 2}}, {3, 1}, {}}.run();
    expect_near(out, {0, 0, 1, 1 / std::sqrt(2.0f)});
}

// ---- Blackbody and Wavelength -----------------------------------------------------------------

const Values kIdentity = {1, 0, 0, 0, 1, 0, 0, 0, 1};

Values blackbody(float t, Values m = kIdentity) {
    return OneNode{node_type("blackbody"), {}, {{t}}, {3}, m}.run();
}

Values wavelength(float nm, Values m = kIdentity) {
    return OneNode{node_type("wavelength"), {}, {{nm}}, {3}, m}.run();
}

TEST(VectorNodes, Blackbody) {
    expect_near(blackbody(12000), {0.8262955f, 0.9945081f, 1.5663077f});
    expect_near(blackbody(50000), {0.8262955f, 0.9945081f, 1.5663077f});
    expect_near(blackbody(500), {5.4132945f, 0, 0});  // green and blue clamped at 0
    // 1000 K, the band from 965 K: red 2488.45471/t - 1.11330907e-3 t + 3.22621544 = 4.60136108,
    // green 0.03904196, blue a negative cubic, clamped.
    expect_near(blackbody(1000), {4.60136108f, 0.03904196f, 0}, 1e-4f);
    // The fit is continuous across its bands (each within 0.5%) and about white near 6500 K.
    for (float edge : {965.0f, 1167.0f, 1449.0f, 1902.0f, 3315.0f, 6365.0f}) {
        const Values below = blackbody(edge - 0.01f), above = blackbody(edge);
        for (int k = 0; k < 3; ++k)
            EXPECT_NEAR(below[k], above[k], 5e-3f * std::fmax(above[k], 0.1f)) << edge;
    }
    const Values d65 = blackbody(6500);
    EXPECT_NEAR(d65[0] / d65[1], 1.0f, 0.1f);
    EXPECT_NEAR(d65[2] / d65[1], 1.0f, 0.1f);
    // The matrix takes the colour to the working space (here: channels swapped), then >= 0.
    expect_near(blackbody(12000, {0, 0, 1, 0, 1, 0, 1, 0, 0}), {1.5663077f, 0.9945081f, 0.8262955f});
    expect_near(blackbody(12000, {-1, 0, 0, 0, 1, 0, 0, 0, 1}), {0, 0.9945081f, 1.5663077f});
}

TEST(VectorNodes, Wavelength) {
    const float k = 1.0f / 2.52f;
    // CIE 1931 at 555 nm: x 0.5121, y 1.0000, z 0.0057; at 380 nm: 0.0014, 0, 0.0065.
    expect_near(wavelength(555), {0.5121f * k, 1.0f * k, 0.0057f * k});
    expect_near(wavelength(380), {0.0014f * k, 0, 0.0065f * k});
    // Halfway between 380 and 385 nm (385: 0.0022, 0.0001, 0.0105).
    expect_near(wavelength(382.5f), {0.0018f * k, 0.00005f * k, 0.0085f * k});
    expect_near(wavelength(780), {0, 0, 0});
    expect_near(wavelength(300), {0, 0, 0});
    OneNode nan_input{node_type("wavelength"), {}, {{0}}, {3}, kIdentity};
    nan_input.first_from_renderer = true;
    nan_input.renderer_value = std::nanf("");
    expect_near(nan_input.run(), {0, 0, 0});
    expect_near(wavelength(555, {0, 1, 0, 1, 0, 0, 0, 0, 1}), {1.0f * k, 0.5121f * k, 0.0057f * k});
}

// ---- Checks -----------------------------------------------------------------------------------

TEST(VectorNodes, ChecksNameNodeAndField) {
    const auto rejected = [](OneNode n, const char* field) {
        const std::string e = n.rejection();
        EXPECT_NE(e.find(field), std::string::npos) << e;
    };
    rejected({node_type("vector_math"), {29, 0}, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {1}}, {3, 1}, {}},
             "operation");
    rejected({node_type("vector_math"), {0, 3}, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {1}}, {3, 1}, {}},
             "revision");
    rejected({node_type("map_range"), {2, 0, 0}, {{0}, {0}, {1}, {0}, {1}, {4}}, {1}, {}}, "data type");
    rejected({node_type("map_range"), {0, 4, 0}, {{0}, {0}, {1}, {0}, {1}, {4}}, {1}, {}}, "interpolation");
    rejected({node_type("map_range"), {0, 0, 2}, {{0}, {0}, {1}, {0}, {1}, {4}}, {1}, {}}, "clamp");
    // The vector form needs 3-wide registers: a float output at the end of the file is not.
    rejected({node_type("map_range"),
              {1, 0, 0},
              {{0, 0, 0}, {0, 0, 0}, {1, 1, 1}, {0, 0, 0}, {1, 1, 1}, {4, 4, 4}},
              {1},
              {}},
             "3 wide");
    rejected({node_type("clamp"), {-1}, {{0}, {0}, {1}}, {1}, {}}, "type");
    rejected({node_type("mapping"), {4}, {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {1, 1, 1}}, {3}, {}}, "type");
    rejected({node_type("vector_rotate"), {5, 0}, {{0, 0, 0}, {0, 0, 0}, {0, 0, 1}, {0}, {0, 0, 0}}, {3}, {}},
             "type");
    rejected({node_type("vector_rotate"), {0, 2}, {{0, 0, 0}, {0, 0, 0}, {0, 0, 1}, {0}, {0, 0, 0}}, {3}, {}},
             "invert");
    rejected({node_type("vector_transform"), {3, 0, 0, 0}, {{0, 0, 0}}, {3}, {}}, "type");
    rejected({node_type("blackbody"), {}, {{1000}}, {3}, {1, 0, 0}}, "data count");
    rejected({node_type("wavelength"), {}, {{500}}, {3}, {}}, "data count");
}

}  // namespace
