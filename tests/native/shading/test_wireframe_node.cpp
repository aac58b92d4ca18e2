// Wireframe (shading/nodes/wireframe_node.cpp) through the C ABI: distances to a triangle's
// edges in world units and in pixels (with an oblique view), no wire without a triangle, and a
// render where the renderer's position, triangle and footprint feed it.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "node_types.h"
#include "render_helpers.h"
#include "scene_handle.h"

namespace {

using stratum_test::node_type;

constexpr uint32_t kInputs = STRATUM_SHADER_INPUT_REGISTERS;

// One Wireframe node on the renderer's inputs (position, true normal, incoming, footprint,
// triangle) with Size in register kInputs; Fac in kInputs + 1.
StratumStatus add_wireframe(StratumScene* scene, float size, int32_t use_pixel_size) {
    StratumShaderNode node{};
    node.type = node_type("wireframe");
    node.modes[0] = use_pixel_size;
    const uint32_t inputs[8] = {STRATUM_INPUT_POSITION,        kInputs,
                                STRATUM_INPUT_TRUE_NORMAL,     STRATUM_INPUT_INCOMING,
                                STRATUM_INPUT_PIXEL_FOOTPRINT, STRATUM_INPUT_TRIANGLE,
                                STRATUM_INPUT_TRIANGLE + 3,    STRATUM_INPUT_TRIANGLE + 6};
    std::copy(inputs, inputs + 8, node.inputs);
    node.outputs[0] = kInputs + 1;
    std::vector<float> registers(kInputs + 2, 0.0f);
    registers[kInputs] = size;
    const StratumShaderProgramDesc desc{&node,   1, registers.data(), static_cast<uint32_t>(registers.size()),
                                        nullptr, 0};
    return stratum_scene_add_shader_program(scene, &desc, nullptr);
}

struct Point {
    float position[3];
    float incoming[3] = {0.0f, 0.0f, 1.0f};
    float footprint = 0.0f;
};

// Fac at `p` on the triangle (0, 0, 0), (1, 0, 0), (0, 1, 0) of normal +Z.
float fac(float size, int32_t use_pixel_size, const Point& p, bool triangle = true) {
    stratum_test::SceneHandle h;
    EXPECT_EQ(add_wireframe(h.scene, size, use_pixel_size), STRATUM_OK) << stratum_last_error();
    std::vector<float> in(kInputs, 0.0f);
    std::copy(p.position, p.position + 3, in.begin() + STRATUM_INPUT_POSITION);
    in[STRATUM_INPUT_TRUE_NORMAL + 2] = 1.0f;
    std::copy(p.incoming, p.incoming + 3, in.begin() + STRATUM_INPUT_INCOMING);
    in[STRATUM_INPUT_PIXEL_FOOTPRINT] = p.footprint;
    if (triangle) {
        in[STRATUM_INPUT_TRIANGLE + 3] = 1.0f;      // vertex 1 (1, 0, 0)
        in[STRATUM_INPUT_TRIANGLE + 6 + 1] = 1.0f;  // vertex 2 (0, 1, 0)
    }
    float out = -9.0f;
    EXPECT_EQ(stratum_scene_evaluate_program(h.scene, 0, in.data(), kInputs + 1, 1, &out), STRATUM_OK);
    return out;
}

TEST(WireframeNode, MarksPointsWithinHalfTheSizeOfAnEdge) {
    // Size 0.2: within 0.1 of an edge's line.
    EXPECT_EQ(fac(0.2f, 0, {{0.5f, 0.05f, 0.0f}}), 1.0f);   // 0.05 from the edge along x
    EXPECT_EQ(fac(0.2f, 0, {{0.05f, 0.5f, 0.0f}}), 1.0f);   // 0.05 from the edge along y
    EXPECT_EQ(fac(0.2f, 0, {{0.45f, 0.45f, 0.0f}}), 1.0f);  // 0.1 / sqrt 2 from the hypotenuse
    EXPECT_EQ(fac(0.2f, 0, {{0.3f, 0.3f, 0.0f}}), 0.0f);    // 0.3, 0.3 and 0.28 from the three
    EXPECT_EQ(fac(0.2f, 0, {{0.5f, 0.15f, 0.0f}}), 0.0f);
    // The footprint is not read in world units.
    Point far_footprint{{0.3f, 0.3f, 0.0f}};
    far_footprint.footprint = 100.0f;
    EXPECT_EQ(fac(0.2f, 0, far_footprint), 0.0f);
}

// In pixels the width is the footprint times Size / 2, narrowed where the view is oblique: with
// the surface's axes (a, b) from make_orthonormals(+Z) = ((1, -1, 0), (1, 1, 0)) / sqrt 2 and the
// view tilted 60 degrees about x, each axis keeps sqrt(1 - sin² 60 / 2) = 0.7906 of its length.
TEST(WireframeNode, InPixelsTheWidthIsTheFootprintAcrossTheView) {
    Point p{{0.5f, 0.04f, 0.0f}};
    p.footprint = 0.1f;  // size 1: 0.05 wide, seen straight on
    EXPECT_EQ(fac(1.0f, 1, p), 1.0f);
    p.position[1] = 0.06f;
    EXPECT_EQ(fac(1.0f, 1, p), 0.0f);
    const float s = std::sin(1.0471976f), c = std::cos(1.0471976f);
    Point oblique{{0.5f, 0.038f, 0.0f}, {0.0f, s, c}, 0.1f};  // 0.0395 wide
    EXPECT_EQ(fac(1.0f, 1, oblique), 1.0f);
    oblique.position[1] = 0.041f;
    EXPECT_EQ(fac(1.0f, 1, oblique), 0.0f);
}

TEST(WireframeNode, WithoutATriangleThereIsNoWire) {
    EXPECT_EQ(fac(1000.0f, 0, {{0.0f, 0.0f, 0.0f}}, false), 0.0f);
}

TEST(WireframeNode, RefusesAnUnknownMode) {
    stratum_test::SceneHandle h;
    EXPECT_EQ(add_wireframe(h.scene, 1.0f, 2), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("mode 0 (use pixel size) is 2"), std::string::npos)
        << stratum_last_error();
}

// The square [-1, 1]² of two triangles (diagonal from (-1, -1) to (1, 1)) fills a 16 x 16
// orthographic view: a pixel is 0.125 wide, and Size 2.5 in pixels marks points within 0.156 of
// an edge. Pixel centres lie 0.0625, 0.1875, ... from the square's sides and 0, 0.088, 0.177, ...
// from the diagonal, each at least 0.02 from that width, far more than the 0.005 px (6e-4) by
// which the sample may miss the centre.
TEST(WireframeNode, RenderedTheEdgesOfTheHitTriangleAreAPixelSizeWide) {
    stratum_test::SceneHandle h;
    StratumMaterialDesc m = stratum_test::diffuse_grey(0.0f);
    m.model = STRATUM_MATERIAL_EMISSION;
    ASSERT_EQ(stratum_scene_add_material(h.scene, &m, nullptr), STRATUM_OK);
    ASSERT_TRUE(stratum_test::add_square_instance(h.scene, 0.0f, 1.0f, 0));
    // Emission (fac, fac, fac): the node's Fac broadcast by a copy.
    StratumShaderNode nodes[2] = {};
    nodes[0].type = node_type("wireframe");
    nodes[0].modes[0] = 1;
    const uint32_t inputs[8] = {STRATUM_INPUT_POSITION,        kInputs,
                                STRATUM_INPUT_TRUE_NORMAL,     STRATUM_INPUT_INCOMING,
                                STRATUM_INPUT_PIXEL_FOOTPRINT, STRATUM_INPUT_TRIANGLE,
                                STRATUM_INPUT_TRIANGLE + 3,    STRATUM_INPUT_TRIANGLE + 6};
    std::copy(inputs, inputs + 8, nodes[0].inputs);
    nodes[0].outputs[0] = kInputs + 1;
    nodes[1].type = node_type("copy");
    nodes[1].modes[0] = 2;  // float to vector
    nodes[1].inputs[0] = kInputs + 1;
    nodes[1].outputs[0] = kInputs + 2;
    std::vector<float> registers(kInputs + 5, 0.0f);
    registers[kInputs] = 2.5f;
    const StratumShaderProgramDesc desc{nodes,   2, registers.data(), static_cast<uint32_t>(registers.size()),
                                        nullptr, 0};
    ASSERT_EQ(stratum_scene_add_shader_program(h.scene, &desc, nullptr), STRATUM_OK) << stratum_last_error();
    constexpr int kSize = 16;
    const stratum_test::RenderOutput out = stratum_test::render_pixel_centres(
        h.scene, kInputs + 2, kSize, stratum_test::CentreView::kOrthographic);
    ASSERT_TRUE(out.error.empty()) << out.error;
    int wire = 0;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const double px = (x + 0.5) / 8.0 - 1.0, py = (y + 0.5) / 8.0 - 1.0;
            const double side = 1.0 - std::max(std::abs(px), std::abs(py));
            const double diagonal = std::abs(px - py) / std::sqrt(2.0);
            const float expected = std::min(side, diagonal) < 2.5 * 0.125 / 2.0 ? 1.0f : 0.0f;
            EXPECT_EQ(out.rgba[(static_cast<size_t>(y) * kSize + x) * 4], expected) << x << "," << y;
            wire += expected == 1.0f;
        }
    }
    EXPECT_GT(wire, 60);  // the border (60 pixels) and the diagonal
}

}  // namespace
