#include "integrators/transparent_shadow.h"

#include "integrators/ray_offset.h"
#include "integrators/shading_point.h"

namespace stratum {

Rgb shadow_transmittance(const RenderScene& scene, Vec3 origin, Vec3 dir, float t_max, const RayQuery& query,
                         uint32_t max_surfaces, uint64_t& rays) {
    Rgb transmittance(1.0f);
    for (uint32_t crossed = 0;; ++crossed) {
        SurfaceHit hit;
        ++rays;
        if (!scene.intersect(origin, dir, 0.0f, t_max, &hit, query)) return transmittance;
        if (crossed >= max_surfaces) return Rgb(0.0f);
        // Built (and textured) as for shading, so alpha cut-outs shadow as they look.
        transmittance *= build_closures(scene, hit, -dir).closures.transparency();
        if (transmittance.is_black()) return transmittance;
        // Continue from just past the surface; the remaining distance shrinks accordingly.
        const Vec3 ng = dot(hit.geometric_normal, dir) > 0.0f ? hit.geometric_normal : -hit.geometric_normal;
        const Vec3 next = offset_ray_origin(hit.position, ng);
        if (!std::isinf(t_max)) t_max -= length(next - origin);
        if (t_max <= 0.0f) return transmittance;
        origin = next;
    }
}

}  // namespace stratum
