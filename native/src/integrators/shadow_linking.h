// The forward half of shadow linking: Cycles' "dedicated light" pass (5.0
// integrator/intersect_dedicated_light.h, shade_dedicated_light.h). A shadow-linked emitter
// (scene/light_links.h) is seen past occluders that do not block it, which the main path, stopped
// by the first surface, cannot do; so the main path's scattered rays ignore shadow-linked
// emission (camera rays excepted), and after every scattering this pass follows the scattered
// ray through every surface, picks one of the shadow-linked emitters it meets uniformly
// (reservoir sampling), and the caller adds that emitter's emission × the forward MIS weight ×
// the number met, times the transmittance of a shadow ray to it that honours its shadow linking.
// That is an unbiased estimate of the sum over the emitters met, each seen through its own
// occluders only.
//
// | ScatteredRay     | meaning                                                                |
// |------------------|------------------------------------------------------------------------|
// | origin, dir      | the scattered ray (origin offset off the scattering surface)           |
// | query            | its time and visibility kind (a shadow catcher's copy: as it shifts it)|
// | shadow_query     | the query of a shadow ray to the pick (the same shift)                 |
// | track            | what the surfaces' programs see of it (RayTrack after the scattering)  |
// | receiver_set     | receiver_light_set of the scattering surface: only emitters lighting it|
// | seed             | the reservoir's random numbers (a hash of pixel, sample and vertex)    |
// | scatter_pdf, ... | the scattering vertex's pdf, point and normal, for the MIS weight      |
// | transparent_left | Transparent surfaces the shadow ray to the pick may still cross        |
// | bounces, transparent | the path's counts as the ray leaves: what the Light Path node of the |
// |                  | emitters met sees (surfaces as hit by the ray, lamps with EMISSION)    |
//
// Where the walk stops: Cycles stops at the first opaque surface of blocker set 0, assuming
// every shadow-linked emitter is blocked by set 0. That holds for blocker collections of
// EXCLUDE entries only; an emitter with an INCLUDE entry is not blocked by set 0, and Cycles
// loses its light behind such a surface (its NEE still sees it). Here the walk stops at an opaque
// surface whose blocker set blocks every shadow-linked emitter (LightSet::
// shadow_sets_blocking_all_linked), the same surface for EXCLUDE-only linking, and no light is
// lost otherwise. At most kMaxSurfaces surfaces are walked (Cycles' 1024).
#pragma once

#include <cstdint>

#include "integrators/light_path_limits.h"
#include "integrators/shading_point.h"
#include "render_scene/render_scene.h"

namespace stratum {

struct ShadowLinkedEmitter {
    uint32_t met = 0;                     // shadow-linked emitters met: the pick's weight; 0 = none
    bool lamp = false;                    // a lamp (else an emissive surface)
    uint32_t light = kNoLight;            // its LightSet index (kNoLight: a surface that is no light entry)
    Rgb radiance{0.0f};                   // emitted toward the ray's origin
    Vec3 position;                        // where the ray meets it
    float t = 0.0f;                       // its distance along the ray
    uint64_t shadow_sets = kAllLinkSets;  // its shadow_set_membership
    bool casts_shadow = true;             // a lamp's SHADOW visibility bit (Cycles' cast_shadow)
    float solid_angle_pdf = 0.0f;         // a lamp's: Light::intersect's, for the MIS weight
    uint32_t lightgroup = 0;              // its light group (film/light_groups.h; 0 = none)
};

struct ScatteredRay {
    Vec3 origin, dir;
    RayQuery query, shadow_query;
    RayTrack track;
    uint8_t receiver_set = 0;
    uint64_t seed = 0;
    float scatter_pdf = 0.0f;
    Vec3 scatter_origin, scatter_normal;
    uint32_t transparent_left = 0;
    BounceCounts bounces;
    uint32_t transparent = 0;
};

inline constexpr uint32_t kMaxShadowLinkSurfaces = 1024;

ShadowLinkedEmitter pick_shadow_linked_emitter(const RenderScene& scene, const ScatteredRay& ray,
                                               uint64_t& rays);

}  // namespace stratum
