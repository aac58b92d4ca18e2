// A lamp's emission scaled by a program (stratum_scene_set_light_program, lights/lamp_program.h),
// as Cycles shades a lamp's node tree with the distance to the lamp as the ray length: a Light
// Falloff's Linear output (strength x distance) in next-event estimation, on a camera ray that
// meets an area lamp, for a sun (Cycles' FLT_MAX), and in light tracing; the checks, removal and
// the scene file.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "node_types.h"
#include "render_helpers.h"
#include "scene_handle.h"

namespace {

using stratum_test::node_type;

constexpr uint32_t kInputs = STRATUM_SHADER_INPUT_REGISTERS;
constexpr float kStrength = 0.5f;

// Light Falloff (strength 0.5, revision `revision`) on RAY_LENGTH, its Linear output broadcast
// to RGB in kInputs + 5 .. + 7.
uint32_t add_linear_falloff(StratumScene* scene, int32_t revision = 1) {
    StratumShaderNode nodes[2] = {};
    nodes[0].type = node_type("light_falloff");
    nodes[0].modes[0] = revision;
    nodes[0].inputs[0] = kInputs;
    nodes[0].inputs[1] = kInputs + 1;
    nodes[0].inputs[2] = STRATUM_INPUT_RAY_LENGTH;
    for (uint32_t k = 0; k < 3; ++k) nodes[0].outputs[k] = kInputs + 2 + k;
    nodes[1].type = node_type("copy");
    nodes[1].modes[0] = 2;  // float to vector
    nodes[1].inputs[0] = kInputs + 3;
    nodes[1].outputs[0] = kInputs + 5;
    std::vector<float> registers(kInputs + 8, 0.0f);
    registers[kInputs] = kStrength;
    const StratumShaderProgramDesc desc{nodes,   2, registers.data(), static_cast<uint32_t>(registers.size()),
                                        nullptr, 0};
    uint32_t id = 0;
    EXPECT_EQ(stratum_scene_add_shader_program(scene, &desc, &id), STRATUM_OK) << stratum_last_error();
    return id;
}

StratumLightDesc light_at(int32_t type, float x, float y, float z, float strength) {
    StratumLightDesc l{};
    l.type = type;
    l.color[0] = l.color[1] = l.color[2] = 1.0f;
    l.strength = strength;
    l.size_x = l.size_y = 1.0f;
    std::copy(stratum_test::kIdentity, stratum_test::kIdentity + 16, l.transform);
    l.transform[3] = x;
    l.transform[7] = y;
    l.transform[11] = z;
    return l;
}

// Direct light only, 1 sample at each pixel's centre (within 0.005 px); light tracing splats each
// particle into the one pixel it lands in (a box of width 1), 4 particles per pixel.
stratum_test::Settings settings(const char* integrator, int size) {
    const bool light = std::string(integrator) == "light";
    return {{"width", size},
            {"height", size},
            {"samples", light ? 4 : 1},
            {"filter_type", "box"},
            {"filter_width", light ? 1.0 : 0.01},
            {"max_bounces", 0},
            {"integrator", integrator}};
}

// A grey plane z = 0 of half side 10 under a lamp; an orthographic camera 3 above frames [-1, 1]².
struct LitPlane {
    stratum_test::SceneHandle h;
    explicit LitPlane(const StratumLightDesc& light, bool orthographic = true) {
        const StratumMaterialDesc grey = stratum_test::diffuse_grey(0.8f);
        EXPECT_EQ(stratum_scene_add_material(h.scene, &grey, nullptr), STRATUM_OK);
        EXPECT_TRUE(stratum_test::add_square_instance(h.scene, 0.0f, 10.0f, 0));
        EXPECT_EQ(stratum_scene_add_light(h.scene, &light), STRATUM_OK) << stratum_last_error();
        StratumCameraDesc cam = stratum_test::camera_at(0.0f, 0.0f, 3.0f);
        if (orthographic) {
            cam.type = STRATUM_CAMERA_ORTHOGRAPHIC;
            cam.ortho_scale = 2.0f;
        }
        EXPECT_EQ(stratum_scene_set_camera(h.scene, &cam), STRATUM_OK);
    }
    std::vector<float> render(const stratum_test::Settings& s) {
        const stratum_test::RenderOutput out = stratum_test::render(h.scene, s);
        EXPECT_TRUE(out.error.empty()) << out.error;
        return out.rgba;
    }
};

// Next-event estimation from a point lamp 2 above the plane's centre, direct light only (1
// sample, the delta lamp sampled exactly): with the program each pixel is 0.5 t times the pixel
// without it, t the distance from the pixel's point to the lamp. Both renders take the same
// sample point, within 0.005 px (6.25e-4 in x and y) of the centre, where t changes by at most
// |x| / t <= 0.58 per unit: 0.5 x 0.58 x 8.9e-4 = 2.6e-4 on the ratio.
TEST(LampPrograms, NextEventEstimationTakesTheProgramAtTheLampsDistance) {
    LitPlane scene(light_at(STRATUM_LIGHT_POINT, 0.0f, 0.0f, 2.0f, 100.0f));
    const std::vector<float> plain = scene.render(settings("path", 16));
    const uint32_t program = add_linear_falloff(scene.h.scene);
    ASSERT_EQ(stratum_scene_set_light_program(scene.h.scene, 0, program, kInputs + 5), STRATUM_OK)
        << stratum_last_error();
    const std::vector<float> scaled = scene.render(settings("path", 16));
    for (int y = 0; y < 16; ++y) {
        for (int x = 0; x < 16; ++x) {
            const size_t p = (static_cast<size_t>(y) * 16 + x) * 4;
            const double px = (x + 0.5) / 8.0 - 1.0, py = (y + 0.5) / 8.0 - 1.0;
            const double t = std::sqrt(px * px + py * py + 4.0);
            ASSERT_GT(plain[p], 0.0f);
            EXPECT_NEAR(scaled[p] / plain[p], kStrength * t, 2.6e-4 + 1e-6) << x << "," << y;
        }
    }
    // Removed, the lamp is as it was.
    ASSERT_EQ(stratum_scene_set_light_program(scene.h.scene, 0, STRATUM_NO_PROGRAM, 0), STRATUM_OK);
    EXPECT_EQ(scene.render(settings("path", 16)), plain);
}

// A camera ray that meets an area lamp 2 in front of the orthographic camera takes the program
// at that distance: 0.5 x 2 = 1 times the lamp's radiance, at every pixel.
TEST(LampPrograms, ARayThatMeetsTheLampTakesTheProgramAtItsDistance) {
    StratumLightDesc lamp = light_at(STRATUM_LIGHT_AREA_RECTANGLE, 0.0f, 0.0f, 1.0f, 50.0f);
    lamp.size_x = lamp.size_y = 4.0f;
    // Facing the camera (+Z): rotated half a turn about x.
    lamp.transform[5] = -1.0f;
    lamp.transform[10] = -1.0f;
    LitPlane scene(lamp);
    const std::vector<float> plain = scene.render(settings("path", 8));
    const uint32_t program = add_linear_falloff(scene.h.scene);
    ASSERT_EQ(stratum_scene_set_light_program(scene.h.scene, 0, program, kInputs + 5), STRATUM_OK);
    const std::vector<float> scaled = scene.render(settings("path", 8));
    for (size_t p = 0; p < 64; ++p) {
        ASSERT_GT(plain[p * 4], 0.0f) << p;
        EXPECT_NEAR(scaled[p * 4] / plain[p * 4], kStrength * 2.0f, 1e-5f) << p;
    }
}

// A sun is at Cycles' FLT_MAX: Light Falloff from 4.4 gives the strength itself on every output.
TEST(LampPrograms, ASunIsAtFltMax) {
    StratumLightDesc sun = light_at(STRATUM_LIGHT_SUN, 0.0f, 0.0f, 5.0f, 3.0f);
    LitPlane scene(sun);
    const std::vector<float> plain = scene.render(settings("path", 8));
    const uint32_t program = add_linear_falloff(scene.h.scene, 1);
    ASSERT_EQ(stratum_scene_set_light_program(scene.h.scene, 0, program, kInputs + 5), STRATUM_OK);
    const std::vector<float> scaled = scene.render(settings("path", 8));
    for (size_t p = 0; p < 64; ++p) {
        ASSERT_GT(plain[p * 4], 0.0f) << p;
        EXPECT_NEAR(scaled[p * 4] / plain[p * 4], kStrength, 1e-6f) << p;
    }
}

// Light tracing from the point lamp 2 above the plane, seen by a perspective camera 3 above
// (90 degrees over 64 pixels: each pixel sees a 0.09375-wide square of the plane). A particle
// takes the program where it lands, so a pixel's ratio is a mean of 0.5 t over the points
// inside its square: it lies between 0.5 t at the square's nearest and farthest points.
TEST(LampPrograms, LightTracingTakesTheProgramWhereAParticleLands) {
    LitPlane scene(light_at(STRATUM_LIGHT_POINT, 0.0f, 0.0f, 2.0f, 1000.0f), false);
    const std::vector<float> plain = scene.render(settings("light", 64));
    const uint32_t program = add_linear_falloff(scene.h.scene);
    ASSERT_EQ(stratum_scene_set_light_program(scene.h.scene, 0, program, kInputs + 5), STRATUM_OK);
    const std::vector<float> scaled = scene.render(settings("light", 64));
    int lit = 0;
    for (int y = 0; y < 64; ++y) {
        for (int x = 0; x < 64; ++x) {
            const size_t p = (static_cast<size_t>(y) * 64 + x) * 4;
            if (plain[p] == 0.0f) continue;
            ++lit;
            const double w = 6.0 / 64.0, x0 = -3.0 + x * w, y0 = -3.0 + y * w;
            const auto t = [](double px, double py) { return std::sqrt(px * px + py * py + 4.0); };
            const double nx = std::clamp(0.0, x0, x0 + w), ny = std::clamp(0.0, y0, y0 + w);
            const double fx = std::abs(x0) > std::abs(x0 + w) ? x0 : x0 + w;
            const double fy = std::abs(y0) > std::abs(y0 + w) ? y0 : y0 + w;
            const double ratio = scaled[p] / plain[p];
            EXPECT_GE(ratio, kStrength * t(nx, ny) * (1.0 - 1e-5)) << x << "," << y;
            EXPECT_LE(ratio, kStrength * t(fx, fy) * (1.0 + 1e-5)) << x << "," << y;
        }
    }
    EXPECT_GT(lit, 64 * 64 / 2);
}

TEST(LampPrograms, RefusesWhatALampCannotRun) {
    LitPlane scene(light_at(STRATUM_LIGHT_POINT, 0.0f, 0.0f, 2.0f, 100.0f));
    const uint32_t program = add_linear_falloff(scene.h.scene);
    const auto refused = [&](uint32_t light, uint32_t id, uint32_t reg, const char* message) {
        EXPECT_EQ(stratum_scene_set_light_program(scene.h.scene, light, id, reg),
                  STRATUM_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(stratum_last_error()).find(message), std::string::npos) << stratum_last_error();
    };
    refused(1, program, kInputs + 5, "light_id 1 is not a light");
    refused(1, STRATUM_NO_PROGRAM, 0, "light_id 1 is not a light");
    refused(0, program + 1, kInputs + 5, "is not a program");
    refused(0, program, kInputs + 6, "(3 wide) is outside program");
    // A program that reads where the lamp is seen (here the position) is not a lamp's.
    StratumShaderNode reads_position{};
    reads_position.type = node_type("copy");
    reads_position.modes[0] = 1;  // vector
    reads_position.inputs[0] = STRATUM_INPUT_POSITION;
    reads_position.outputs[0] = kInputs;
    const std::vector<float> registers(kInputs + 3, 0.0f);
    const StratumShaderProgramDesc desc{
        &reads_position, 1, registers.data(), static_cast<uint32_t>(registers.size()), nullptr, 0};
    uint32_t id = 0;
    ASSERT_EQ(stratum_scene_add_shader_program(scene.h.scene, &desc, &id), STRATUM_OK);
    refused(0, id, kInputs,
            "node 0 (copy) reads renderer input register 0; a light's program may read only RAY_LENGTH");
}

std::string read_file(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(LampPrograms, TheSceneFileKeepsALampsProgram) {
    LitPlane scene(light_at(STRATUM_LIGHT_POINT, 0.0f, 0.0f, 2.0f, 100.0f));
    const uint32_t program = add_linear_falloff(scene.h.scene);
    ASSERT_EQ(stratum_scene_set_light_program(scene.h.scene, 0, program, kInputs + 5), STRATUM_OK);
    const std::vector<float> before = scene.render(settings("path", 8));
    const std::string a = ::testing::TempDir() + "lamp_program_a.json",
                      b = ::testing::TempDir() + "lamp_program_b.json";
    ASSERT_EQ(stratum_scene_save(scene.h.scene, a.c_str()), STRATUM_OK) << stratum_last_error();
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(a.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    ASSERT_EQ(stratum_scene_save(loaded, b.c_str()), STRATUM_OK);
    const stratum_test::RenderOutput after = stratum_test::render(loaded, settings("path", 8));
    stratum_scene_destroy(loaded);
    EXPECT_EQ(read_file(a), read_file(b));
    const nlohmann::json lights = nlohmann::json::parse(read_file(a)).at("programs").at("lights");
    EXPECT_EQ(lights, nlohmann::json::parse(R"([{"light": 0, "program": 0, "register": 149}])"));
    EXPECT_EQ(after.rgba, before);
    std::remove(a.c_str());
    std::remove(b.c_str());
}

}  // namespace
