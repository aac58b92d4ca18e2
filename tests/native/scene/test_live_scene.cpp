// Live edits (scene/live_scene.h, RenderScene::update): after each edit of a scene a renderer
// already rendered, its next render equals, bit for bit, the render of a scene built anew with
// the edit, and the edit is applied in place (no fresh build) where it can be; node programs
// replaced in place too.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <vector>

#include "api/scene_handle.h"
#include "node_types.h"
#include "render_helpers.h"
#include "render_scene/render_scene.h"

using namespace stratum_test;

namespace {

// A box of 12 triangles, [-0.5, 0.5]^3, every triangle of material `material`.
struct BoxMesh {
    std::vector<float> positions;
    std::vector<uint32_t> triangles;
    std::vector<uint32_t> materials;
};

BoxMesh make_box(uint32_t material) {
    BoxMesh b;
    for (int i = 0; i < 8; ++i)
        for (int axis = 0; axis < 3; ++axis) b.positions.push_back((i >> axis) & 1 ? 0.5f : -0.5f);
    const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                  {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : faces) {
        b.triangles.insert(b.triangles.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
        b.materials.insert(b.materials.end(), {material, material});
    }
    return b;
}

std::array<float, 16> translation(float x, float y, float z, float scale = 1.0f) {
    return {scale, 0, 0, x, 0, scale, 0, y, 0, 0, scale, z, 0, 0, 0, 1};
}

// Everything the tests edit, so that a scene can be built anew with the same values.
struct Values {
    std::array<float, 16> instanced_a = translation(-1.2f, 0, -4), instanced_b = translation(1.2f, 0, -4);
    std::array<float, 16> flattened = translation(0, -1.6f, -4, 2.0f);
    std::array<float, 16> emitter = translation(0, 1.8f, -4, 0.6f);
    float red = 0.8f;
    float light_strength = 200.0f;
    float camera_x = 0.0f;
    float background = 0.05f;
};

StratumInstanceDesc instance(uint32_t mesh, const std::array<float, 16>& m) {
    StratumInstanceDesc d{};
    d.mesh_id = mesh;
    std::copy(m.begin(), m.end(), d.transform);
    d.visibility = STRATUM_VISIBLE_ALL;
    return d;
}

StratumMaterialDesc diffuse(float r, float g, float b) {
    return {STRATUM_MATERIAL_DIFFUSE, {r, g, b}, 1, 0, 0, 1.5f, {0, 0, 0}, STRATUM_MICROFACET_GGX};
}

StratumLightDesc point_light(float strength) {
    StratumLightDesc l{};
    l.type = STRATUM_LIGHT_POINT;
    std::fill(l.color, l.color + 3, 1.0f);
    l.strength = strength;
    l.radius = 0.1f;
    std::copy(kIdentity, kIdentity + 16, l.transform);
    l.transform[3] = 2.0f;
    l.transform[7] = 2.0f;
    l.transform[11] = -2.0f;
    return l;
}

// Materials 0 (red diffuse), 1 (grey diffuse), 2 (emitter); meshes 0 (red box, placed twice:
// instanced), 1 (grey box, placed once: flattened into the top level), 2 (emissive box).
StratumScene* build(const Values& v) {
    StratumScene* scene = nullptr;
    EXPECT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    const StratumMaterialDesc red = diffuse(v.red, 0.2f, 0.2f), grey = diffuse(0.5f, 0.5f, 0.5f);
    StratumMaterialDesc emitter = diffuse(0, 0, 0);
    emitter.model = STRATUM_MATERIAL_EMISSION;
    std::fill(emitter.emission, emitter.emission + 3, 3.0f);
    for (const StratumMaterialDesc* m :
         std::initializer_list<const StratumMaterialDesc*>{&red, &grey, &emitter})
        EXPECT_EQ(stratum_scene_add_material(scene, m, nullptr), STRATUM_OK);
    for (uint32_t material = 0; material < 3; ++material) {
        const BoxMesh box = make_box(material);
        const StratumMeshDesc mesh{box.positions.data(), 8, box.triangles.data(), 12, nullptr, nullptr,
                                   box.materials.data()};
        EXPECT_EQ(stratum_scene_add_mesh(scene, &mesh, nullptr), STRATUM_OK);
    }
    for (const StratumInstanceDesc& d : {instance(0, v.instanced_a), instance(0, v.instanced_b),
                                         instance(1, v.flattened), instance(2, v.emitter)})
        EXPECT_EQ(stratum_scene_add_instance_ex(scene, &d), STRATUM_OK);
    const StratumLightDesc light = point_light(v.light_strength);
    EXPECT_EQ(stratum_scene_add_light(scene, &light), STRATUM_OK);
    const StratumCameraDesc camera = camera_at(v.camera_x, 0, 0);
    EXPECT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK);
    const float bg[3] = {v.background, v.background, v.background};
    EXPECT_EQ(stratum_scene_set_background(scene, bg), STRATUM_OK);
    return scene;
}

std::vector<float> render_with(StratumRenderer* r) {
    EXPECT_TRUE(render_to_end(r)) << stratum_last_error();
    std::vector<float> rgba(24 * 16 * 4);
    EXPECT_EQ(stratum_renderer_read_pixels(r, rgba.data(), rgba.size()), STRATUM_OK);
    return rgba;
}

StratumRenderer* make_renderer(StratumScene* scene, const char* bvh = "static") {
    StratumRenderer* r = nullptr;
    EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_string(r, "bvh", bvh), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_int(r, "width", 24), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_int(r, "height", 16), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_int(r, "samples", 8), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_int(r, "max_bounces", 3), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_string(r, "sampler", "sobol"), STRATUM_OK);
    return r;
}

std::vector<float> fresh_render(const Values& v, const char* bvh) {
    StratumScene* scene = build(v);
    StratumRenderer* r = make_renderer(scene, bvh);
    std::vector<float> rgba = render_with(r);
    stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
    return rgba;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

// Both BVH layouts: static (a single placement flattened: its edit remaps its vertices) and
// dynamic (every mesh instanced: an edit is a top-level recommit).
class LiveSceneEdits : public ::testing::TestWithParam<const char*> {};

TEST_P(LiveSceneEdits, EveryEditRendersAsAFreshBuildOfTheEditedScene) {
    const char* bvh = GetParam();
    Values v;
    StratumScene* scene = build(v);
    StratumRenderer* r = make_renderer(scene, bvh);
    const std::vector<float> before = render_with(r);
    ASSERT_TRUE(same_bits(before, fresh_render(v, bvh)));

    struct Edit {
        const char* what;
        void (*apply)(StratumScene*, Values&);
    };
    const Edit edits[] = {
        {"move an instanced object",
         [](StratumScene* s, Values& values) {
             values.instanced_b = translation(0.9f, 0.3f, -3.5f);
             const StratumInstanceDesc d = instance(0, values.instanced_b);
             ASSERT_EQ(stratum_scene_set_instance(s, 1, &d), STRATUM_OK) << stratum_last_error();
         }},
        {"move the flattened object",
         [](StratumScene* s, Values& values) {
             values.flattened = translation(0.2f, -1.5f, -4.2f, 2.0f);
             const StratumInstanceDesc d = instance(1, values.flattened);
             ASSERT_EQ(stratum_scene_set_instance(s, 2, &d), STRATUM_OK);
         }},
        {"move the emitter (its triangles are lights)",
         [](StratumScene* s, Values& values) {
             values.emitter = translation(-0.4f, 1.6f, -3.8f, 0.6f);
             const StratumInstanceDesc d = instance(2, values.emitter);
             ASSERT_EQ(stratum_scene_set_instance(s, 3, &d), STRATUM_OK);
         }},
        {"change a material colour",
         [](StratumScene* s, Values& values) {
             values.red = 0.3f;
             const StratumMaterialDesc m = diffuse(values.red, 0.2f, 0.2f);
             ASSERT_EQ(stratum_scene_set_material(s, 0, &m), STRATUM_OK);
         }},
        {"change a light's power",
         [](StratumScene* s, Values& values) {
             values.light_strength = 50.0f;
             const StratumLightDesc l = point_light(values.light_strength);
             ASSERT_EQ(stratum_scene_set_light(s, 0, &l), STRATUM_OK);
         }},
        {"move the camera",
         [](StratumScene* s, Values& values) {
             values.camera_x = 0.3f;
             const StratumCameraDesc c = camera_at(values.camera_x, 0, 0);
             ASSERT_EQ(stratum_scene_set_camera(s, &c), STRATUM_OK);
         }},
        {"change the world",
         [](StratumScene* s, Values& values) {
             values.background = 0.4f;
             const float bg[3] = {values.background, values.background, values.background};
             ASSERT_EQ(stratum_scene_set_background(s, bg), STRATUM_OK);
         }},
    };
    std::vector<float> previous = before;
    for (const Edit& e : edits) {
        e.apply(scene, v);
        const std::vector<float> edited = render_with(r);
        EXPECT_FALSE(same_bits(edited, previous))
            << bvh << ", " << e.what << ": the edit did not reach the renderer";
        EXPECT_TRUE(same_bits(edited, fresh_render(v, bvh)))
            << bvh << ", " << e.what << ": differs from a fresh build";
        previous = edited;
    }
    stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
}

INSTANTIATE_TEST_SUITE_P(BvhLayouts, LiveSceneEdits, ::testing::Values("static", "dynamic"));

TEST(LiveScene, EditsOfTransformsMaterialsLightsAndWorldAreAppliedInPlace) {
    Values v;
    StratumScene* handle = build(v);
    stratum::Scene copy;
    stratum::SceneVersion seen;
    ASSERT_TRUE(handle->live->sync(&copy, &seen).rebuild);
    stratum::RenderScene built(copy);
    const StratumInstanceDesc moved = instance(0, translation(0.5f, 0.5f, -5));
    ASSERT_EQ(stratum_scene_set_instance(handle, 1, &moved), STRATUM_OK);
    const StratumMaterialDesc m = diffuse(0.1f, 0.9f, 0.1f);
    ASSERT_EQ(stratum_scene_set_material(handle, 1, &m), STRATUM_OK);
    const StratumLightDesc l = point_light(10.0f);
    ASSERT_EQ(stratum_scene_set_light(handle, 0, &l), STRATUM_OK);
    const stratum::SceneChanges changes = handle->live->sync(&copy, &seen);
    EXPECT_FALSE(changes.rebuild);
    EXPECT_EQ(changes.instances, std::vector<uint32_t>{1});
    EXPECT_TRUE(changes.materials && changes.lights);
    EXPECT_TRUE(built.update(copy, changes));
    // Nothing changed since: an empty change set.
    EXPECT_FALSE(handle->live->sync(&copy, &seen).any());
    // A new instance changes the list: a fresh build.
    const StratumInstanceDesc extra = instance(1, translation(3, 0, -6));
    ASSERT_EQ(stratum_scene_add_instance_ex(handle, &extra), STRATUM_OK);
    EXPECT_TRUE(handle->live->sync(&copy, &seen).rebuild);
    stratum_scene_destroy(handle);
}

TEST(LiveScene, AnInstanceSkippedAsDegenerateCanBeEditedAndStaysSkipped) {
    // A placement of scale 0 cannot be traced (it is skipped with a notice); editing it to
    // another such transform, or its visibility, keeps it skipped: the update has no placement
    // to move and must not touch one.
    Values v;
    std::array<float, 16> flat = translation(0, 0, -4);
    flat[5] = 0.0f;
    const auto add_flat = [&](StratumScene* s, const std::array<float, 16>& m, uint32_t visibility) {
        StratumInstanceDesc d = instance(0, m);
        d.visibility = visibility;
        EXPECT_EQ(stratum_scene_add_instance_ex(s, &d), STRATUM_OK) << stratum_last_error();
    };
    StratumScene* scene = build(v);
    add_flat(scene, flat, STRATUM_VISIBLE_ALL);
    StratumRenderer* r = make_renderer(scene);
    render_with(r);
    std::array<float, 16> flatter = flat;
    flatter[3] = 0.5f;
    StratumInstanceDesc edited = instance(0, flatter);
    edited.visibility = STRATUM_VISIBLE_CAMERA;
    ASSERT_EQ(stratum_scene_set_instance(scene, 4, &edited), STRATUM_OK);
    const std::vector<float> after = render_with(r);
    StratumScene* fresh = build(v);
    add_flat(fresh, flatter, STRATUM_VISIBLE_CAMERA);
    StratumRenderer* fresh_renderer = make_renderer(fresh);
    EXPECT_TRUE(same_bits(after, render_with(fresh_renderer)));
    stratum_renderer_destroy(fresh_renderer);
    stratum_scene_destroy(fresh);
    stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
}

// A program of one constant RGB `value` in kInputs + 0 .. 2 (a float broadcast from kInputs +
// 3), or, `falloff`, value times a Light Falloff's Linear output of strength 1 (the distance).
uint32_t add_scaling_program(StratumScene* scene, float value, bool falloff, uint32_t program_id = ~0u) {
    constexpr uint32_t kInputs = STRATUM_SHADER_INPUT_REGISTERS;
    StratumShaderNode nodes[2] = {};
    nodes[0].type = stratum_test::node_type("light_falloff");
    nodes[0].modes[0] = 1;
    nodes[0].inputs[0] = kInputs + 3;
    nodes[0].inputs[1] = kInputs + 4;  // smooth 0
    nodes[0].inputs[2] = STRATUM_INPUT_RAY_LENGTH;
    for (uint32_t k = 0; k < 3; ++k) nodes[0].outputs[k] = kInputs + 5 + k;
    nodes[1].type = stratum_test::node_type("copy");
    nodes[1].modes[0] = 2;  // float to vector
    nodes[1].inputs[0] = falloff ? kInputs + 6 : kInputs + 3;
    nodes[1].outputs[0] = kInputs;
    std::vector<float> registers(kInputs + 8, 0.0f);
    registers[kInputs + 3] = value;
    const StratumShaderProgramDesc desc{nodes,   2, registers.data(), static_cast<uint32_t>(registers.size()),
                                        nullptr, 0};
    if (program_id != ~0u) {
        EXPECT_EQ(stratum_scene_set_shader_program(scene, program_id, &desc), STRATUM_OK)
            << stratum_last_error();
        return program_id;
    }
    uint32_t id = 0;
    EXPECT_EQ(stratum_scene_add_shader_program(scene, &desc, &id), STRATUM_OK) << stratum_last_error();
    return id;
}

// The test scene with program 0 (emission `emission`) driving the emitter material's emission and
// program 1 (`lamp` times the distance) scaling the point light.
StratumScene* build_with_programs(const Values& v, float emission, float lamp) {
    StratumScene* scene = build(v);
    add_scaling_program(scene, emission, false);
    add_scaling_program(scene, lamp, true);
    const StratumProgramBinding b{2, 0, STRATUM_PROGRAM_EMISSION, 0, STRATUM_SHADER_INPUT_REGISTERS};
    EXPECT_EQ(stratum_scene_bind_program(scene, &b), STRATUM_OK) << stratum_last_error();
    EXPECT_EQ(stratum_scene_set_light_program(scene, 0, 1, STRATUM_SHADER_INPUT_REGISTERS), STRATUM_OK)
        << stratum_last_error();
    return scene;
}

// A program replaced in place, a material's or a lamp's, reaches a renderer that rendered the
// scene before it: the next render is that of a scene built with the new program.
TEST(LiveScene, AProgramReplacedInPlaceRendersAsAFreshBuild) {
    Values v;
    StratumScene* scene = build_with_programs(v, 3.0f, 0.5f);
    StratumRenderer* r = make_renderer(scene);
    const std::vector<float> before = render_with(r);
    const auto fresh = [&](float emission, float lamp) {
        StratumScene* s = build_with_programs(v, emission, lamp);
        StratumRenderer* fr = make_renderer(s);
        const std::vector<float> rgba = render_with(fr);
        stratum_renderer_destroy(fr);
        stratum_scene_destroy(s);
        return rgba;
    };
    ASSERT_TRUE(same_bits(before, fresh(3.0f, 0.5f)));
    add_scaling_program(scene, 1.0f, false, 0);
    const std::vector<float> material_edited = render_with(r);
    EXPECT_FALSE(same_bits(material_edited, before)) << "the material's program did not reach the renderer";
    EXPECT_TRUE(same_bits(material_edited, fresh(1.0f, 0.5f)));
    add_scaling_program(scene, 2.0f, true, 1);
    const std::vector<float> lamp_edited = render_with(r);
    EXPECT_FALSE(same_bits(lamp_edited, material_edited)) << "the lamp's program did not reach the renderer";
    EXPECT_TRUE(same_bits(lamp_edited, fresh(1.0f, 2.0f)));
    stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
}

TEST(LiveScene, ACameraEditUpdatesInPlace) {
    Values v;
    StratumScene* handle = build(v);
    stratum::Scene copy;
    stratum::SceneVersion seen;
    handle->live->sync(&copy, &seen);
    stratum::RenderScene built(copy);
    const StratumCameraDesc camera = camera_at(0.5f, 0.2f, 1.0f);
    ASSERT_EQ(stratum_scene_set_camera(handle, &camera), STRATUM_OK);
    const stratum::SceneChanges changes = handle->live->sync(&copy, &seen);
    EXPECT_TRUE(changes.camera && !changes.rebuild && changes.instances.empty());
    EXPECT_TRUE(built.update(copy, changes));
    stratum_scene_destroy(handle);
}

TEST(LiveScene, EditsAreValidatedAndARejectedOneChangesNothing) {
    Values v;
    StratumScene* scene = build(v);
    StratumRenderer* r = make_renderer(scene);
    const std::vector<float> before = render_with(r);
    StratumInstanceDesc bad = instance(0, translation(0, 0, -4));
    bad.transform[0] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(stratum_scene_set_instance(scene, 0, &bad), STRATUM_ERROR_INVALID_ARGUMENT);
    const StratumInstanceDesc ok = instance(0, translation(0, 0, -4));
    EXPECT_EQ(stratum_scene_set_instance(scene, 9, &ok), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("instance 9 does not exist"), std::string::npos);
    const StratumMaterialDesc m = diffuse(0.5f, 0.5f, 0.5f);
    EXPECT_EQ(stratum_scene_set_material(scene, 3, &m), STRATUM_ERROR_INVALID_ARGUMENT);
    StratumMaterialDesc negative = m;
    negative.base_color[0] = -1.0f;
    EXPECT_EQ(stratum_scene_set_material(scene, 0, &negative), STRATUM_ERROR_INVALID_ARGUMENT);
    const StratumLightDesc l = point_light(1.0f);
    EXPECT_EQ(stratum_scene_set_light(scene, 1, &l), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_TRUE(same_bits(render_with(r), before));
    // The renderer keeps rendering the scene after the host destroyed its handle.
    stratum_scene_destroy(scene);
    EXPECT_TRUE(same_bits(render_with(r), before));
    stratum_renderer_destroy(r);
}
