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

// A path's ray as Cycles tracks it for sd->ray_length and sd->dP: the distance travelled since the
// path last scattered when the ray starts (transparent surfaces passed through count, as Cycles
// continues the same ray past them), and the compact differential at the ray's origin and its
// spread per unit distance (a camera ray's, which Cycles keeps through every bounce).
struct RayTrack {
    float travelled = 0.0f, dp = 0.0f, dd = 0.0f;

    // Cycles starts a camera ray at its near clip point (kernel/camera/camera.h moves ray->P by
    // nearclip along the ray), so its lengths count from there, t_min along ours.
    static RayTrack camera(const CameraRay& ray) { return {-ray.t_min, ray.dp, ray.dd}; }
    // What the programs of a hit t along the ray see.
    RayReach at(float t) const { return {travelled + t, dp + t * dd}; }
    // The next ray starts at the hit t along this one: past a transparent surface, or scattered.
    void pass_through(float t) {
        travelled += t;
        dp += t * dd;
    }
    void scatter(float t) {
        travelled = 0.0f;
        dp += t * dd;
    }
};

}  // namespace stratum
