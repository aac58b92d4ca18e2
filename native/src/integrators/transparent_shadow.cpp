#include "integrators/transparent_shadow.h"

#include "integrators/ray_offset.h"
#include "integrators/shading_point.h"

namespace stratum {

Rgb shadow_transmittance(const RenderScene& scene, Vec3 origin, Vec3 dir, float t_max, const RayQuery& query,
                         uint32_t max_surfaces, uint64_t& rays, float footprint, const LightPathState& path,
                         uint64_t shadow_sets) {
    // Every surface blocks when no material has a Transparent closure and no light is
    // shadow-linked: any hit decides, which Embree answers without searching for the closest one
    // or shading it.
    if (!scene.has_transparent_closures() && shadow_sets == kAllLinkSets) {
        ++rays;
        return scene.occluded(origin, dir, 0.0f, t_max, query) ? Rgb(0.0f) : Rgb(1.0f);
    }
    // The point the ray must reach. Each re-spawn past a transparent surface starts off that
    // surface (offset along its normal) and is re-aimed at this point: keeping the direction
    // would shift the ray sideways and, at grazing angles, into the light's own surface.
    const bool finite = !std::isinf(t_max);
    const Vec3 end = finite ? origin + dir * t_max : Vec3();
    Rgb transmittance(1.0f);
    float travelled = 0.0f;  // from the shaded point: Cycles' ray length of each surface crossed
    for (uint32_t crossed = 0;;) {
        SurfaceHit hit;
        ++rays;
        if (!scene.intersect(origin, dir, 0.0f, t_max, &hit, query)) return transmittance;
        if ((shadow_sets >> hit.links.blocker_shadow_set) & 1u) {
            if (crossed >= max_surfaces) return Rgb(0.0f);
            // Built (and textured) as for shading, so alpha cut-outs shadow as they look.
            transmittance *=
                build_closures(scene, hit, -dir, {travelled + hit.t, footprint, path.shadow(crossed)})
                    .closures.transparency();
            ++crossed;
        }
        travelled += hit.t;
        if (transmittance.is_black()) return transmittance;
        const Vec3 ng = dot(hit.geometric_normal, dir) > 0.0f ? hit.geometric_normal : -hit.geometric_normal;
        origin = offset_ray_origin(hit.position, ng);
        if (finite) {
            const Vec3 d = end - origin;
            const float len = length(d);
            // Past the end point (or turned back by the offset): nothing is left to cross.
            if (len <= 0.0f || dot(d, dir) <= 0.0f) return transmittance;
            dir = d / len;
            t_max = len;
        }
    }
}

}  // namespace stratum
