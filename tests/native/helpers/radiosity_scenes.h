// Scenes of the radiosity tests, built natively (stratum::Scene, then RenderScene) where a test
// inspects patches and form factors, and the closed-form references they are checked against.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "render_helpers.h"
#include "render_scene/render_scene.h"
#include "scene/scene.h"

namespace stratum_test {

// A Lambertian material of albedo k (grey) emitting `emission` (grey radiance).
inline stratum::SceneMaterial lambert(float k, float emission = 0.0f) {
    stratum::Material m{};
    m.model = STRATUM_MATERIAL_DIFFUSE;
    m.base_color = stratum::Rgb(k);
    m.roughness = 1.0f;
    m.ior = 1.5f;
    m.emission = stratum::Rgb(emission);
    return stratum::SceneMaterial{{stratum::WeightedClosure{stratum::Rgb(1.0f), m}}};
}

// Adds a mesh of `positions` (x, y, z flat) and `triangles` (flat) with one material, placed
// once at the identity.
inline void add_mesh(stratum::Scene& scene, const std::vector<float>& positions,
                     const std::vector<uint32_t>& triangles, uint32_t material) {
    stratum::Mesh mesh;
    for (size_t i = 0; i < positions.size(); i += 3)
        mesh.positions.push_back({positions[i], positions[i + 1], positions[i + 2]});
    for (size_t i = 0; i < triangles.size(); i += 3)
        mesh.triangles.push_back({triangles[i], triangles[i + 1], triangles[i + 2]});
    mesh.material_ids.assign(mesh.triangles.size(), material);
    stratum::Instance inst{};
    inst.mesh_id = static_cast<uint32_t>(scene.meshes.size());
    inst.visibility = stratum::kVisibleAll;
    scene.meshes.push_back(std::move(mesh));
    scene.instances.push_back(inst);
}

// The cube [−1, 1]³, each face a quad (two triangles) of its own mesh, wound outward; the faces
// share their edges' vertices exactly, so the mesh is closed (Embree's robust mode is watertight).
inline stratum::Scene closed_cube(float k, float emission = 0.0f) {
    stratum::Scene scene;
    scene.materials.push_back(lambert(k, emission));
    const float faces[6][12] = {
        {1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1}, {-1, -1, -1, -1, -1, 1, -1, 1, 1, -1, 1, -1},
        {-1, 1, -1, -1, 1, 1, 1, 1, 1, 1, 1, -1}, {-1, -1, -1, 1, -1, -1, 1, -1, 1, -1, -1, 1},
        {-1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1}, {-1, -1, -1, -1, 1, -1, 1, 1, -1, 1, -1, -1},
    };
    for (const auto& f : faces) add_mesh(scene, std::vector<float>(f, f + 12), {0, 1, 2, 0, 2, 3}, 0);
    return scene;
}

// Which face of closed_cube a point on it lies on: 0 +x, 1 −x, 2 +y, 3 −y, 4 +z, 5 −z.
inline int cube_face(stratum::Vec3 p) {
    const float ax = std::abs(p.x), ay = std::abs(p.y), az = std::abs(p.z);
    if (ax >= ay && ax >= az) return p.x > 0 ? 0 : 1;
    if (ay >= az) return p.y > 0 ? 2 : 3;
    return p.z > 0 ? 4 : 5;
}

// Form factor between two parallel, directly opposed rectangles a × b at distance c (Howell's
// catalogue C-11; Cohen & Wallace 1993, Appendix).
inline double parallel_rectangles_form_factor(double a, double b, double c) {
    const double x = a / c, y = b / c, pi = 3.14159265358979323846;
    return 2.0 / (pi * x * y) *
           (std::log(std::sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y))) +
            x * std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y)) +
            y * std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) - x * std::atan(x) -
            y * std::atan(y));
}

// Form factor between two squares meeting at a right angle along a common edge, as a cube's
// adjacent faces (Howell's catalogue C-14 with W = H = 1: 0.200044).
inline double perpendicular_squares_form_factor() {
    const double w = 1.0, h = 1.0, pi = 3.14159265358979323846;
    const double hw = h * h + w * w;
    const double a = (1 + w * w) * (1 + h * h) / (1 + hw);
    const double b = std::pow(w * w * (1 + hw) / ((1 + w * w) * hw), w * w);
    const double c = std::pow(h * h * (1 + hw) / ((1 + h * h) * hw), h * h);
    return (w * std::atan(1 / w) + h * std::atan(1 / h) - std::sqrt(hw) * std::atan(1 / std::sqrt(hw)) +
            0.25 * std::log(a * b * c)) /
           (pi * w);
}

// The unit sphere of make_ported_sphere (rings, port_rings) with one material.
inline stratum::Scene sphere_scene(const PortedSphereMesh& sphere, float k, float emission = 0.0f) {
    stratum::Scene scene;
    scene.materials.push_back(lambert(k, emission));
    add_mesh(scene, sphere.mesh.positions, sphere.mesh.triangles, 0);
    return scene;
}

// ---- the diffuse Cornell box (issue 17, acceptance 2) ------------------------------------------
//
// The box [−1, 1]³ open toward +Z, seen by camera_at(0, 0, 1.9) (90°: only the interior shows):
// white floor, back wall and ceiling, red left and green right wall (the Cornell measurements'
// reflectances), two white blocks turned about the vertical, and an emissive quad of 0.5 × 0.5
// in the middle of the ceiling, coplanar with it (the ceiling is four quads around it), emitting
// kCornellEmission from both faces and reflecting nothing. Every material is Lambertian.
struct CornellQuad {
    float corners[12];
    uint32_t material;  // 0 white, 1 red, 2 green, 3 light
};
inline constexpr float kCornellEmission = 12.0f;
inline constexpr float kCornellCamera[3] = {0.0f, 0.0f, 1.9f};
inline constexpr float kCornellAlbedo[3][3] = {
    {0.73f, 0.71f, 0.68f}, {0.63f, 0.065f, 0.05f}, {0.14f, 0.45f, 0.09f}};

// The five faces (no bottom) of a box of half sides (hx, h/2, hz) standing on the floor y = −1
// at (cx, cz), turned by `angle` about the vertical.
inline void add_block(std::vector<CornellQuad>& quads, float cx, float cz, float hx, float hz, float height,
                      float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    const auto at = [&](float x, float y, float z) {
        return std::array<float, 3>{cx + c * x + s * z, y, cz - s * x + c * z};
    };
    const float y0 = -1.0f, y1 = -1.0f + height;
    const std::array<float, 3> p[8] = {at(-hx, y0, -hz), at(hx, y0, -hz), at(hx, y0, hz), at(-hx, y0, hz),
                                       at(-hx, y1, -hz), at(hx, y1, -hz), at(hx, y1, hz), at(-hx, y1, hz)};
    const int faces[5][4] = {{4, 7, 6, 5}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    for (const auto& f : faces) {
        CornellQuad q{{}, 0};
        for (int k = 0; k < 4; ++k)
            for (int a = 0; a < 3; ++a) q.corners[3 * k + a] = p[f[k]][a];
        quads.push_back(q);
    }
}

inline std::vector<CornellQuad> cornell_quads() {
    std::vector<CornellQuad> q = {
        {{-1, -1, -1, 1, -1, -1, 1, -1, 1, -1, -1, 1}, 0},  // floor
        {{-1, -1, -1, -1, 1, -1, 1, 1, -1, 1, -1, -1}, 0},  // back wall
        {{-1, -1, -1, -1, -1, 1, -1, 1, 1, -1, 1, -1}, 1},  // left wall (red)
        {{1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1}, 2},      // right wall (green)
        // The ceiling y = 1 around the light: front and back strips, left and right pieces.
        {{-1, 1, -1, 1, 1, -1, 1, 1, -0.25f, -1, 1, -0.25f}, 0},
        {{-1, 1, 0.25f, 1, 1, 0.25f, 1, 1, 1, -1, 1, 1}, 0},
        {{-1, 1, -0.25f, -0.25f, 1, -0.25f, -0.25f, 1, 0.25f, -1, 1, 0.25f}, 0},
        {{0.25f, 1, -0.25f, 1, 1, -0.25f, 1, 1, 0.25f, 0.25f, 1, 0.25f}, 0},
        {{-0.25f, 1, -0.25f, 0.25f, 1, -0.25f, 0.25f, 1, 0.25f, -0.25f, 1, 0.25f}, 3},  // light
    };
    add_block(q, 0.35f, 0.3f, 0.3f, 0.3f, 0.6f, -0.3f);    // short block
    add_block(q, -0.35f, -0.35f, 0.3f, 0.3f, 1.2f, 0.3f);  // tall block
    return q;
}

inline stratum::Scene cornell_scene() {
    stratum::Scene scene;
    for (const auto& a : kCornellAlbedo) {
        stratum::SceneMaterial m = lambert(0.0f);
        m.closures[0].params.base_color = stratum::Rgb(a[0], a[1], a[2]);
        scene.materials.push_back(m);
    }
    scene.materials.push_back(lambert(0.0f, kCornellEmission));
    for (const CornellQuad& q : cornell_quads())
        add_mesh(scene, std::vector<float>(q.corners, q.corners + 12), {0, 1, 2, 0, 2, 3}, q.material);
    return scene;
}

// The same box through the C ABI (for renders), with its camera; nullptr on failure.
inline StratumScene* make_cornell_box() {
    StratumScene* scene = nullptr;
    if (stratum_scene_create(&scene) != STRATUM_OK) return nullptr;
    bool ok = true;
    for (const auto& a : kCornellAlbedo) {
        StratumMaterialDesc m = diffuse_grey(0.0f);
        std::copy(a, a + 3, m.base_color);
        uint32_t id = 0;
        ok = ok && stratum_scene_add_material(scene, &m, &id) == STRATUM_OK;
    }
    StratumMaterialDesc light = diffuse_grey(0.0f);
    light.emission[0] = light.emission[1] = light.emission[2] = kCornellEmission;
    uint32_t id = 0;
    ok = ok && stratum_scene_add_material(scene, &light, &id) == STRATUM_OK;
    for (const CornellQuad& q : cornell_quads()) ok = ok && add_quad_instance(scene, q.corners, q.material);
    const StratumCameraDesc camera = camera_at(kCornellCamera[0], kCornellCamera[1], kCornellCamera[2]);
    ok = ok && stratum_scene_set_camera(scene, &camera) == STRATUM_OK;
    if (!ok) {
        stratum_scene_destroy(scene);
        return nullptr;
    }
    return scene;
}

}  // namespace stratum_test
