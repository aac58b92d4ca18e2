// The C ABI rejects bad input with a status and a message that names the value, and never
// throws or aborts.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "scene_handle.h"
#include "setting_choices.h"

using stratum_test::SceneHandle;

namespace {

constexpr float kIdentity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

uint32_t add_grey(StratumScene* s) {
    StratumMaterialDesc m{STRATUM_MATERIAL_DIFFUSE, {0.5f, 0.5f, 0.5f}, 1.0f, 0.0f, 0.5f, 1.5f, {0, 0, 0},
                          STRATUM_MICROFACET_GGX};
    uint32_t id = 99;
    EXPECT_EQ(stratum_scene_add_material(s, &m, &id), STRATUM_OK);
    return id;
}

std::string last_error() { return stratum_last_error(); }

}  // namespace

TEST(Api, ModelListingsNameEveryValue) {
    const char* name = nullptr;
    int32_t value = -1;
    // At least the built-in models (a test in the same process may have registered more).
    ASSERT_GE(stratum_model_count(STRATUM_MODEL_LIGHT), 6);
    ASSERT_EQ(stratum_model_entry(STRATUM_MODEL_LIGHT, 5, &name, &value), STRATUM_OK);
    EXPECT_STREQ(name, "spot_v1");
    EXPECT_EQ(value, STRATUM_LIGHT_SPOT_V1);
    ASSERT_GE(stratum_model_count(STRATUM_MODEL_CLOSURE), 8);
    ASSERT_EQ(stratum_model_entry(STRATUM_MODEL_CLOSURE, 0, &name, &value), STRATUM_OK);
    EXPECT_STREQ(name, "diffuse");
    EXPECT_EQ(value, STRATUM_MATERIAL_DIFFUSE);
    EXPECT_EQ(stratum_model_count(99), -1);
    EXPECT_EQ(stratum_model_entry(99, 0, &name, &value), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("99"), std::string::npos);
    EXPECT_EQ(stratum_model_entry(STRATUM_MODEL_LIGHT, 1000, &name, &value), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("1000"), std::string::npos);
    EXPECT_EQ(stratum_model_entry(STRATUM_MODEL_LIGHT, 0, nullptr, nullptr), STRATUM_OK);
}

TEST(Api, NanVertexIsRejectedWithItsIndex) {
    SceneHandle h;
    const uint32_t mat = add_grey(h.scene);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, nan, 0};
    const uint32_t triangles[] = {0, 1, 2};
    const StratumMeshDesc mesh{positions, 3, triangles, 1, nullptr, nullptr, &mat};
    EXPECT_EQ(stratum_scene_add_mesh(h.scene, &mesh, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("vertex 2"), std::string::npos) << last_error();
    EXPECT_NE(last_error().find("nan"), std::string::npos) << last_error();
}

TEST(Api, OutOfRangeIndicesAndZeroSizesAreRejected) {
    SceneHandle h;
    const uint32_t mat = add_grey(h.scene);
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t bad_triangles[] = {0, 1, 7};
    StratumMeshDesc mesh{positions, 3, bad_triangles, 1, nullptr, nullptr, &mat};
    EXPECT_EQ(stratum_scene_add_mesh(h.scene, &mesh, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("vertex index 7"), std::string::npos) << last_error();

    const uint32_t triangles[] = {0, 1, 2};
    const uint32_t bad_material = 5;
    mesh = {positions, 3, triangles, 1, nullptr, nullptr, &bad_material};
    EXPECT_EQ(stratum_scene_add_mesh(h.scene, &mesh, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("material id 5"), std::string::npos) << last_error();

    mesh = {positions, 0, triangles, 1, nullptr, nullptr, &mat};
    EXPECT_EQ(stratum_scene_add_mesh(h.scene, &mesh, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("vertex_count is 0"), std::string::npos) << last_error();

    EXPECT_EQ(stratum_scene_add_instance(h.scene, 3, kIdentity), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("mesh_id 3"), std::string::npos) << last_error();
}

TEST(Api, BadMaterialLightAndCameraValuesAreNamed) {
    SceneHandle h;
    StratumMaterialDesc m{STRATUM_MATERIAL_DIFFUSE, {0.5f, 1.5f, 0.5f}, 1.0f, 0.0f, 0.5f, 1.5f, {0, 0, 0},
                          STRATUM_MICROFACET_GGX};
    EXPECT_EQ(stratum_scene_add_material(h.scene, &m, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("base_color[1] = 1.5"), std::string::npos) << last_error();

    StratumLightDesc l{};
    l.type = STRATUM_LIGHT_AREA_RECTANGLE;
    l.strength = 10;
    l.size_x = 0;
    l.size_y = 1;
    std::copy(kIdentity, kIdentity + 16, l.transform);
    EXPECT_EQ(stratum_scene_add_light(h.scene, &l), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("size_x"), std::string::npos) << last_error();

    StratumCameraDesc c{50, 36, 24, STRATUM_SENSOR_FIT_AUTO, 0, 0, 10.0f, 1.0f, {}, 0, 0, 0, 0, 0, 0};
    std::copy(kIdentity, kIdentity + 16, c.transform);
    EXPECT_EQ(stratum_scene_set_camera(h.scene, &c), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("clip_start"), std::string::npos) << last_error();
    c.clip_start = 0.1f;
    c.transform[3] = std::numeric_limits<float>::infinity();
    EXPECT_EQ(stratum_scene_set_camera(h.scene, &c), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("element 3"), std::string::npos) << last_error();
}

TEST(Api, UnknownSettingNamesAndValuesAreRejected) {
    SceneHandle h;
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(h.scene, &r), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_int(r, "sampels", 4), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("'sampels'"), std::string::npos) << last_error();
    EXPECT_EQ(stratum_renderer_set_string(r, "sampler", "no_such"), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("'no_such'"), std::string::npos) << last_error();
    EXPECT_EQ(stratum_renderer_set_int(r, "width", 0), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_renderer_set_float(r, "filter_width", std::nan("")), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_renderer_set_string(r, "filter_type", "gaussian"), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_renderer_set_int(r, "samples", 8), STRATUM_OK);
    // No camera: start fails cleanly.
    EXPECT_EQ(stratum_renderer_start(r), STRATUM_ERROR_INVALID_STATE);
    EXPECT_NE(last_error().find("camera"), std::string::npos) << last_error();
    float pixel[4];
    EXPECT_EQ(stratum_renderer_read_pixels(r, pixel, 4), STRATUM_ERROR_INVALID_ARGUMENT);
    stratum_renderer_destroy(r);
}

TEST(Api, NullPointersAreErrorsNotCrashes) {
    EXPECT_EQ(stratum_scene_create(nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_scene_add_material(nullptr, nullptr, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_renderer_start(nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    StratumScene* s = nullptr;
    EXPECT_EQ(stratum_scene_load("/nonexistent/scene.json", &s), STRATUM_ERROR_IO);
    EXPECT_EQ(s, nullptr);
    stratum_scene_destroy(nullptr);
    stratum_renderer_destroy(nullptr);
}

TEST(Api, LightIntegratorIsAcceptedAndBadIntegratorNamesAreRejected) {
    SceneHandle h;
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(h.scene, &r), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_string(r, "integrator", "light"), STRATUM_OK) << last_error();
    EXPECT_EQ(stratum_renderer_set_string(r, "integrator", "Light"), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("'Light'"), std::string::npos) << last_error();
    EXPECT_NE(last_error().find("light"), std::string::npos) << last_error();
    EXPECT_EQ(stratum_renderer_set_string(r, "integrator", "light_tracer"), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_renderer_set_int(r, "integrator", 1), STRATUM_ERROR_INVALID_ARGUMENT);
    bool listed = false;
    for (const char* name : setting_choices("integrator")) listed |= std::string(name) == "light";
    EXPECT_TRUE(listed);
    stratum_renderer_destroy(r);
}
