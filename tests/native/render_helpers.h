// Scene construction and rendering through the C ABI, shared by the render tests.
#pragma once

#include <stratum/stratum.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <string_view>
#include <utility>
#include <vector>

namespace stratum_test {

inline constexpr float kIdentity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

// A UV sphere of radius r centred at the origin, wound so normals point outward.
struct SphereMesh {
    std::vector<float> positions;
    std::vector<uint32_t> triangles;
};

inline SphereMesh make_sphere(float r, uint32_t rings, uint32_t segments) {
    SphereMesh m;
    const float pi = 3.14159265358979f;
    for (uint32_t i = 0; i <= rings; ++i) {
        const float theta = pi * static_cast<float>(i) / static_cast<float>(rings);
        for (uint32_t j = 0; j < segments; ++j) {
            const float phi = 2.0f * pi * static_cast<float>(j) / static_cast<float>(segments);
            m.positions.insert(m.positions.end(), {r * std::sin(theta) * std::cos(phi),
                                                   r * std::sin(theta) * std::sin(phi), r * std::cos(theta)});
        }
    }
    for (uint32_t i = 0; i < rings; ++i) {
        for (uint32_t j = 0; j < segments; ++j) {
            const uint32_t a = i * segments + j, b = i * segments + (j + 1) % segments;
            const uint32_t c = a + segments, d = b + segments;
            m.triangles.insert(m.triangles.end(), {a, c, b, b, c, d});
        }
    }
    return m;
}

struct RenderOutput {
    std::vector<float> rgba;
    StratumProgress progress{};
};

// Renders `scene` with integer settings {name, value} and returns the pixels.
inline RenderOutput render(StratumScene* scene, std::initializer_list<std::pair<const char*, int64_t>> ints,
                           const char* sampler = "random") {
    RenderOutput out;
    StratumRenderer* r = nullptr;
    if (stratum_renderer_create(scene, &r) != STRATUM_OK) return out;
    int64_t width = 0, height = 0;
    for (const auto& [name, value] : ints) {
        if (stratum_renderer_set_int(r, name, value) != STRATUM_OK) {
            stratum_renderer_destroy(r);
            return out;
        }
        if (std::string_view(name) == "width") width = value;
        if (std::string_view(name) == "height") height = value;
    }
    stratum_renderer_set_string(r, "sampler", sampler);
    if (stratum_renderer_start(r) == STRATUM_OK) {
        int32_t done = 0;
        while (!done) stratum_renderer_wait(r, 1000, &done);
        stratum_renderer_progress(r, &out.progress);
        out.rgba.resize(static_cast<size_t>(width * height * 4));
        stratum_renderer_read_pixels(r, out.rgba.data(), out.rgba.size());
    }
    stratum_renderer_destroy(r);
    return out;
}

// A camera at `position` looking down −Z with a 90° horizontal field of view.
inline StratumCameraDesc camera_at(float x, float y, float z) {
    StratumCameraDesc c{18.0f, 36.0f, 36.0f, STRATUM_SENSOR_FIT_AUTO, 0, 0, 1e-3f, 1e3f, {}, 0, 0, 0,
                        0,     0,     0};
    std::copy(kIdentity, kIdentity + 16, c.transform);
    c.transform[3] = x;
    c.transform[7] = y;
    c.transform[11] = z;
    return c;
}

// A closed sphere of radius 1 whose wall has `material`, seen from inside by a camera at
// (x, y, z); nullptr on failure. The caller destroys the scene.
inline StratumScene* make_sphere_interior(const StratumMaterialDesc& material, uint32_t rings, float x,
                                          float y, float z) {
    StratumScene* scene = nullptr;
    if (stratum_scene_create(&scene) != STRATUM_OK) return nullptr;
    uint32_t mat = 0, mesh_id = 0;
    const SphereMesh sphere = make_sphere(1.0f, rings, 2 * rings);
    const std::vector<uint32_t> mats(sphere.triangles.size() / 3, 0u);
    const StratumMeshDesc mesh{sphere.positions.data(),
                               static_cast<uint32_t>(sphere.positions.size() / 3),
                               sphere.triangles.data(),
                               static_cast<uint32_t>(sphere.triangles.size() / 3),
                               nullptr,
                               nullptr,
                               mats.data()};
    const StratumCameraDesc camera = camera_at(x, y, z);
    if (stratum_scene_add_material(scene, &material, &mat) != STRATUM_OK ||
        stratum_scene_add_mesh(scene, &mesh, &mesh_id) != STRATUM_OK ||
        stratum_scene_add_instance(scene, mesh_id, kIdentity) != STRATUM_OK ||
        stratum_scene_set_camera(scene, &camera) != STRATUM_OK) {
        stratum_scene_destroy(scene);
        return nullptr;
    }
    return scene;
}

}  // namespace stratum_test
