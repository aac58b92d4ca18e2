// stratum_scene_add_instances: a batch places what one stratum_scene_add_instance per row
// places, and a rejected row adds nothing, names its value and is written to out_failed_index.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "scene_handle.h"

using stratum_test::SceneHandle;

namespace {

using Matrix = std::array<float, 16>;

constexpr Matrix kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Matrix translated(float x, float y, float z) {
    Matrix m = kIdentity;
    m[3] = x;
    m[7] = y;
    m[11] = z;
    return m;
}

// One material and two one-triangle meshes (ids 0 and 1).
void add_meshes(StratumScene* s) {
    StratumMaterialDesc m{STRATUM_MATERIAL_DIFFUSE, {0.5f, 0.5f, 0.5f}, 1.0f, 0.0f, 0.5f, 1.5f, {0, 0, 0},
                          STRATUM_MICROFACET_GGX};
    uint32_t mat = 99;
    ASSERT_EQ(stratum_scene_add_material(s, &m, &mat), STRATUM_OK);
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t triangles[] = {0, 1, 2};
    const StratumMeshDesc mesh{positions, 3, triangles, 1, nullptr, nullptr, &mat};
    for (int i = 0; i < 2; ++i) ASSERT_EQ(stratum_scene_add_mesh(s, &mesh, nullptr), STRATUM_OK);
}

// Whether instance `index` exists: a live edit of it is accepted (with the values it has).
bool has_instance(StratumScene* s, uint32_t index, const Matrix& m, uint32_t mesh_id) {
    StratumInstanceDesc d{};
    d.mesh_id = mesh_id;
    std::copy(m.begin(), m.end(), d.transform);
    d.visibility = STRATUM_VISIBLE_ALL;
    return stratum_scene_set_instance(s, index, &d) == STRATUM_OK;
}

std::string saved(const StratumScene* s, const std::string& name) {
    const auto path = std::filesystem::temp_directory_path() / name;
    EXPECT_EQ(stratum_scene_save(s, path.c_str()), STRATUM_OK) << stratum_last_error();
    std::ifstream in(path, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::filesystem::remove(path);
    return bytes;
}

}  // namespace

TEST(AddInstances, BatchSavesTheSameSceneAsOneCallPerInstance) {
    const std::vector<uint32_t> ids = {0, 1, 1, 0};
    std::vector<float> transforms;
    for (int i = 0; i < 4; ++i) {
        const Matrix m = translated(0.5f * static_cast<float>(i), -0.25f * static_cast<float>(i), 2.0f);
        transforms.insert(transforms.end(), m.begin(), m.end());
    }
    SceneHandle one_by_one, batch;
    add_meshes(one_by_one.scene);
    add_meshes(batch.scene);
    for (size_t i = 0; i < ids.size(); ++i)
        ASSERT_EQ(stratum_scene_add_instance(one_by_one.scene, ids[i], transforms.data() + 16 * i),
                  STRATUM_OK);
    uint32_t failed = 7;
    ASSERT_EQ(stratum_scene_add_instances(batch.scene, 4, ids.data(), transforms.data(), &failed), STRATUM_OK)
        << stratum_last_error();
    EXPECT_EQ(failed, UINT32_MAX);
    EXPECT_EQ(saved(batch.scene, "stratum_add_instances_batch.json"),
              saved(one_by_one.scene, "stratum_add_instances_single.json"));
}

TEST(AddInstances, RejectedRowAddsNothingAndIsNamed) {
    SceneHandle h;
    add_meshes(h.scene);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    struct Case {
        uint32_t bad_row;
        uint32_t mesh_id;  // of the bad row
        Matrix transform;  // of the bad row
        const char* named;
    };
    Matrix nan_element = kIdentity;
    nan_element[6] = nan;
    Matrix projective = kIdentity;
    projective[14] = 0.5f;
    const Case cases[] = {
        {2, 5, kIdentity, "instance mesh_id 5 out of range [0, 2)"},
        {1, 0, nan_element, "instance transform element 6 = nan is not finite"},
        {3, 1, projective, "instance transform is not affine"},
        {0, 0, translated(2e30f, 0, 0), "places its origin at"},
    };
    for (const Case& c : cases) {
        std::vector<uint32_t> ids(4, 0);
        std::vector<float> transforms;
        for (int i = 0; i < 4; ++i) transforms.insert(transforms.end(), kIdentity.begin(), kIdentity.end());
        ids[c.bad_row] = c.mesh_id;
        std::copy(c.transform.begin(), c.transform.end(), transforms.begin() + 16 * c.bad_row);
        uint32_t failed = 7;
        EXPECT_EQ(stratum_scene_add_instances(h.scene, 4, ids.data(), transforms.data(), &failed),
                  STRATUM_ERROR_INVALID_ARGUMENT);
        const std::string error = stratum_last_error();
        EXPECT_EQ(error.rfind("stratum_scene_add_instances: ", 0), 0u) << error;
        EXPECT_NE(error.find(c.named), std::string::npos) << error;
        EXPECT_EQ(failed, c.bad_row) << error;
        // All or nothing: the rows before the bad one were not added either.
        EXPECT_FALSE(has_instance(h.scene, 0, kIdentity, 0)) << c.named;
    }
    // The out index is optional; a good batch after refused ones starts at instance 0.
    const uint32_t ids[] = {1, 0};
    const std::vector<float> transforms = [] {
        std::vector<float> t(kIdentity.begin(), kIdentity.end());
        t.insert(t.end(), kIdentity.begin(), kIdentity.end());
        return t;
    }();
    ASSERT_EQ(stratum_scene_add_instances(h.scene, 2, ids, transforms.data(), nullptr), STRATUM_OK);
    EXPECT_TRUE(has_instance(h.scene, 1, kIdentity, 0));
    EXPECT_FALSE(has_instance(h.scene, 2, kIdentity, 0));
}

TEST(AddInstances, NullArraysAreErrorsUnlessTheBatchIsEmpty) {
    SceneHandle h;
    add_meshes(h.scene);
    uint32_t failed = 7;
    EXPECT_EQ(stratum_scene_add_instances(h.scene, 0, nullptr, nullptr, &failed), STRATUM_OK);
    EXPECT_EQ(failed, UINT32_MAX);
    EXPECT_EQ(stratum_scene_add_instances(h.scene, 3, nullptr, kIdentity.data(), &failed),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("NULL"), std::string::npos);
    EXPECT_EQ(failed, UINT32_MAX);  // no row was rejected: the call was
    const uint32_t id = 0;
    EXPECT_EQ(stratum_scene_add_instances(h.scene, 1, &id, nullptr, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_scene_add_instances(nullptr, 1, &id, kIdentity.data(), &failed),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_FALSE(has_instance(h.scene, 0, kIdentity, 0));
}
