// Scenes of the radiosity tests, built natively (stratum::Scene, then RenderScene) where a test
// inspects patches and form factors, and the closed-form references they are checked against.
#pragma once

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

}  // namespace stratum_test
