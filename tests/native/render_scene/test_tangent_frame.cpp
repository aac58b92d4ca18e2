// Normal maps in MikkTSpace tangent frames (issue 12 point 10): the mesh's corner tangents
// through the C ABI and the scene file, and the frame at a hit against Cycles' formula
// (svm_node_normal_map, kernel/svm/tex_coord.h) evaluated by hand in object space:
//   T, sign, N interpolated (unnormalised), B = sign cross(N, T),
//   N' = normalize(M^-T (c.x T + c.y B + c.z N)).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "render_scene/material_texturing.h"
#include "render_scene/render_scene.h"
#include "stratum/stratum.h"

using namespace stratum;

namespace {

// The unit square [0,1]^2 at z = 0 as triangles (0,1,2), (0,2,3), with per-vertex normals tilted
// apart and per-vertex tangents turning, expanded to corners (signs: -1 at vertex 3).
struct TangentSquare {
    std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    std::vector<uint32_t> triangles = {0, 1, 2, 0, 2, 3};
    std::array<Vec3, 4> normals = {Vec3(0.1f, 0.0f, 1.0f), Vec3(0.0f, 0.1f, 1.0f), Vec3(-0.1f, 0.0f, 1.0f),
                                   Vec3(0.0f, -0.2f, 1.0f)};
    std::array<Vec3, 4> tangents = {Vec3(1.0f, 0.0f, 0.0f), Vec3(std::cos(0.2f), std::sin(0.2f), 0.0f),
                                    Vec3(std::cos(0.4f), std::sin(0.4f), 0.1f), Vec3(1.0f, 0.1f, 0.0f)};
    std::array<float, 4> signs = {1.0f, 1.0f, 1.0f, -1.0f};

    std::vector<float> corner_tangents() const {
        std::vector<float> out;
        for (uint32_t v : triangles)
            out.insert(out.end(), {tangents[v].x, tangents[v].y, tangents[v].z, signs[v]});
        return out;
    }
    std::vector<float> vertex_normals() const {
        std::vector<float> out;
        for (Vec3 n : normals) {
            const Vec3 u = normalize(n);
            out.insert(out.end(), {u.x, u.y, u.z});
        }
        return out;
    }
};

// Rotation about z by `angle` after the scale (sx, sy, 1): M = R S, so M^-T = R S^-1.
Transform rotated_scaled(float angle, float sx, float sy) {
    const float c = std::cos(angle), s = std::sin(angle);
    Transform t;
    t.m = {c * sx, -s * sy, 0, 0.5f, s * sx, c * sy, 0, -0.25f, 0, 0, 1, 0};
    return t;
}

}  // namespace

TEST(TangentFrame, HitFrameIsCyclesObjectSpaceFrameUnderNonUniformScale) {
    const TangentSquare sq;
    Scene scene;
    scene.materials.push_back(SceneMaterial{{WeightedClosure{Rgb(1.0f), Material{}}}});
    Mesh mesh;
    for (size_t i = 0; i < 4; ++i)
        mesh.positions.push_back(Vec3(sq.positions[3 * i], sq.positions[3 * i + 1], sq.positions[3 * i + 2]));
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    for (Vec3 n : sq.normals) mesh.vertex_normals.push_back(normalize(n));
    for (uint32_t v : sq.triangles) {
        mesh.corner_tangents.push_back(sq.tangents[v]);
        mesh.corner_signs.push_back(sq.signs[v]);
    }
    mesh.material_ids = {0, 0};
    scene.meshes.push_back(mesh);
    const float angle = 0.7f, sx = 2.0f, sy = 0.5f;
    Instance inst{};
    inst.mesh_id = 0;
    inst.object_to_world = inst.object_to_world_end = rotated_scaled(angle, sx, sy);
    scene.instances.push_back(inst);
    const RenderScene rs(scene);

    // Object point (0.3, 0.6) lies in triangle (0, 2, 3) with barycentrics 0.4, 0.3, 0.3.
    const Vec3 world = inst.object_to_world.point(Vec3(0.3f, 0.6f, 0.0f));
    SurfaceHit hit;
    ASSERT_TRUE(rs.intersect(world + Vec3(0, 0, 5), Vec3(0, 0, -1), 0.0f, kInfinity, &hit, RayQuery{}));
    ASSERT_TRUE(hit.tangent_frame.mikktspace);
    const float b[3] = {0.4f, 0.3f, 0.3f};
    const uint32_t v[3] = {0, 2, 3};
    Vec3 t(0.0f, 0.0f, 0.0f), n(0.0f, 0.0f, 0.0f);
    float sign = 0.0f;
    for (int i = 0; i < 3; ++i) {
        t = t + sq.tangents[v[i]] * b[i];
        n = n + normalize(sq.normals[v[i]]) * b[i];
        sign += sq.signs[v[i]] * b[i];
    }
    const Vec3 bitangent = cross(n, t) * sign;
    const Rgb texel(0.65f, 0.4f, 0.95f);  // c = 2 texel - 1 = (0.3, -0.2, 0.9)
    const Vec3 c(0.3f, -0.2f, 0.9f);
    const Vec3 object = t * c.x + bitangent * c.y + n * c.z;
    // M^-T = R S^-1: divide by the scale, then rotate.
    const Vec3 scaled(object.x / sx, object.y / sy, object.z);
    const Vec3 expected = normalize(Vec3(std::cos(angle) * scaled.x - std::sin(angle) * scaled.y,
                                         std::sin(angle) * scaled.x + std::cos(angle) * scaled.y, scaled.z));
    const Vec3 got = apply_normal_map(texel, 1.0f, hit.shading_normal, hit.tangent_frame);
    EXPECT_NEAR(got.x, expected.x, 1e-5f);
    EXPECT_NEAR(got.y, expected.y, 1e-5f);
    EXPECT_NEAR(got.z, expected.z, 1e-5f);
    // A flat texel (0.5, 0.5, 1) gives the frame's own normal, M^-T times the interpolated N.
    const Vec3 flat = apply_normal_map(Rgb(0.5f, 0.5f, 1.0f), 1.0f, hit.shading_normal, hit.tangent_frame);
    EXPECT_NEAR(dot(flat, normalize(hit.tangent_frame.normal)), 1.0f, 1e-6f);
}

TEST(TangentFrame, AbiTakesCornerTangentsRejectsNonFiniteAndTheSceneFileKeepsThem) {
    const TangentSquare sq;
    const std::vector<float> tangents = sq.corner_tangents(), normals = sq.vertex_normals();
    const std::vector<uint32_t> materials = {0, 0};
    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    StratumMaterialDesc material{};
    material.base_color[0] = material.base_color[1] = material.base_color[2] = 0.8f;
    material.roughness = 0.5f;
    material.ior = 1.45f;
    ASSERT_EQ(stratum_scene_add_material(scene, &material, nullptr), STRATUM_OK) << stratum_last_error();
    StratumMeshDesc d{};
    d.positions = sq.positions.data();
    d.vertex_count = 4;
    d.triangles = sq.triangles.data();
    d.triangle_count = 2;
    d.material_ids = materials.data();
    d.vertex_normals = normals.data();
    d.corner_tangents = tangents.data();
    ASSERT_EQ(stratum_scene_add_mesh(scene, &d, nullptr), STRATUM_OK) << stratum_last_error();

    std::vector<float> bad = tangents;
    bad[4 * 4 + 3] = NAN;  // corner 4's sign
    d.corner_tangents = bad.data();
    EXPECT_EQ(stratum_scene_add_mesh(scene, &d, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("corner tangent 4"), std::string::npos)
        << stratum_last_error();

    const std::string path = ::testing::TempDir() + "tangent_square.json";
    ASSERT_EQ(stratum_scene_save(scene, path.c_str()), STRATUM_OK) << stratum_last_error();
    stratum_scene_destroy(scene);
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(path.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    const std::string again = ::testing::TempDir() + "tangent_square_again.json";
    ASSERT_EQ(stratum_scene_save(loaded, again.c_str()), STRATUM_OK);
    stratum_scene_destroy(loaded);
    std::ifstream a(path), b(again);
    const std::string first{std::istreambuf_iterator<char>(a), std::istreambuf_iterator<char>()};
    const std::string second{std::istreambuf_iterator<char>(b), std::istreambuf_iterator<char>()};
    EXPECT_EQ(first, second);
    EXPECT_NE(first.find("\"corner_tangents\":[1.0,0.0,0.0,1.0"), std::string::npos) << first.substr(0, 400);
}
