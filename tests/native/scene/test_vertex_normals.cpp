// Vertex normals (StratumMeshDesc::vertex_normals): a smooth mesh given one normal per vertex
// renders exactly as the same mesh given those normals at every triangle corner (the hit
// interpolates the same three unit normals with the same arithmetic), and bad input is named.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <cmath>
#include <string>
#include <vector>

#include "render_helpers.h"

namespace {

using stratum_test::camera_at;
using stratum_test::kIdentity;
using stratum_test::make_sphere;
using stratum_test::render;

// A smooth sphere (normals = positions / r) lit by a sun, seen from outside, rendered with its
// normals given per vertex or per corner.
std::vector<float> render_sphere(bool per_vertex) {
    const auto sphere = make_sphere(1.0f, 12, 24);
    std::vector<float> vertex_normals(sphere.positions);  // r = 1: the position is the normal
    std::vector<float> corner_normals;
    for (uint32_t v : sphere.triangles)
        corner_normals.insert(corner_normals.end(),
                              {vertex_normals[3 * v], vertex_normals[3 * v + 1], vertex_normals[3 * v + 2]});
    StratumScene* scene = nullptr;
    EXPECT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    const StratumMaterialDesc grey{STRATUM_MATERIAL_DIFFUSE, {0.8f, 0.8f, 0.8f}, 1, 0, 0, 1.5f, {0, 0, 0}, 0};
    uint32_t mat = 0, mesh = 0;
    EXPECT_EQ(stratum_scene_add_material(scene, &grey, &mat), STRATUM_OK);
    const std::vector<uint32_t> ids(sphere.triangles.size() / 3, mat);
    StratumMeshDesc d{};
    d.positions = sphere.positions.data();
    d.vertex_count = static_cast<uint32_t>(sphere.positions.size() / 3);
    d.triangles = sphere.triangles.data();
    d.triangle_count = static_cast<uint32_t>(ids.size());
    d.material_ids = ids.data();
    (per_vertex ? d.vertex_normals : d.corner_normals) =
        per_vertex ? vertex_normals.data() : corner_normals.data();
    EXPECT_EQ(stratum_scene_add_mesh(scene, &d, &mesh), STRATUM_OK);
    EXPECT_EQ(stratum_scene_add_instance(scene, mesh, kIdentity), STRATUM_OK);
    StratumLightDesc sun{};
    sun.type = STRATUM_LIGHT_SUN;
    sun.color[0] = sun.color[1] = sun.color[2] = 1.0f;
    sun.strength = 3.0f;
    std::copy(kIdentity, kIdentity + 16, sun.transform);
    EXPECT_EQ(stratum_scene_add_light(scene, &sun), STRATUM_OK);
    const StratumCameraDesc camera = camera_at(0.0f, 0.0f, 3.0f);
    EXPECT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK);
    auto out = render(scene, {{"width", 24}, {"height", 24}, {"samples", 4}, {"max_bounces", 0}});
    stratum_scene_destroy(scene);
    return out.rgba;
}

TEST(VertexNormals, RenderExactlyAsTheSameNormalsPerCorner) {
    const std::vector<float> per_vertex = render_sphere(true), per_corner = render_sphere(false);
    ASSERT_EQ(per_vertex.size(), 24u * 24u * 4u);
    EXPECT_EQ(per_vertex, per_corner);
    // The sphere is smooth-shaded: neighbouring lit pixels differ, and the centre is lit.
    EXPECT_GT(per_vertex[4 * (12 * 24 + 12)], 0.1f);
}

TEST(VertexNormals, BadInputIsNamed) {
    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    const StratumMaterialDesc grey{STRATUM_MATERIAL_DIFFUSE, {0.8f, 0.8f, 0.8f}, 1, 0, 0, 1.5f, {0, 0, 0}, 0};
    uint32_t mat = 0, mesh = 0;
    ASSERT_EQ(stratum_scene_add_material(scene, &grey, &mat), STRATUM_OK);
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t triangle[3] = {0, 1, 2};
    float normals[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    const float corners[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    StratumMeshDesc d{positions, 3, triangle, 1, nullptr, nullptr, &mat, normals};
    d.corner_normals = corners;
    EXPECT_EQ(stratum_scene_add_mesh(scene, &d, &mesh), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("vertex_normals"), std::string::npos);
    d.corner_normals = nullptr;
    normals[4] = std::nanf("");
    EXPECT_EQ(stratum_scene_add_mesh(scene, &d, &mesh), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("vertex normal 1"), std::string::npos);
    stratum_scene_destroy(scene);
}

}  // namespace
