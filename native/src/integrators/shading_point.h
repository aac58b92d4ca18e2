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

// wo_world: unit direction from the hit toward the ray's origin.
ShadingPoint build_closures(const RenderScene& scene, const SurfaceHit& hit, Vec3 wo_world);

}  // namespace stratum
