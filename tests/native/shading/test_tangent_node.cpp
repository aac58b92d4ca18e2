// Tangent (shading/nodes/tangent_node.cpp) through the C ABI: the radial tangents about each
// axis, taken to world space as normals are, the UV map's tangent projected into the shading
// plane, and rendered, where the renderer's inputs feed it (radial Z against the renderer's own
// Geometry Tangent, which the agreement tests hold to Cycles; a mesh's MikkTSpace tangents).
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <array>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "node_types.h"
#include "render_helpers.h"
#include "scene_handle.h"

namespace {

using stratum_test::node_type;
using Vec = std::array<float, 3>;

constexpr uint32_t kInputs = STRATUM_SHADER_INPUT_REGISTERS;
constexpr int32_t kRadial = 0, kUvMap = 1, kX = 0, kY = 1, kZ = 2;

StratumShaderNode tangent_node(int32_t direction, int32_t axis, uint32_t out) {
    StratumShaderNode node{};
    node.type = node_type("tangent");
    node.modes[0] = direction;
    node.modes[1] = axis;
    const uint32_t inputs[6] = {STRATUM_INPUT_GENERATED,
                                STRATUM_INPUT_NORMAL,
                                STRATUM_INPUT_NORMAL_TRANSFORM,
                                STRATUM_INPUT_NORMAL_TRANSFORM + 3,
                                STRATUM_INPUT_NORMAL_TRANSFORM + 6,
                                STRATUM_INPUT_MIKKTSPACE_TANGENT};
    std::copy(inputs, inputs + 6, node.inputs);
    node.outputs[0] = out;
    return node;
}

struct At {
    Vec generated{0.5f, 0.5f, 0.5f};
    Vec normal{0.0f, 0.0f, 1.0f};
    std::array<Vec, 3> transform{Vec{1, 0, 0}, Vec{0, 1, 0}, Vec{0, 0, 1}};
    Vec mikktspace{0.0f, 0.0f, 0.0f};
};

Vec tangent(int32_t direction, int32_t axis, const At& at) {
    stratum_test::SceneHandle h;
    const StratumShaderNode node = tangent_node(direction, axis, kInputs);
    const std::vector<float> registers(kInputs + 3, 0.0f);
    const StratumShaderProgramDesc desc{&node,   1, registers.data(), static_cast<uint32_t>(registers.size()),
                                        nullptr, 0};
    EXPECT_EQ(stratum_scene_add_shader_program(h.scene, &desc, nullptr), STRATUM_OK) << stratum_last_error();
    std::vector<float> in(kInputs, 0.0f);
    const auto put = [&](uint32_t first, Vec v) { std::copy(v.begin(), v.end(), in.begin() + first); };
    put(STRATUM_INPUT_GENERATED, at.generated);
    put(STRATUM_INPUT_NORMAL, at.normal);
    for (uint32_t k = 0; k < 3; ++k) put(STRATUM_INPUT_NORMAL_TRANSFORM + 3 * k, at.transform[k]);
    put(STRATUM_INPUT_MIKKTSPACE_TANGENT, at.mikktspace);
    Vec out{-9.0f, -9.0f, -9.0f};
    EXPECT_EQ(stratum_scene_evaluate_program(h.scene, 0, in.data(), kInputs, 3, out.data()), STRATUM_OK);
    return out;
}

void expect_near(Vec got, Vec want, float tolerance = 1e-6f) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(got[k], want[k], tolerance) << "component " << k;
}

TEST(TangentNode, RadialTangentsCircleEachAxisThroughTheTextureSpacesCentre) {
    // About Z at generated (0.8, 0.5, 0.3): (-(0.5 - 0.5), 0.8 - 0.5, 0) = (0, 0.3, 0).
    expect_near(tangent(kRadial, kZ, {{0.8f, 0.5f, 0.3f}, {0, 0, 1}}), {0, 1, 0});
    // About X at (0.5, 0.8, 0.5): (0, 0, 0.3), in the plane of the normal +X.
    expect_near(tangent(kRadial, kX, {{0.5f, 0.8f, 0.5f}, {1, 0, 0}}), {0, 0, 1});
    // About Y at (0.8, 0.5, 0.5): (0, 0, 0.3), in the plane of the normal +Y.
    expect_near(tangent(kRadial, kY, {{0.8f, 0.5f, 0.5f}, {0, 1, 0}}), {0, 0, 1});
    // A tangent out of the shading plane is projected into it: about Z at (0.8, 0.5, 0.3) with
    // the normal tilted toward +Y, (0, 0.3, 0) loses its part along the normal.
    const float s = std::sqrt(0.5f);
    expect_near(tangent(kRadial, kZ, {{0.8f, 0.5f, 0.3f}, {0, s, s}}), {0, s, -s});
}

// M = R(0.7) S(2, 0.5): the normal transform M^-T = R S^-1 takes the object's axes to (c, s, 0) / 2,
// (-s, c, 0) / 0.5, (0, 0, 1). The radial tangent (-0.2, 0.3, 0) at generated (0.8, 0.7, 0.3)
// becomes -0.2 X + 0.3 Y, which points elsewhere than M applied to it as a vector would.
TEST(TangentNode, TheRadialTangentGoesToWorldSpaceAsANormal) {
    const float c = std::cos(0.7f), s = std::sin(0.7f);
    At at{{0.8f, 0.7f, 0.3f}, {0, 0, 1}, {Vec{c / 2, s / 2, 0}, Vec{-s / 0.5f, c / 0.5f, 0}, Vec{0, 0, 1}}};
    const float wx = -0.2f * c / 2 + 0.3f * -s / 0.5f, wy = -0.2f * s / 2 + 0.3f * c / 0.5f;
    const float l = std::sqrt(wx * wx + wy * wy);
    expect_near(tangent(kRadial, kZ, at), {wx / l, wy / l, 0.0f});
}

TEST(TangentNode, TheUvMapsTangentIsProjectedIntoTheShadingPlane) {
    At at;
    at.mikktspace = {2.0f, 0.0f, 1.0f};
    expect_near(tangent(kUvMap, kZ, at), {1, 0, 0});
    // The generated point, the axis and the transform play no part.
    at.generated = {0.9f, 0.1f, 0.4f};
    at.transform = {Vec{0, 3, 0}, Vec{5, 0, 0}, Vec{0, 0, 7}};
    expect_near(tangent(kUvMap, kX, at), {1, 0, 0});
}

TEST(TangentNode, AMeshWithoutTangentsGivesZeroAsCyclesMissingAttribute) {
    const Vec out = tangent(kUvMap, kZ, At{});
    EXPECT_EQ(out, (Vec{0.0f, 0.0f, 0.0f}));
}

TEST(TangentNode, RefusesUnknownModes) {
    stratum_test::SceneHandle h;
    for (const auto& [direction, axis, message] :
         {std::tuple{2, 0, "mode 0 (direction) is 2"}, std::tuple{0, 3, "mode 1 (axis) is 3"}}) {
        const StratumShaderNode node = tangent_node(direction, axis, kInputs);
        const std::vector<float> registers(kInputs + 3, 0.0f);
        const StratumShaderProgramDesc desc{
            &node, 1, registers.data(), static_cast<uint32_t>(registers.size()), nullptr, 0};
        EXPECT_EQ(stratum_scene_add_shader_program(h.scene, &desc, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(stratum_last_error()).find(message), std::string::npos) << stratum_last_error();
    }
}

// The square [-half, half]² placed by `matrix`, seen by a 16 x 16 orthographic camera over
// [-1, 1]²; `program` drives its emission from register kInputs. Returns the pixels' RGBA.
std::vector<float> render_square(float half, const float (&matrix)[16], const float* corner_tangents,
                                 const std::vector<StratumShaderNode>& program) {
    stratum_test::SceneHandle h;
    StratumMaterialDesc m = stratum_test::diffuse_grey(0.0f);
    m.model = STRATUM_MATERIAL_EMISSION;
    EXPECT_EQ(stratum_scene_add_material(h.scene, &m, nullptr), STRATUM_OK);
    const float corners[12] = {-half, -half, 0, half, -half, 0, half, half, 0, -half, half, 0};
    const uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
    const uint32_t materials[] = {0, 0};
    StratumMeshDesc mesh{corners, 4, triangles, 2, nullptr, nullptr, materials};
    mesh.corner_tangents = corner_tangents;
    uint32_t mesh_id = 0;
    EXPECT_EQ(stratum_scene_add_mesh(h.scene, &mesh, &mesh_id), STRATUM_OK) << stratum_last_error();
    EXPECT_EQ(stratum_scene_add_instance(h.scene, mesh_id, matrix), STRATUM_OK) << stratum_last_error();
    const std::vector<float> registers(kInputs + 8, 0.0f);
    const StratumShaderProgramDesc desc{program.data(),   static_cast<uint32_t>(program.size()),
                                        registers.data(), static_cast<uint32_t>(registers.size()),
                                        nullptr,          0};
    EXPECT_EQ(stratum_scene_add_shader_program(h.scene, &desc, nullptr), STRATUM_OK) << stratum_last_error();
    const stratum_test::RenderOutput out =
        stratum_test::render_pixel_centres(h.scene, kInputs, 16, stratum_test::CentreView::kOrthographic);
    EXPECT_TRUE(out.error.empty()) << out.error;
    return out.rgba;
}

// Radial Z from the renderer's generated point, normal and normal transform is the renderer's
// Geometry Tangent (computed apart, the same formula): a unit vector, and their difference 0, at
// every pixel of a square turned and scaled unevenly (M = R(0.7) S(0.6, 0.9)) that fills the view.
TEST(TangentNode, RenderedRadialZIsTheGeometryTangent) {
    const float c = std::cos(0.7f), s = std::sin(0.7f);
    const float matrix[16] = {0.6f * c, -0.9f * s, 0, 0, 0.6f * s, 0.9f * c, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const std::vector<float> tangent =
        render_square(10.0f, matrix, nullptr, {tangent_node(kRadial, kZ, kInputs)});
    StratumShaderNode subtract{};
    subtract.type = node_type("vector_math");
    subtract.modes[0] = 1;  // SUBTRACT
    subtract.inputs[0] = kInputs + 3;
    subtract.inputs[1] = STRATUM_INPUT_TANGENT;
    subtract.inputs[2] = kInputs + 3;
    subtract.inputs[3] = kInputs + 6;
    subtract.outputs[0] = kInputs;
    subtract.outputs[1] = kInputs + 7;
    const std::vector<float> difference =
        render_square(10.0f, matrix, nullptr, {tangent_node(kRadial, kZ, kInputs + 3), subtract});
    for (size_t p = 0; p < 256; ++p) {
        const float* t = &tangent[p * 4];
        EXPECT_NEAR(t[0] * t[0] + t[1] * t[1] + t[2] * t[2], 1.0f, 1e-6f) << p;
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(difference[p * 4 + k], 0.0f, 1e-6f) << p;
    }
}

// Corner tangents (2, 1, 0.5) everywhere on a flat square seen straight on: the node gives their
// projection into the plane, (2, 1, 0) / sqrt 5, at every pixel; without tangents, 0.
TEST(TangentNode, RenderedUvMapIsTheMeshsMikktspaceTangentInThePlane) {
    std::vector<float> tangents;
    for (int corner = 0; corner < 6; ++corner) tangents.insert(tangents.end(), {2.0f, 1.0f, 0.5f, 1.0f});
    const float r5 = std::sqrt(5.0f);
    for (const bool with_tangents : {true, false}) {
        const std::vector<float> rgba =
            render_square(1.0f, stratum_test::kIdentity, with_tangents ? tangents.data() : nullptr,
                          {tangent_node(kUvMap, kZ, kInputs)});
        for (size_t p = 0; p < rgba.size() / 4; ++p) {
            EXPECT_NEAR(rgba[p * 4], with_tangents ? 2.0f / r5 : 0.0f, 1e-6f) << p;
            EXPECT_NEAR(rgba[p * 4 + 1], with_tangents ? 1.0f / r5 : 0.0f, 1e-6f) << p;
            EXPECT_NEAR(rgba[p * 4 + 2], 0.0f, 1e-6f) << p;
        }
    }
}

}  // namespace
