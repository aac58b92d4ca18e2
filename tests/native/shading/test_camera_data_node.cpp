// Camera Data (shading/nodes/camera_data_node.cpp) through the C ABI: its outputs on given
// camera-space points, and rendered, where the renderer's CAMERA input feeds it.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <cmath>
#include <vector>

#include "node_types.h"
#include "render_helpers.h"
#include "scene_handle.h"

namespace {

using stratum_test::node_type;

constexpr uint32_t kInputs = STRATUM_SHADER_INPUT_REGISTERS;

// One Camera Data node reading the renderer's CAMERA input; its outputs are registers
// kInputs .. kInputs + 4: view vector (3), view z depth, view distance.
StratumStatus add_camera_data(StratumScene* scene) {
    StratumShaderNode node{};
    node.type = node_type("camera_data");
    node.inputs[0] = STRATUM_INPUT_CAMERA;
    node.outputs[0] = kInputs;
    node.outputs[1] = kInputs + 3;
    node.outputs[2] = kInputs + 4;
    const std::vector<float> registers(kInputs + 5, 0.0f);
    const StratumShaderProgramDesc desc{&node,   1, registers.data(), static_cast<uint32_t>(registers.size()),
                                        nullptr, 0};
    return stratum_scene_add_shader_program(scene, &desc, nullptr);
}

std::vector<float> evaluate_at(float x, float y, float z) {
    stratum_test::SceneHandle h;
    EXPECT_EQ(add_camera_data(h.scene), STRATUM_OK) << stratum_last_error();
    std::vector<float> inputs(kInputs, 0.0f);
    inputs[STRATUM_INPUT_CAMERA] = x;
    inputs[STRATUM_INPUT_CAMERA + 1] = y;
    inputs[STRATUM_INPUT_CAMERA + 2] = z;
    std::vector<float> out(5, -9.0f);
    EXPECT_EQ(stratum_scene_evaluate_program(h.scene, 0, inputs.data(), kInputs, 5, out.data()), STRATUM_OK);
    return out;
}

TEST(CameraDataNode, IsTheDirectionDepthAndDistanceOfTheCameraSpacePoint) {
    // (3, 4, 12) is 13 from the camera: each division and the square root are exact.
    const std::vector<float> out = evaluate_at(3.0f, 4.0f, 12.0f);
    EXPECT_EQ(out[0], 3.0f / 13.0f);
    EXPECT_EQ(out[1], 4.0f / 13.0f);
    EXPECT_EQ(out[2], 12.0f / 13.0f);
    EXPECT_EQ(out[3], 12.0f);
    EXPECT_EQ(out[4], 13.0f);
    // Behind the camera the depth is negative and the vector points backwards.
    const std::vector<float> behind = evaluate_at(0.0f, 0.0f, -2.0f);
    EXPECT_EQ(behind[2], -1.0f);
    EXPECT_EQ(behind[3], -2.0f);
    EXPECT_EQ(behind[4], 2.0f);
}

TEST(CameraDataNode, AtTheCameraCentreTheVectorIsNaNAsInCycles) {
    const std::vector<float> out = evaluate_at(0.0f, 0.0f, 0.0f);
    EXPECT_TRUE(std::isnan(out[0]) && std::isnan(out[1]) && std::isnan(out[2]));
    EXPECT_EQ(out[3], 0.0f);
    EXPECT_EQ(out[4], 0.0f);
}

// A square 3 in front of a perspective camera, its emission (view vector z, view z depth, view
// distance) from the node at each pixel's centre: the depth is 3 everywhere, the distance 3 / cos
// of the angle off the axis, and vector z times distance is the depth again.
TEST(CameraDataNode, ReadsTheRenderersCameraSpaceAtEachPixel) {
    stratum_test::SceneHandle h;
    StratumMaterialDesc m = stratum_test::diffuse_grey(0.0f);
    m.model = STRATUM_MATERIAL_EMISSION;
    ASSERT_EQ(stratum_scene_add_material(h.scene, &m, nullptr), STRATUM_OK);
    ASSERT_TRUE(stratum_test::add_square_instance(h.scene, 0.0f, 10.0f, 0));
    ASSERT_EQ(add_camera_data(h.scene), STRATUM_OK) << stratum_last_error();
    constexpr int kSize = 8;
    const stratum_test::RenderOutput out = stratum_test::render_pixel_centres(
        h.scene, kInputs + 2, kSize, stratum_test::CentreView::kPerspective);
    ASSERT_TRUE(out.error.empty()) << out.error;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const float* px = &out.rgba[(static_cast<size_t>(y) * kSize + x) * 4];
            // 90 degrees across 8 pixels: the pixel centre's direction is (u, v, 1) on the plane
            // one unit ahead, u = (x + 0.5) / 4 - 1. The sample lies within 0.005 px of it in x
            // and y, where the distance changes by at most 3 x 0.25 per pixel in each: 7.5e-3.
            const double u = (x + 0.5) / 4.0 - 1.0, v = (y + 0.5) / 4.0 - 1.0;
            const double distance = 3.0 * std::sqrt(u * u + v * v + 1.0);
            EXPECT_NEAR(px[1], 3.0, 1e-5) << x << "," << y;
            EXPECT_NEAR(px[2], distance, 7.5e-3) << x << "," << y;
            EXPECT_NEAR(px[0] * px[2], px[1], 1e-5) << x << "," << y;
        }
    }
}

}  // namespace
