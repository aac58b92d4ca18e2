// The scene in render-ready form: instances flattened to world-space triangles in an Embree
// BVH, emissive triangles and light objects in one LightSet, and the shading data a hit needs.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "accel/embree_scene.h"
#include "lights/light_set.h"
#include "scene/scene.h"

namespace stratum {

// Everything the integrator needs to know about a ray hit.
struct SurfaceHit {
    Vec3 position;
    Vec3 geometric_normal;  // unit, oriented as the triangle's winding
    Vec3 shading_normal;    // unit, interpolated corner normal (or the geometric normal)
    const Material* material;
    uint32_t emissive_light;      // index in the LightSet, or kNoLight
    Vec2 uv{0.0f, 0.0f};          // interpolated corner_uvs (0,0 if the mesh has none)
    Vec3 dpdu{0.0f, 0.0f, 0.0f};  // world-space tangent along +u (0 if no UVs), for normal maps
    uint32_t material_id = 0;     // scene material id
    uint32_t visibility = 31;     // the instance's StratumVisibility bits
    bool holdout = false;         // the instance is a holdout
};

inline constexpr uint32_t kNoLight = 0xffffffffu;

// What a ray is for: the shutter time it samples (motion blur) and the StratumVisibility bit of
// its kind (CAMERA, DIFFUSE, GLOSSY, TRANSMISSION or SHADOW), matched against each instance's
// visibility.
struct RayQuery {
    float time = 0.5f;
    uint32_t visibility = 31;
};

class RenderScene {
public:
    // Throws std::runtime_error with a readable message (caught at the C ABI).
    explicit RenderScene(const Scene& scene);

    bool intersect(Vec3 origin, Vec3 direction, float t_min, float t_max, SurfaceHit* hit,
                   const RayQuery& query = {}) const;
    bool occluded(Vec3 origin, Vec3 direction, float t_min, float t_max, const RayQuery& query = {}) const {
        (void)query;
        return embree_.occluded(origin, direction, t_min, t_max);
    }
    const LightSet& lights() const { return lights_; }
    // The closures of scene material `id` (SurfaceHit::material_id), before texturing.
    const SceneMaterial& material(uint32_t id) const { return materials_[id]; }
    // Radiance of a ray that leaves the scene in direction `dir`: the environment image if
    // there is one, else the constant background.
    Rgb background(Vec3 dir) const {
        const EnvironmentLight* env = lights_.environment();
        return env ? env->radiance(dir) : background_;
    }

private:
    struct InstanceGeometry {
        const Mesh* mesh;
        std::vector<Vec3> positions;           // world space
        std::vector<Vec3> corner_normals;      // world space, unit; empty if the mesh has none
        std::vector<uint32_t> emissive_light;  // per triangle, kNoLight if not emissive
    };
    std::vector<SceneMaterial> materials_;
    std::vector<InstanceGeometry> instances_;
    EmbreeScene embree_;
    LightSet lights_;
    Rgb background_;
};

}  // namespace stratum
