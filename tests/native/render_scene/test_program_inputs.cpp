// What the renderer writes into a program's input registers (StratumShaderInput) for the inputs
// of the Wireframe and Tangent nodes and of Cycles' ray data: the hit triangle, the MikkTSpace
// tangent, the normal transform, the ray length and the pixel footprint, at a surface hit
// (render_scene/material_programs.h), in the world (world_baking.h) and along rendered paths;
// and that a scene file written when the inputs took 100 registers loads into today's layout.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "node_types.h"
#include "render_helpers.h"
#include "render_scene/render_scene.h"
#include "render_scene/world_baking.h"
#include "scene_handle.h"

namespace {

using stratum::Vec3;

Vec3 read3(const std::vector<float>& r, uint32_t at) { return {r[at], r[at + 1], r[at + 2]}; }

void expect_near(Vec3 got, Vec3 want, float tolerance, const char* what) {
    EXPECT_NEAR(got.x, want.x, tolerance) << what;
    EXPECT_NEAR(got.y, want.y, tolerance) << what;
    EXPECT_NEAR(got.z, want.z, tolerance) << what;
}

// The unit square [0,1]^2 at z = 0, triangles (0,1,2), (0,2,3), corner tangents turning per
// vertex; placed by M = R(0.7) S(2, 0.5) plus a translation, so that M^-T differs from M.
struct Square {
    stratum::Scene scene;
    stratum::Transform m;
    std::array<Vec3, 4> tangents = {Vec3(1.0f, 0.0f, 0.0f), Vec3(0.9f, 0.3f, 0.0f), Vec3(0.8f, 0.5f, 0.1f),
                                    Vec3(1.0f, 0.1f, 0.0f)};

    explicit Square(bool with_tangents) {
        const float c = std::cos(0.7f), s = std::sin(0.7f);
        m.m = {c * 2.0f, -s * 0.5f, 0, 0.5f, s * 2.0f, c * 0.5f, 0, -0.25f, 0, 0, 1, 0};
        scene.materials.push_back(stratum::SceneMaterial{{stratum::WeightedClosure{stratum::Rgb(1.0f), {}}}});
        stratum::Mesh mesh;
        mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
        mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
        mesh.material_ids = {0, 0};
        if (with_tangents) {
            for (uint32_t v : {0u, 1u, 2u, 0u, 2u, 3u}) {
                mesh.corner_tangents.push_back(tangents[v]);
                mesh.corner_signs.push_back(1.0f);
            }
        }
        scene.meshes.push_back(mesh);
        stratum::Instance inst{};
        inst.mesh_id = 0;
        inst.object_to_world = inst.object_to_world_end = m;
        scene.instances.push_back(inst);
    }
};

// The inputs at object point (0.3, 0.6) (triangle (0, 2, 3), barycentrics 0.4, 0.3, 0.3), seen
// from above, with the given ray data.
std::vector<float> inputs_at(const Square& sq, stratum::RayReach reach) {
    const stratum::RenderScene rs(sq.scene);
    const Vec3 world = sq.m.point(Vec3(0.3f, 0.6f, 0.0f));
    stratum::SurfaceHit hit;
    EXPECT_TRUE(rs.intersect(world + Vec3(0, 0, 5), Vec3(0, 0, -1), 0.0f, stratum::kInfinity, &hit,
                             stratum::RayQuery{}));
    std::vector<float> r(STRATUM_SHADER_INPUT_REGISTERS, -9.0f);
    stratum::write_surface_inputs(hit, rs.program_inputs(hit, Vec3(0, 0, 1), false, reach), r.data());
    return r;
}

TEST(ProgramInputs, ASurfaceHitGivesItsTriangleTangentNormalTransformAndRay) {
    const Square sq(true);
    const std::vector<float> r = inputs_at(sq, {5.5f, 0.25f});
    expect_near(read3(r, STRATUM_INPUT_TRIANGLE), sq.m.point(Vec3(0, 0, 0)), 1e-6f, "vertex 0");
    expect_near(read3(r, STRATUM_INPUT_TRIANGLE + 3), sq.m.point(Vec3(1, 1, 0)), 1e-6f, "vertex 2");
    expect_near(read3(r, STRATUM_INPUT_TRIANGLE + 6), sq.m.point(Vec3(0, 1, 0)), 1e-6f, "vertex 3");
    // M^-T = R S^-1 up to a positive scale: (cos, sin, 0) / 2, (-sin, cos, 0) / 0.5, (0, 0, 1),
    // each times det S = 1 in the cofactor form.
    const float c = std::cos(0.7f), s = std::sin(0.7f);
    const Vec3 axes[3] = {Vec3(c / 2.0f, s / 2.0f, 0.0f), Vec3(-s / 0.5f, c / 0.5f, 0.0f),
                          Vec3(0.0f, 0.0f, 1.0f)};
    for (uint32_t k = 0; k < 3; ++k)
        expect_near(read3(r, STRATUM_INPUT_NORMAL_TRANSFORM + 3 * k), axes[k], 1e-6f, "normal transform");
    // The tangent interpolated in object space, then taken as a normal is: M^-T t.
    const Vec3 t = sq.tangents[0] * 0.4f + sq.tangents[2] * 0.3f + sq.tangents[3] * 0.3f;
    expect_near(read3(r, STRATUM_INPUT_MIKKTSPACE_TANGENT), axes[0] * t.x + axes[1] * t.y + axes[2] * t.z,
                1e-6f, "MikkTSpace tangent");
    EXPECT_EQ(r[STRATUM_INPUT_RAY_LENGTH], 5.5f);
    EXPECT_EQ(r[STRATUM_INPUT_PIXEL_FOOTPRINT], 0.25f);
}

TEST(ProgramInputs, AMeshWithoutTangentsGivesAZeroMikktspaceTangent) {
    const std::vector<float> r = inputs_at(Square(false), {1.0f, 0.0f});
    expect_near(read3(r, STRATUM_INPUT_MIKKTSPACE_TANGENT), Vec3(0, 0, 0), 0.0f, "no tangents");
}

TEST(ProgramInputs, TheWorldHasNoTriangleNoFootprintAndTheIdentityNormalTransform) {
    std::vector<float> r(STRATUM_SHADER_INPUT_REGISTERS, -9.0f);
    stratum::write_world_inputs(Vec3(0.6f, 0.0f, 0.8f), r.data());
    for (uint32_t k = 0; k < 9; ++k) EXPECT_EQ(r[STRATUM_INPUT_TRIANGLE + k], 0.0f);
    EXPECT_EQ(r[STRATUM_INPUT_PIXEL_FOOTPRINT], 0.0f);
    expect_near(read3(r, STRATUM_INPUT_NORMAL_TRANSFORM), Vec3(1, 0, 0), 0.0f, "x");
    expect_near(read3(r, STRATUM_INPUT_NORMAL_TRANSFORM + 3), Vec3(0, 1, 0), 0.0f, "y");
    expect_near(read3(r, STRATUM_INPUT_NORMAL_TRANSFORM + 6), Vec3(0, 0, 1), 0.0f, "z");
}

// Cycles' compact differential of a pinhole camera of 90 degrees across 8 pixels, at the view-
// plane point (u, v, -1) of a pixel: the mean distance of its unit direction to those one pixel
// (0.25) right and up.
double camera_spread(double u, double v) {
    const auto unit = [](double x, double y) {
        const double l = std::sqrt(x * x + y * y + 1.0);
        return std::array<double, 3>{x / l, y / l, -1.0 / l};
    };
    const auto distance = [](std::array<double, 3> a, std::array<double, 3> b) {
        return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                         (a[2] - b[2]) * (a[2] - b[2]));
    };
    const auto c = unit(u, v);
    return 0.5 * (distance(unit(u + 0.25, v), c) + distance(unit(u, v + 0.25), c));
}

// A camera 3 above an emitting plane, a fully transparent sheet 1 above it: the plane's program
// emits (ray length, footprint, 0). The ray passes the sheet, so its length is the distance from
// where it left the camera (Cycles continues the same ray): from the near clip plane, 0.5 deep,
// where Cycles starts a camera ray. The footprint is the camera's spread times the distance from
// the camera (Cycles moves the ray's differential with its origin).
TEST(ProgramInputs, RayLengthAndFootprintFollowTheCameraRayPastTransparentSurfaces) {
    stratum_test::SceneHandle h;
    StratumMaterialDesc emitter = stratum_test::diffuse_grey(0.0f);
    emitter.model = STRATUM_MATERIAL_EMISSION;
    StratumMaterialDesc sheet = stratum_test::diffuse_grey(1.0f);
    sheet.model = STRATUM_MATERIAL_TRANSPARENT;
    ASSERT_EQ(stratum_scene_add_material(h.scene, &emitter, nullptr), STRATUM_OK);
    ASSERT_EQ(stratum_scene_add_material(h.scene, &sheet, nullptr), STRATUM_OK);
    ASSERT_TRUE(stratum_test::add_square_instance(h.scene, 0.0f, 10.0f, 0));
    ASSERT_TRUE(stratum_test::add_square_instance(h.scene, 1.0f, 10.0f, 1));
    // Two copies: emission (RAY_LENGTH, PIXEL_FOOTPRINT, 0) in registers kInputs .. kInputs + 2.
    constexpr uint32_t kInputs = STRATUM_SHADER_INPUT_REGISTERS;
    StratumShaderNode copies[2] = {};
    for (uint32_t k = 0; k < 2; ++k) {
        copies[k].type = stratum_test::node_type("copy");
        copies[k].inputs[0] = k == 0 ? STRATUM_INPUT_RAY_LENGTH : STRATUM_INPUT_PIXEL_FOOTPRINT;
        copies[k].outputs[0] = kInputs + k;
    }
    const std::vector<float> registers(kInputs + 3, 0.0f);
    const StratumShaderProgramDesc desc{copies,  2, registers.data(), static_cast<uint32_t>(registers.size()),
                                        nullptr, 0};
    ASSERT_EQ(stratum_scene_add_shader_program(h.scene, &desc, nullptr), STRATUM_OK) << stratum_last_error();
    constexpr int kSize = 8;
    const stratum_test::RenderOutput out = stratum_test::render_pixel_centres(
        h.scene, kInputs, kSize, stratum_test::CentreView::kPerspective, 0.5f);
    ASSERT_TRUE(out.error.empty()) << out.error;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const float* px = &out.rgba[(static_cast<size_t>(y) * kSize + x) * 4];
            const double u = (x + 0.5) / 4.0 - 1.0, v = (y + 0.5) / 4.0 - 1.0;
            const double l = 3.0 * std::sqrt(u * u + v * v + 1.0);
            // The sample lies within 0.005 px of the centre in x and y: l changes by at most
            // 0.75 per pixel in each, the footprint by at most 0.06 (summed over x and y,
            // evaluated over this image).
            EXPECT_NEAR(px[0], l * (1.0 - 0.5 / 3.0), 7.5e-3) << x << "," << y;
            EXPECT_NEAR(px[1], l * camera_spread(u, v), 3e-4 + 1e-6) << x << "," << y;
        }
    }
}

// An orthographic camera's rays do not spread: the footprint is a pixel's width everywhere.
TEST(ProgramInputs, AnOrthographicFootprintIsAPixelsWidth) {
    stratum_test::SceneHandle h;
    StratumMaterialDesc emitter = stratum_test::diffuse_grey(0.0f);
    emitter.model = STRATUM_MATERIAL_EMISSION;
    ASSERT_EQ(stratum_scene_add_material(h.scene, &emitter, nullptr), STRATUM_OK);
    ASSERT_TRUE(stratum_test::add_square_instance(h.scene, 0.0f, 10.0f, 0));
    constexpr uint32_t kInputs = STRATUM_SHADER_INPUT_REGISTERS;
    StratumShaderNode copy{};
    copy.type = stratum_test::node_type("copy");
    copy.modes[0] = 2;  // float to vector
    copy.inputs[0] = STRATUM_INPUT_PIXEL_FOOTPRINT;
    copy.outputs[0] = kInputs;
    const std::vector<float> registers(kInputs + 3, 0.0f);
    const StratumShaderProgramDesc desc{&copy,   1, registers.data(), static_cast<uint32_t>(registers.size()),
                                        nullptr, 0};
    ASSERT_EQ(stratum_scene_add_shader_program(h.scene, &desc, nullptr), STRATUM_OK) << stratum_last_error();
    const stratum_test::RenderOutput out =
        stratum_test::render_pixel_centres(h.scene, kInputs, 8, stratum_test::CentreView::kOrthographic);
    ASSERT_TRUE(out.error.empty()) << out.error;
    for (size_t p = 0; p < 64; ++p) EXPECT_NEAR(out.rgba[p * 4], 2.0f / 8.0f, 1e-6f) << p;
}

std::string read_file(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// A scene file of version 1 numbered a program's own registers from 100, one of version 2 from
// 128: the same scene written that way (today's file with every register number at or above 144
// moved down and the registers between left out) loads as the scene itself, evaluates alike and
// saves as today's.
TEST(ProgramInputs, OlderSceneFilesProgramsMoveToTodaysRegisters) {
    constexpr uint32_t kInputs = STRATUM_SHADER_INPUT_REGISTERS;
    stratum_test::SceneHandle h;
    StratumMaterialDesc emitter = stratum_test::diffuse_grey(0.0f);
    emitter.model = STRATUM_MATERIAL_EMISSION;
    ASSERT_EQ(stratum_scene_add_material(h.scene, &emitter, nullptr), STRATUM_OK);
    StratumShaderNode add{};
    add.type = stratum_test::node_type("math");  // mode 0: ADD
    add.inputs[0] = STRATUM_INPUT_GENERATED;
    add.inputs[1] = add.inputs[2] = kInputs;
    add.outputs[0] = kInputs + 1;
    std::vector<float> registers(kInputs + 4, 0.0f);  // 6, then the emission's three
    registers[kInputs] = 6.0f;
    const StratumShaderProgramDesc desc{&add,    1, registers.data(), static_cast<uint32_t>(registers.size()),
                                        nullptr, 0};
    ASSERT_EQ(stratum_scene_add_shader_program(h.scene, &desc, nullptr), STRATUM_OK) << stratum_last_error();
    const StratumProgramBinding b{0, 0, STRATUM_PROGRAM_EMISSION, 0, kInputs + 1};
    ASSERT_EQ(stratum_scene_bind_program(h.scene, &b), STRATUM_OK) << stratum_last_error();
    const std::string today = ::testing::TempDir() + "program_inputs_today.json";
    const std::string old = ::testing::TempDir() + "program_inputs_old.json";
    const std::string again = ::testing::TempDir() + "program_inputs_again.json";
    ASSERT_EQ(stratum_scene_save(h.scene, today.c_str()), STRATUM_OK) << stratum_last_error();

    for (const auto& [version, old_inputs] : {std::pair{1, 100u}, std::pair{2, 128u}}) {
        nlohmann::json file = nlohmann::json::parse(read_file(today));
        ASSERT_EQ(file.at("version"), 3);
        file["version"] = version;
        // A structured binding is not captured by a lambda before C++20's P1091 (clang 14).
        const uint32_t inputs_then = old_inputs;
        const auto old_number = [&](uint32_t reg) {
            return reg >= kInputs ? reg - kInputs + inputs_then : reg;
        };
        for (nlohmann::json& program : file.at("programs").at("programs")) {
            for (nlohmann::json& row : program.at("nodes")) {
                for (size_t k = 7; k < 25; ++k)
                    row[k] = old_number(row[k].get<uint32_t>());  // inputs, outputs
            }
            nlohmann::json& regs = program.at("registers");
            regs.erase(regs.begin() + old_inputs, regs.begin() + kInputs);
        }
        for (nlohmann::json& binding : file.at("programs").at("bindings"))
            binding["register"] = old_number(binding.at("register").get<uint32_t>());
        std::ofstream(old) << file.dump();

        StratumScene* loaded = nullptr;
        ASSERT_EQ(stratum_scene_load(old.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
        std::vector<float> inputs(kInputs, 0.0f);
        inputs[STRATUM_INPUT_GENERATED] = 0.25f;
        float out = 0.0f;
        ASSERT_EQ(stratum_scene_evaluate_program(loaded, 0, inputs.data(), kInputs + 1, 1, &out), STRATUM_OK)
            << stratum_last_error();
        EXPECT_EQ(out, 6.25f) << "version " << version;
        ASSERT_EQ(stratum_scene_save(loaded, again.c_str()), STRATUM_OK);
        stratum_scene_destroy(loaded);
        EXPECT_EQ(read_file(again), read_file(today)) << "version " << version;
    }
    for (const std::string& path : {today, old, again}) std::remove(path.c_str());
}

}  // namespace
