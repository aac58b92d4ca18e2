// The closures and frame of a surface hit, as the integrators shade it: the single place where a
// material's closures are built (and, later, textured) before evaluation.
//
// | field         | meaning                                                                   |
// |---------------|---------------------------------------------------------------------------|
// | closures      | the hit material's closures; transmissive ones get the relative IOR of the |
// |               | far side: 1/ior on back faces (Cycles: SD_BACKFACING inverts eta)          |
// | ng            | geometric normal turned toward the incoming ray's origin (wo side)        |
// | ns            | shading normal, negated with ng on back faces, then bent so the view      |
// |               | direction reflects above the surface (valid_reflection_normal.h)          |
// | backfacing    | the ray hit the triangle's back (winding) face                            |
#pragma once

#include "bsdf/closure_set.h"
#include "integrators/light_path_limits.h"
#include "render_scene/render_scene.h"

namespace stratum {

struct ShadingPoint {
    ClosureSet closures;
    Vec3 ng, ns;
    bool backfacing;
};

// wo_world: unit direction from the hit toward the ray's origin; `reach`, what the hit's node
// programs see of the ray (RayTrack::at on camera paths); `filter`, what the path changes of the
// closures (Filter Glossy, caustics: integrators/light_path_closures.h).
ShadingPoint build_closures(const RenderScene& scene, const SurfaceHit& hit, Vec3 wo_world, RayReach reach,
                            const ClosureFilter& filter = {});

// A path's ray as Cycles tracks it for sd->ray_length, sd->dP and the Light Path node: the
// distance travelled since the path last scattered when the ray starts (transparent surfaces
// passed through count, as Cycles continues the same ray past them), the compact differential at
// the ray's origin and its spread per unit distance (a camera ray's, which Cycles keeps through
// every bounce), and the ray's kind (LightPathRay bits: CAMERA until the first scattering, then
// the last scattering's; a pass-through keeps it, as path_state_next keeps the visibility bits).
struct RayTrack {
    float travelled = 0.0f, dp = 0.0f, dd = 0.0f;
    uint32_t rays = 0;

    // Cycles starts a camera ray at its near clip point (kernel/camera/camera.h moves ray->P by
    // nearclip along the ray), so its lengths count from there, t_min along ours.
    static RayTrack camera(const CameraRay& ray) { return {-ray.t_min, ray.dp, ray.dd, kLightPathCamera}; }
    // What the programs of a hit t along the ray see, with the path's depths zero.
    RayReach at(float t) const { return {travelled + t, dp + t * dd, LightPathState{rays}}; }
    // The same on a path that has scattered `bounces` times and passed `transparent` transparent
    // surfaces (Cycles' path state as the hit receives it).
    RayReach at(float t, const BounceCounts& bounces, uint32_t transparent) const {
        return {travelled + t, dp + t * dd,
                LightPathState{rays, bounces.total(), bounces.diffuse(), bounces.glossy(), transparent,
                               bounces.transmission()}};
    }
    // The next ray starts at the hit t along this one: past a transparent surface, or scattered
    // (light_path_rays: the kind of the scattered ray).
    void pass_through(float t) {
        travelled += t;
        dp += t * dd;
    }
    void scatter(float t, uint32_t scattered_rays) {
        travelled = 0.0f;
        dp += t * dd;
        rays = scattered_rays;
    }
};

}  // namespace stratum
