// Instancing (a two-level Embree BVH): a placed mesh shades exactly as the same mesh flattened to
// world space, 10 000 placements of one mesh cost one mesh of memory, hits report uv, dpdu,
// visibility and holdout from the prototype and its transform, and ray masks select instances.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "render_helpers.h"
#include "render_scene/render_scene.h"

using namespace stratum_test;

namespace {

// Row-major object-to-world: rotation by `angle` about the unit axis (ax, ay, az), then a scale
// (sx, sy, sz) applied first, then a translation.
std::vector<float> placement(float angle, float ax, float ay, float az, float sx, float sy, float sz,
                             float tx, float ty, float tz) {
    const float c = std::cos(angle), s = std::sin(angle), t = 1 - c;
    const float r[3][3] = {{t * ax * ax + c, t * ax * ay - s * az, t * ax * az + s * ay},
                           {t * ax * ay + s * az, t * ay * ay + c, t * ay * az - s * ax},
                           {t * ax * az - s * ay, t * ay * az + s * ax, t * az * az + c}};
    const float scale[3] = {sx, sy, sz}, tr[3] = {tx, ty, tz};
    std::vector<float> m(16, 0.0f);
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) m[4 * i + j] = r[i][j] * scale[j];
        m[4 * i + 3] = tr[i];
    }
    m[15] = 1;
    return m;
}

struct TestMesh {
    std::vector<float> positions, normals, uvs;
    std::vector<uint32_t> triangles, materials;
    StratumMeshDesc desc() const {
        return {positions.data(),
                static_cast<uint32_t>(positions.size() / 3),
                triangles.data(),
                static_cast<uint32_t>(triangles.size() / 3),
                normals.empty() ? nullptr : normals.data(),
                uvs.empty() ? nullptr : uvs.data(),
                materials.data()};
    }
};

// A sphere with smooth corner normals (the unit position) and material `material`.
TestMesh smooth_sphere(uint32_t rings, uint32_t material) {
    const SphereMesh s = make_sphere(1.0f, rings, 2 * rings);
    TestMesh m{s.positions, {}, {}, s.triangles, {}};
    for (uint32_t v : s.triangles)
        m.normals.insert(m.normals.end(), &s.positions[3 * v], &s.positions[3 * v] + 3);
    m.materials.assign(s.triangles.size() / 3, material);
    return m;
}

// The axis-aligned square [-h, h]^2 at height z, facing +Z, uv (0,0) at (-h,-h) to (1,1) at (h,h).
TestMesh square(float h, float z, uint32_t material) {
    TestMesh m;
    m.positions = {-h, -h, z, h, -h, z, h, h, z, -h, h, z};
    m.triangles = {0, 1, 2, 0, 2, 3};
    m.uvs = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
    m.materials = {material, material};
    return m;
}

// The mesh with its positions and corner normals mapped by `t` (normals by the cofactor matrix).
TestMesh flattened(const TestMesh& mesh, const std::vector<float>& t) {
    const stratum::Transform m = stratum::Transform::from_row_major(t.data());
    TestMesh out = mesh;
    for (size_t i = 0; i < mesh.positions.size(); i += 3) {
        const stratum::Vec3 p = m.point({mesh.positions[i], mesh.positions[i + 1], mesh.positions[i + 2]});
        out.positions[i] = p.x, out.positions[i + 1] = p.y, out.positions[i + 2] = p.z;
    }
    for (size_t i = 0; i < mesh.normals.size(); i += 3) {
        const stratum::Vec3 n = m.normal({mesh.normals[i], mesh.normals[i + 1], mesh.normals[i + 2]});
        out.normals[i] = n.x, out.normals[i + 1] = n.y, out.normals[i + 2] = n.z;
    }
    return out;
}

constexpr StratumMaterialDesc kGrey{STRATUM_MATERIAL_DIFFUSE, {0.6f, 0.6f, 0.6f}, 1, 0, 0, 1.5f, {0, 0, 0},
                                    STRATUM_MICROFACET_GGX};
constexpr StratumMaterialDesc kGlow{STRATUM_MATERIAL_EMISSION, {0, 0, 0}, 1, 0, 0, 1.5f, {1, 1, 1},
                                    STRATUM_MICROFACET_GGX};

// Floor, a small emissive square overhead and three placements of a smooth sphere: either as
// instances of one mesh or as three meshes flattened to world space.
StratumScene* three_spheres(bool instanced) {
    StratumScene* scene = nullptr;
    EXPECT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    uint32_t grey = 0, glow = 0, id = 0;
    stratum_scene_add_material(scene, &kGrey, &grey);
    stratum_scene_add_material(scene, &kGlow, &glow);
    const TestMesh floor = square(4, -1, grey), lamp = square(0.5f, 3, glow);
    for (const TestMesh* m : {&floor, &lamp}) {
        const StratumMeshDesc d = m->desc();
        stratum_scene_add_mesh(scene, &d, &id);
        stratum_scene_add_instance(scene, id, kIdentity);
    }
    const std::vector<std::vector<float>> places = {
        placement(0.7f, 0, 0, 1, 0.5f, 0.5f, 0.5f, -1.2f, 0, -0.5f),
        placement(1.1f, 0.6f, 0, 0.8f, 0.3f, 0.6f, 0.4f, 0, 0.5f, -0.6f),
        placement(-0.4f, 1, 0, 0, 0.7f, 0.7f, 0.7f, 1.3f, -0.3f, -0.3f)};
    const TestMesh sphere = smooth_sphere(12, grey);
    if (instanced) {
        const StratumMeshDesc d = sphere.desc();
        stratum_scene_add_mesh(scene, &d, &id);
        for (const auto& p : places) EXPECT_EQ(stratum_scene_add_instance(scene, id, p.data()), STRATUM_OK);
    } else {
        for (const auto& p : places) {
            const TestMesh flat = flattened(sphere, p);
            const StratumMeshDesc d = flat.desc();
            stratum_scene_add_mesh(scene, &d, &id);
            stratum_scene_add_instance(scene, id, kIdentity);
        }
    }
    const float bg[3] = {0.2f, 0.2f, 0.25f};
    stratum_scene_set_background(scene, bg);
    const StratumCameraDesc camera = camera_at(0, 0, 4);
    stratum_scene_set_camera(scene, &camera);
    return scene;
}

}  // namespace

// Embree intersects an instance in object space, a flattened mesh in world space: the hit
// distance and barycentrics differ in the last bits, so the images are not bit-identical; the
// shading of a hit uses the same arithmetic (world vertices first, then interpolation), so the
// difference stays float noise. Per pixel, a sample can only change a lot where a ray grazes
// a silhouette and hits in one scene but misses in the other: that happens in a handful of
// samples, bounded here by the mean over the image (1e-3 relative) and the share of pixels
// that differ by more than 1e-3 relative (2%). Measured: 9213 of the 9216 values are
// bit-identical and none differs by more than 1e-3.
TEST(Instancing, InstancesRenderAsTheFlattenedMeshes) {
    StratumScene* inst = three_spheres(true);
    StratumScene* flat = three_spheres(false);
    const auto a = render(inst, {{"width", 48}, {"height", 48}, {"samples", 16}, {"max_bounces", 3}});
    const auto b = render(flat, {{"width", 48}, {"height", 48}, {"samples", 16}, {"max_bounces", 3}});
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    ASSERT_FALSE(a.rgba.empty());
    double sum_a = 0, sum_b = 0;
    size_t differing = 0, identical = 0;
    for (size_t i = 0; i < a.rgba.size(); ++i) {
        sum_a += a.rgba[i];
        sum_b += b.rgba[i];
        if (std::abs(a.rgba[i] - b.rgba[i]) > 1e-3f * std::max(1.0f, std::abs(b.rgba[i]))) ++differing;
        if (a.rgba[i] == b.rgba[i]) ++identical;
    }
    std::printf("instanced vs flattened: mean %.6f vs %.6f, %zu of %zu values differ > 1e-3, %zu identical\n",
                sum_a / static_cast<double>(a.rgba.size()), sum_b / static_cast<double>(b.rgba.size()),
                differing, a.rgba.size(), identical);
    EXPECT_NEAR(sum_a, sum_b, 1e-3 * sum_b);
    EXPECT_LT(differing, a.rgba.size() / 50);
    stratum_scene_destroy(inst);
    stratum_scene_destroy(flat);
}

namespace {

// Resident set size in bytes (Linux /proc/self/statm, second field in pages).
double resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    double size = 0, resident = 0;
    statm >> size >> resident;
    return resident * 4096.0;
}

}  // namespace

// 10 000 placements of a 1 024-triangle sphere: one object-space BVH and 10 000 instance records.
// Flattened, the 10.24M world-space triangles would need at least 10.24M x (36 bytes of vertices
// + 12 of indices) = 490 MB before any BVH; the instanced scene must stay far below (100 MB
// bound; the measured figures are printed and noted in docs/cycles_models.md). A ray straight
// down onto each placement's centre hits that placement.
TEST(Instancing, TenThousandInstancesCostOneMesh) {
    using namespace stratum;
    Scene scene;
    scene.materials.push_back(SceneMaterial{{WeightedClosure{Rgb(1.0f), Material{}}}});
    const SphereMesh s = make_sphere(0.4f, 16, 32);  // 16 * 32 * 2 = 1024 triangles
    Mesh mesh;
    for (size_t i = 0; i < s.positions.size(); i += 3)
        mesh.positions.push_back({s.positions[i], s.positions[i + 1], s.positions[i + 2]});
    for (size_t i = 0; i < s.triangles.size(); i += 3)
        mesh.triangles.push_back({s.triangles[i], s.triangles[i + 1], s.triangles[i + 2]});
    mesh.material_ids.assign(mesh.triangles.size(), 0);
    ASSERT_EQ(mesh.triangles.size(), 1024u);
    scene.meshes.push_back(std::move(mesh));
    for (int i = 0; i < 100; ++i) {
        for (int j = 0; j < 100; ++j) {
            Instance inst{};
            inst.mesh_id = 0;
            inst.object_to_world.m[3] = static_cast<float>(i);
            inst.object_to_world.m[7] = static_cast<float>(j);
            inst.visibility = 31;
            scene.instances.push_back(inst);
        }
    }
    const double before = resident_bytes();
    const auto t0 = std::chrono::steady_clock::now();
    const RenderScene rs(scene);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double grown = resident_bytes() - before;
    std::printf("10000 instances x 1024 triangles: BVH build %.3f s, resident +%.1f MB\n", seconds,
                grown / 1e6);
    EXPECT_LT(grown, 100e6);
    size_t hits = 0;
    for (int i = 0; i < 100; ++i) {
        for (int j = 0; j < 100; ++j) {
            SurfaceHit hit;
            const Vec3 centre(static_cast<float>(i), static_cast<float>(j), 0.0f);
            if (rs.intersect(centre + Vec3(0, 0, 5), Vec3(0, 0, -1), 0.0f, kInfinity, &hit) &&
                std::abs(hit.position.z - 0.4f) < 1e-3f && std::abs(hit.position.x - centre.x) < 1e-3f &&
                std::abs(hit.position.y - centre.y) < 1e-3f)
                ++hits;
        }
    }
    EXPECT_EQ(hits, 10000u);
}
