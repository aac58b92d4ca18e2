// Determinism (DESIGN.md): same scene + settings + seed => bit-identical image, whatever the
// thread count, and however many renders the process has made before. Every registered
// sampler x integrator renders a Cornell box many times in this one process, with threads 1, 2
// and 7 in turn. `make sanitize` also runs this test under valgrind memcheck, with
// STRATUM_DETERMINISM_RENDERS=3 (renders per sampler x integrator, default 10: memcheck is about
// 50 times slower, and a read of uninitialised memory shows there on the first render that
// makes it, whether or not it changes a pixel).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "render_helpers.h"
#include "setting_choices.h"

using namespace stratum_test;

namespace {

// Renders per sampler x integrator: STRATUM_DETERMINISM_RENDERS if set (at least 2, so that two
// renders are compared), else 10.
int renders_per_case() {
    const char* value = std::getenv("STRATUM_DETERMINISM_RENDERS");
    return value ? std::max(2, std::atoi(value)) : 10;
}
constexpr int64_t kThreadCounts[] = {1, 2, 7};

StratumMaterialDesc principled_v1(float r, float g, float b) {
    return {STRATUM_MATERIAL_PRINCIPLED_V1, {r, g, b}, 1.0f, 0, 0, 1.5f, {0, 0, 0}, STRATUM_MICROFACET_GGX};
}

// Flat mesh data in world space, grown quad by quad (triangles 0-1-2 and 0-2-3).
struct MeshData {
    std::vector<float> positions;
    std::vector<uint32_t> triangles;
    std::vector<uint32_t> materials;
    std::vector<float> vertex_normals;

    void quad(std::initializer_list<float> corners, uint32_t material) {
        const auto base = static_cast<uint32_t>(positions.size() / 3);
        positions.insert(positions.end(), corners);
        triangles.insert(triangles.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        materials.insert(materials.end(), {material, material});
    }
};

uint32_t add_mesh(StratumScene* scene, const MeshData& m) {
    const StratumMeshDesc desc{m.positions.data(),
                               static_cast<uint32_t>(m.positions.size() / 3),
                               m.triangles.data(),
                               static_cast<uint32_t>(m.triangles.size() / 3),
                               nullptr,
                               nullptr,
                               m.materials.data(),
                               m.vertex_normals.empty() ? nullptr : m.vertex_normals.data()};
    uint32_t id = 0;
    EXPECT_EQ(stratum_scene_add_mesh(scene, &desc, &id), STRATUM_OK) << stratum_last_error();
    return id;
}

// Object-to-world matrix: uniform scale, rotation `angle` about Z, translation (x, y, z).
std::vector<float> placement(float scale, float angle, float x, float y, float z) {
    const float c = scale * std::cos(angle), s = scale * std::sin(angle);
    return {c, -s, 0, x, s, c, 0, y, 0, 0, scale, z, 0, 0, 0, 1};
}

// The reporter's box (issue 12), with what reaches the code paths it exercises: walls of the
// Principled v1 BSDF with roughness 1 and specular 0; a 0.5 m emissive quad of strength 15
// just under the ceiling; one cube mesh placed twice (instancing), one cube standing on the
// floor (its bottom coplanar with it) and one moving over the shutter (motion, time
// dimension); a smooth glass sphere (vertex normals, delta scattering); a point lamp (light
// tracing and lamp sampling).
StratumScene* cornell_box() {
    StratumScene* scene = nullptr;
    EXPECT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    uint32_t white = 0, red = 0, green = 0, light = 0, metal = 0, glass = 0;
    const StratumMaterialDesc emitter{STRATUM_MATERIAL_EMISSION, {1, 1, 1}, 1, 0, 0, 1.5f, {15, 15, 15},
                                      STRATUM_MICROFACET_GGX};
    const StratumMaterialDesc brushed{
        STRATUM_MATERIAL_PRINCIPLED_V2,     {0.9f, 0.7f, 0.3f}, 0.4f, 0.5f, 0.5f, 1.5f, {0, 0, 0},
        STRATUM_MICROFACET_MULTISCATTER_GGX};
    const StratumMaterialDesc clear{STRATUM_MATERIAL_GLASS, {1, 1, 1}, 0, 0, 0, 1.45f, {0, 0, 0},
                                    STRATUM_MICROFACET_GGX};
    const StratumMaterialDesc walls[] = {principled_v1(0.8f, 0.8f, 0.8f),
                                         principled_v1(0.8f, 0.1f, 0.1f),
                                         principled_v1(0.1f, 0.8f, 0.1f),
                                         emitter,
                                         brushed,
                                         clear};
    uint32_t* ids[] = {&white, &red, &green, &light, &metal, &glass};
    for (size_t i = 0; i < 6; ++i)
        EXPECT_EQ(stratum_scene_add_material(scene, &walls[i], ids[i]), STRATUM_OK) << stratum_last_error();

    MeshData room;
    room.quad({-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0}, white);  // floor
    room.quad({-1, -1, 2, -1, 1, 2, 1, 1, 2, 1, -1, 2}, white);  // ceiling
    room.quad({-1, 1, 0, 1, 1, 0, 1, 1, 2, -1, 1, 2}, white);    // back
    room.quad({-1, -1, 0, -1, 1, 0, -1, 1, 2, -1, -1, 2}, red);  // left
    room.quad({1, -1, 0, 1, -1, 2, 1, 1, 2, 1, 1, 0}, green);    // right
    room.quad({-0.25f, -0.25f, 1.99f, -0.25f, 0.25f, 1.99f, 0.25f, 0.25f, 1.99f, 0.25f, -0.25f, 1.99f},
              light);  // emitter, facing down
    EXPECT_EQ(stratum_scene_add_instance(scene, add_mesh(scene, room), kIdentity), STRATUM_OK);

    // Unit cube with its bottom face at z = 0 of its object space.
    MeshData cube;
    cube.quad({-0.5f, -0.5f, 0, -0.5f, 0.5f, 0, 0.5f, 0.5f, 0, 0.5f, -0.5f, 0}, metal);
    cube.quad({-0.5f, -0.5f, 1, 0.5f, -0.5f, 1, 0.5f, 0.5f, 1, -0.5f, 0.5f, 1}, metal);
    cube.quad({-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, -0.5f, 1, -0.5f, -0.5f, 1}, metal);
    cube.quad({0.5f, -0.5f, 0, 0.5f, 0.5f, 0, 0.5f, 0.5f, 1, 0.5f, -0.5f, 1}, metal);
    cube.quad({0.5f, 0.5f, 0, -0.5f, 0.5f, 0, -0.5f, 0.5f, 1, 0.5f, 0.5f, 1}, metal);
    cube.quad({-0.5f, 0.5f, 0, -0.5f, -0.5f, 0, -0.5f, -0.5f, 1, -0.5f, 0.5f, 1}, metal);
    const uint32_t cube_id = add_mesh(scene, cube);
    EXPECT_EQ(stratum_scene_add_instance(scene, cube_id, placement(0.6f, 0.3f, -0.35f, 0.3f, 0).data()),
              STRATUM_OK);
    StratumInstanceDesc moving{};
    moving.mesh_id = cube_id;
    const std::vector<float> start = placement(0.5f, -0.3f, 0.4f, -0.2f, 0);
    const std::vector<float> end = placement(0.5f, -0.2f, 0.45f, -0.2f, 0);
    std::copy(start.begin(), start.end(), moving.transform);
    std::copy(end.begin(), end.end(), moving.transform_end);
    moving.motion = 1;
    moving.visibility = STRATUM_VISIBLE_ALL;
    EXPECT_EQ(stratum_scene_add_instance_ex(scene, &moving), STRATUM_OK) << stratum_last_error();

    const SphereMesh sphere = make_sphere(0.3f, 8, 16);
    MeshData ball{
        sphere.positions, sphere.triangles, std::vector<uint32_t>(sphere.triangles.size() / 3, glass), {}};
    for (size_t i = 0; i < sphere.positions.size(); ++i)
        ball.vertex_normals.push_back(sphere.positions[i] / 0.3f);
    EXPECT_EQ(
        stratum_scene_add_instance(scene, add_mesh(scene, ball), placement(1, 0, 0.3f, 0.2f, 0.8f).data()),
        STRATUM_OK);

    StratumLightDesc lamp{};
    lamp.type = STRATUM_LIGHT_POINT;
    lamp.color[0] = lamp.color[1] = lamp.color[2] = 1.0f;
    lamp.strength = 20.0f;
    lamp.radius = 0.05f;
    std::copy(kIdentity, kIdentity + 16, lamp.transform);
    lamp.transform[3] = -0.5f;
    lamp.transform[7] = -0.5f;
    lamp.transform[11] = 1.5f;
    EXPECT_EQ(stratum_scene_add_light(scene, &lamp), STRATUM_OK) << stratum_last_error();

    // At (0, -3.5, 1) looking along +Y (camera -Z), +Z up.
    StratumCameraDesc camera = camera_at(0, 0, 0);
    const float look_along_y[16] = {1, 0, 0, 0, 0, 0, -1, -3.5f, 0, 1, 0, 1, 0, 0, 0, 1};
    std::copy(look_along_y, look_along_y + 16, camera.transform);
    camera.lens_mm = 35.0f;
    EXPECT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK) << stratum_last_error();
    return scene;
}

}  // namespace

TEST(Determinism, EverySamplerAndIntegratorRepeatsOneImageForAnyThreadCount) {
    StratumScene* scene = cornell_box();
    ASSERT_FALSE(::testing::Test::HasFailure());
    const std::vector<const char*> samplers = setting_choices("sampler");
    const std::vector<const char*> integrators = setting_choices("integrator");
    ASSERT_GE(samplers.size(), 12u);
    ASSERT_GE(integrators.size(), 4u);
    const int renders = renders_per_case();
    for (const char* integrator : integrators) {
        for (const char* sampler : samplers) {
            std::vector<float> first;
            for (int i = 0; i < renders; ++i) {
                const int64_t threads = kThreadCounts[i % 3];
                const RenderOutput out = render(scene, Settings{{"width", 16},
                                                                {"height", 16},
                                                                {"samples", 4},
                                                                {"max_bounces", 6},
                                                                {"seed", 3},
                                                                {"threads", threads},
                                                                {"sampler", sampler},
                                                                {"integrator", integrator},
                                                                // Radiosity's solve at its cheapest
                                                                // (one patch per triangle side, few
                                                                // rays): it is as deterministic
                                                                // at any size.
                                                                {"radiosity_patch_size", 100.0},
                                                                {"radiosity_rays", 16}});
                ASSERT_TRUE(out.error.empty()) << integrator << " " << sampler << ": " << out.error;
                ASSERT_EQ(out.rgba.size(), 16u * 16u * 4u);
                if (i == 0) {
                    // A black or non-finite image would make the comparison say nothing.
                    double sum = 0;
                    for (float v : out.rgba) {
                        ASSERT_TRUE(std::isfinite(v)) << integrator << " " << sampler;
                        sum += v;
                    }
                    ASSERT_GT(sum, 0.0) << integrator << " " << sampler;
                    first = out.rgba;
                    continue;
                }
                // EXPECT_EQ on the whole vector prints 1024 floats; count the differences instead.
                size_t differing = 0;
                for (size_t k = 0; k < first.size(); ++k) differing += out.rgba[k] != first[k];
                EXPECT_EQ(differing, 0u) << integrator << " x " << sampler << ": render " << i << " with "
                                         << threads << " threads differs from the first in " << differing
                                         << " of " << first.size() << " values";
            }
        }
    }
    stratum_scene_destroy(scene);
}

// Filter Glossy and the caustics switches change a path's closures by what it did before
// (integrators/light_path_closures.h): a function of the path alone, so the image is the same
// for any thread count; it must differ from the image without them for the test to say
// something (the box has a glass sphere and glossy Principled walls).
TEST(Determinism, FilterGlossyAndCausticsRepeatOneImageForAnyThreadCount) {
    StratumScene* scene = cornell_box();
    ASSERT_FALSE(::testing::Test::HasFailure());
    for (const char* sampler : {"random", "sobol"}) {
        const Settings base{{"width", 16},      {"height", 16}, {"samples", 8},
                            {"max_bounces", 6}, {"seed", 3},    {"sampler", sampler}};
        Settings plain = base;
        plain.emplace_back("threads", 1);
        const RenderOutput unfiltered = render(scene, plain);
        ASSERT_TRUE(unfiltered.error.empty()) << unfiltered.error;
        std::vector<float> first;
        for (int i = 0; i < 3; ++i) {
            Settings settings = base;
            settings.emplace_back("threads", kThreadCounts[i]);
            settings.emplace_back("filter_glossy", 1.0);
            settings.emplace_back("caustics_reflective", 0);
            settings.emplace_back("caustics_refractive", 0);
            const RenderOutput out = render(scene, settings);
            ASSERT_TRUE(out.error.empty()) << sampler << ": " << out.error;
            if (i == 0) {
                first = out.rgba;
                EXPECT_NE(first, unfiltered.rgba) << sampler << ": the switches changed nothing";
                continue;
            }
            size_t differing = 0;
            for (size_t k = 0; k < first.size(); ++k) differing += out.rgba[k] != first[k];
            EXPECT_EQ(differing, 0u) << sampler << ": " << kThreadCounts[i] << " threads";
        }
    }
    stratum_scene_destroy(scene);
}

// Path guiding learns between passes from records counted in integers (guiding/guiding_tree.h),
// so its tree, and the image, are the same for any thread count: the trained tree must differ
// from the untrained one (nodes > 2) for the comparison to say something about the training.
TEST(Determinism, PathGuidingRepeatsOneImageForAnyThreadCount) {
    StratumScene* scene = cornell_box();
    ASSERT_FALSE(::testing::Test::HasFailure());
    for (const char* sampler : {"random", "sobol"}) {
        std::vector<float> first;
        double first_nodes = 0;
        for (int i = 0; i < 6; ++i) {
            const int64_t threads = kThreadCounts[i % 3];
            const RenderOutput out = render(scene, Settings{{"width", 32},
                                                            {"height", 32},
                                                            {"samples", 16},
                                                            {"max_bounces", 6},
                                                            {"seed", 3},
                                                            {"threads", threads},
                                                            {"sampler", sampler},
                                                            {"use_guiding", 1},
                                                            {"guiding_training_samples", 8}});
            ASSERT_TRUE(out.error.empty()) << sampler << ": " << out.error;
            if (i == 0) {
                first = out.rgba;
                first_nodes = out.counters.at("guiding.nodes");
                EXPECT_GT(first_nodes, 2.0) << sampler << ": the tree did not split";
                EXPECT_GT(out.counters.at("guiding.bytes"), 0.0);
                continue;
            }
            EXPECT_EQ(out.counters.at("guiding.nodes"), first_nodes) << sampler;
            size_t differing = 0;
            for (size_t k = 0; k < first.size(); ++k) differing += out.rgba[k] != first[k];
            EXPECT_EQ(differing, 0u) << sampler << ": render " << i << " with " << threads << " threads";
        }
    }
    stratum_scene_destroy(scene);
}
