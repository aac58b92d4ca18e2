// Shadow-ray transmittance through Transparent closures (Cycles "transparent shadows",
// Cycles 3.4 / 4.x `integrator/intersect_shadow.h` + `shade_shadow.h`): the ray is traced
// surface by surface; a surface whose material has Transparent closures multiplies the
// transmittance by their summed weight x colour, any other surface blocks it.
//
// | parameter      | meaning                                                               |
// |----------------|-----------------------------------------------------------------------|
// | origin, dir    | shadow ray, origin already offset off the shaded surface               |
// | t_max          | distance to the light point (infinity for distant lights)              |
// | max_surfaces   | transparent surfaces that may be crossed (transparent_max_bounces left)|
// | footprint      | the shaded point's footprint (Cycles gives a shadow ray sd->dP and no  |
// |                | spread): what the crossed surfaces' programs see as PIXEL_FOOTPRINT    |
// | path           | the shaded point's Light Path state: the k-th surface crossed (from 0) |
// |                | sees path.shadow(k) (Cycles' shade_shadow: PATH_RAY_SHADOW alone, one  |
// |                | bounce further, the transparent depth counting the surfaces crossed)   |
// | shadow_sets    | the light's shadow_set_membership (shadow linking, scene/light_links.h):|
// |                | surfaces whose blocker set is not in it are passed as if absent         |
// |                | (Cycles' intersection_skip_shadow_link), not counted in max_surfaces    |
#pragma once

#include <cstdint>

#include "render_scene/render_scene.h"

namespace stratum {

// Returns the transmittance (0 when blocked); `rays` counts the rays traced.
Rgb shadow_transmittance(const RenderScene& scene, Vec3 origin, Vec3 dir, float t_max, const RayQuery& query,
                         uint32_t max_surfaces, uint64_t& rays, float footprint = 0.0f,
                         const LightPathState& path = {}, uint64_t shadow_sets = kAllLinkSets);

}  // namespace stratum
