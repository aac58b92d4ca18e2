// Applies a scene's shader-program bindings (stratum_scene_bind_program) to the closures of a
// shading point, after its texture bindings (material_texturing.h): each program bound to the
// hit's material runs once, its inputs written from the hit, then each binding writes its
// parameter.
//
// | parameter      | value written (v = the register(s))                                     |
// |----------------|-------------------------------------------------------------------------|
// | BaseColor      | max(v, 0) per channel                                                   |
// | Roughness, Metallic, Transmission, CoatRoughness | clamp(v, 0, 1)                        |
// | Specular, Coat | max(v, 0)                                                               |
// | Ior            | max(v, 1e-5)                                                            |
// | Emission       | v, the radiance (negative as in Cycles: such a surface darkens the pixel)|
// | Weight         | closure weight *= max(v, 0) per channel                                 |
// | CoatTint       | clamp(v, 0, 1) per channel                                              |
// | Normal         | the point's shading normal: v normalised, in the program's frame (turned|
// |                | toward the viewer, as Cycles' sd->N); zero or not finite keeps it       |
// A NaN reads 0 (where Cycles' closures see NaN its film drops the sample; a 0 is the nearer
// visible result and keeps a NaN off every pass).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "scene/scene.h"
#include "shading/light_path_state.h"
#include "shading/program_binding.h"
#include "shading/shader_program.h"

namespace stratum {

struct SurfaceHit;

// What the programs see of the ray that reached a surface point, besides the hit: Cycles'
// sd->ray_length and sd->dP (StratumShaderInput's RAY_LENGTH and PIXEL_FOOTPRINT), and the path's
// kind and depths the Light Path node reads (its other outputs).
struct RayReach {
    float length = 0.0f;     // from where the path last scattered, transparent surfaces counted
    float footprint = 0.0f;  // the compact ray differential at the point; 0 off camera paths
    LightPathState path;     // all 0 where no integrator tracks a path (light tracing, radiosity)
};

// What a shading point's program inputs are made from, besides the hit.
struct ProgramInputs {
    Vec3 wo;                 // unit, from the hit toward the ray's origin
    bool backfacing;         // the ray hit the triangle's back face
    Vec3 object_location;    // the instance's origin in world space
    Vec3 texspace_location;  // the mesh's texture space (generated coordinates)
    Vec3 texspace_size;
    float object_random;
    Rgb object_color;
    float object_alpha;
    const Transform* world_to_camera;  // null: camera coordinates 0
    const Transform* object_to_world;  // the instance's (at shutter open for a moving one)
    const Mesh* mesh;                  // the hit's mesh (its attributes)
    RayReach reach;
};

// The world-space step of the Bump node's finite differences at a point `ray_length` from the
// ray's origin: small against the surface's features, large against float rounding (Cycles steps
// by the ray differential, about a pixel's footprint; a thousandth of the distance is a pixel of
// a 60-degree view 1,000 pixels wide).
inline float bump_step(float ray_length, Vec3 position) {
    const float scale = std::max(std::abs(position.x), std::max(std::abs(position.y), std::abs(position.z)));
    return std::max(1e-3f * std::min(ray_length, 1e6f), 1e-5f * std::max(scale, 1.0f));
}

class MaterialPrograms {
public:
    MaterialPrograms() = default;
    explicit MaterialPrograms(const Scene& scene);

    // Whether material `material_id` has program bindings.
    bool any(uint32_t material_id) const {
        return material_id < per_material_.size() && !per_material_[material_id].empty();
    }
    // Runs the programs of the hit's material and applies their bindings to its `count` closures
    // and to *shading_normal (unit, oriented as the triangle's winding).
    void apply(const SurfaceHit& hit, const ProgramInputs& inputs, WeightedClosure* closures, uint32_t count,
               Vec3* shading_normal) const;

private:
    std::vector<std::shared_ptr<const ShaderProgram>> programs_;
    std::vector<std::shared_ptr<const Texture>> textures_;
    // Per material, sorted by program: each program then runs once.
    std::vector<std::vector<ProgramBinding>> per_material_;
};

// Writes the input registers (shader_input::kCount) of a surface point.
void write_surface_inputs(const SurfaceHit& hit, const ProgramInputs& inputs, float* registers);

}  // namespace stratum
