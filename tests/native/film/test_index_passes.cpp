// The Object and Material Index passes (IndexOB, IndexMA): each object's and material's pass
// index where a camera ray first meets an opaque surface, through transparent ones, 0 where it
// meets none; carried through the C ABI's instance description and
// stratum_scene_set_material_pass_index, live edits and captured scene files.
//
// The scene, seen by a pinhole camera at the origin looking down −Z (90° field of view) at
// 16 × 16 with a box filter of width 1 (every sample inside its pixel): two quads at z = −3
// covering the lower half of the frame, the left one (object 3, plain material 7) and the right
// one (object 5, a two-closure material 11); in front of the right one at z = −2, a Transparent
// quad (object 17, material 13), which the data passes see through. The upper half is background.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "render_helpers.h"

using namespace stratum_test;

namespace {

constexpr int kSize = 16;
constexpr uint32_t kLeftObject = 3, kRightObject = 5, kGlassObject = 17;
constexpr uint32_t kLeftMaterial = 7, kRightMaterial = 11, kGlassMaterial = 13;

StratumMaterialDesc diffuse(float r, float g, float b) {
    return {STRATUM_MATERIAL_DIFFUSE, {r, g, b}, 0.5f, 0, 0.5f, 1.5f, {0, 0, 0}, STRATUM_MICROFACET_GGX};
}

// A quad x in [x0, x1], y in [−10, 0] at depth z, facing the camera.
bool add_quad(StratumScene* scene, float x0, float x1, float z, uint32_t material, uint32_t pass_index) {
    const float positions[] = {x0, -10, z, x1, -10, z, x1, 0, z, x0, 0, z};
    const uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
    const uint32_t mats[] = {material, material};
    const StratumMeshDesc mesh{positions, 4, triangles, 2, nullptr, nullptr, mats};
    uint32_t mesh_id = 0;
    if (stratum_scene_add_mesh(scene, &mesh, &mesh_id) != STRATUM_OK) return false;
    StratumInstanceDesc instance{};
    instance.mesh_id = mesh_id;
    std::copy(kIdentity, kIdentity + 16, instance.transform);
    instance.visibility = STRATUM_VISIBLE_ALL;
    instance.pass_index = pass_index;
    return stratum_scene_add_instance_ex(scene, &instance) == STRATUM_OK;
}

StratumScene* make_index_scene() {
    StratumScene* scene = nullptr;
    if (stratum_scene_create(&scene) != STRATUM_OK) return nullptr;
    const StratumMaterialDesc left = diffuse(0.8f, 0.2f, 0.2f);
    const StratumClosureDesc right[2] = {{{0.5f, 0.5f, 0.5f}, diffuse(0.2f, 0.8f, 0.2f)},
                                         {{0.5f, 0.5f, 0.5f}, diffuse(0.2f, 0.2f, 0.8f)}};
    StratumMaterialDesc glass = diffuse(1, 1, 1);
    glass.model = STRATUM_MATERIAL_TRANSPARENT;
    const StratumCameraDesc camera = camera_at(0, 0, 0);
    const float background[3] = {0.5f, 0.5f, 0.5f};
    uint32_t ids[3] = {};
    const bool ok = stratum_scene_add_material(scene, &left, &ids[0]) == STRATUM_OK &&
                    stratum_scene_add_closure_material(scene, right, 2, &ids[1]) == STRATUM_OK &&
                    stratum_scene_add_material(scene, &glass, &ids[2]) == STRATUM_OK &&
                    stratum_scene_set_material_pass_index(scene, ids[0], kLeftMaterial) == STRATUM_OK &&
                    stratum_scene_set_material_pass_index(scene, ids[1], kRightMaterial) == STRATUM_OK &&
                    stratum_scene_set_material_pass_index(scene, ids[2], kGlassMaterial) == STRATUM_OK &&
                    add_quad(scene, -10, 0, -3, ids[0], kLeftObject) &&
                    add_quad(scene, 0, 10, -3, ids[1], kRightObject) &&
                    add_quad(scene, 0, 10, -2, ids[2], kGlassObject) &&
                    stratum_scene_set_camera(scene, &camera) == STRATUM_OK &&
                    stratum_scene_set_background(scene, background) == STRATUM_OK;
    if (!ok) {
        ADD_FAILURE() << stratum_last_error();
        stratum_scene_destroy(scene);
        return nullptr;
    }
    return scene;
}

struct IndexImages {
    std::vector<float> rgba, object, material;
};

// Renders `scene` at 4 samples; `passes` "" renders Combined only.
IndexImages render_indices(StratumScene* scene, const char* passes = "IndexOB,IndexMA") {
    IndexImages out;
    StratumRenderer* r = nullptr;
    EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    EXPECT_EQ(apply_settings(r, {{"width", kSize},
                                 {"height", kSize},
                                 {"samples", 4},
                                 {"filter_type", "box"},
                                 {"filter_width", 1.0},
                                 {"passes", passes}}),
              "");
    EXPECT_TRUE(render_to_end(r)) << stratum_last_error();
    out.rgba.resize(kSize * kSize * 4);
    EXPECT_EQ(stratum_renderer_read_pixels(r, out.rgba.data(), out.rgba.size()), STRATUM_OK);
    if (passes[0] != '\0') {
        out.object.resize(kSize * kSize);
        out.material.resize(kSize * kSize);
        EXPECT_EQ(stratum_renderer_read_pass(r, "IndexOB", out.object.data(), out.object.size()), STRATUM_OK);
        EXPECT_EQ(stratum_renderer_read_pass(r, "IndexMA", out.material.data(), out.material.size()),
                  STRATUM_OK);
    }
    stratum_renderer_destroy(r);
    return out;
}

// Every pixel holds exactly the index of what it sees: rows are stored bottom to top, so the
// quads (lower half of the frame) are rows 0..7; columns 0..7 are the left quad.
void expect_indices(const IndexImages& images, uint32_t left_object, uint32_t left_material,
                    uint32_t right_object, uint32_t right_material) {
    ASSERT_EQ(images.object.size(), static_cast<size_t>(kSize * kSize));
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            const bool quads = y < kSize / 2, left = x < kSize / 2;
            const float object = quads ? static_cast<float>(left ? left_object : right_object) : 0.0f;
            const float material = quads ? static_cast<float>(left ? left_material : right_material) : 0.0f;
            EXPECT_EQ(images.object[y * kSize + x], object) << "pixel " << x << ", " << y;
            EXPECT_EQ(images.material[y * kSize + x], material) << "pixel " << x << ", " << y;
        }
    }
}

}  // namespace

TEST(IndexPasses, HoldThePassIndicesOfTheFirstOpaqueSurfaceAndLeaveTheImageUnchanged) {
    StratumScene* scene = make_index_scene();
    ASSERT_NE(scene, nullptr);
    const IndexImages images = render_indices(scene);
    expect_indices(images, kLeftObject, kLeftMaterial, kRightObject, kRightMaterial);
    EXPECT_EQ(images.rgba, render_indices(scene, "").rgba);
    stratum_scene_destroy(scene);
}

TEST(IndexPasses, FollowLiveEditsAndAClosureEditKeepsTheMaterialsIndex) {
    StratumScene* scene = make_index_scene();
    ASSERT_NE(scene, nullptr);
    // Instances in the order added: left quad 0, right quad 1.
    StratumInstanceDesc left{};
    std::copy(kIdentity, kIdentity + 16, left.transform);
    left.visibility = STRATUM_VISIBLE_ALL;
    left.pass_index = 4;
    ASSERT_EQ(stratum_scene_set_instance(scene, 0, &left), STRATUM_OK) << stratum_last_error();
    ASSERT_EQ(stratum_scene_set_material_pass_index(scene, 1, 9), STRATUM_OK);
    const StratumMaterialDesc red = diffuse(0.9f, 0.1f, 0.1f);
    ASSERT_EQ(stratum_scene_set_material(scene, 0, &red), STRATUM_OK);
    expect_indices(render_indices(scene), 4, kLeftMaterial, kRightObject, 9);
    stratum_scene_destroy(scene);
}

TEST(IndexPasses, SurviveACapturedSceneFile) {
    StratumScene* scene = make_index_scene();
    ASSERT_NE(scene, nullptr);
    const std::string path = testing::TempDir() + "stratum_index_passes_" +
                             testing::UnitTest::GetInstance()->current_test_info()->name() + ".json";
    ASSERT_EQ(stratum_scene_save(scene, path.c_str()), STRATUM_OK) << stratum_last_error();
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(path.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    expect_indices(render_indices(loaded), kLeftObject, kLeftMaterial, kRightObject, kRightMaterial);
    std::remove(path.c_str());
    stratum_scene_destroy(loaded);
    stratum_scene_destroy(scene);
}

TEST(IndexPasses, AnIndexAFloatCannotHoldOrAMissingMaterialIsRefusedByName) {
    StratumScene* scene = make_index_scene();
    ASSERT_NE(scene, nullptr);
    EXPECT_EQ(stratum_scene_set_material_pass_index(scene, 0, STRATUM_MAX_PASS_INDEX), STRATUM_OK);
    EXPECT_EQ(stratum_scene_set_material_pass_index(scene, 0, STRATUM_MAX_PASS_INDEX + 1),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("material pass_index = 16777217"), std::string::npos)
        << stratum_last_error();
    EXPECT_EQ(stratum_scene_set_material_pass_index(scene, 3, 1), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("material 3 does not exist"), std::string::npos)
        << stratum_last_error();
    StratumInstanceDesc instance{};
    std::copy(kIdentity, kIdentity + 16, instance.transform);
    instance.visibility = STRATUM_VISIBLE_ALL;
    instance.pass_index = STRATUM_MAX_PASS_INDEX + 1;
    EXPECT_EQ(stratum_scene_add_instance_ex(scene, &instance), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("instance pass_index = 16777217"), std::string::npos)
        << stratum_last_error();
    // The refused edits changed nothing.
    expect_indices(render_indices(scene), kLeftObject, STRATUM_MAX_PASS_INDEX, kRightObject, kRightMaterial);
    stratum_scene_destroy(scene);
}
