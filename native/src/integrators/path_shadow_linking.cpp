// PathIntegrator's use of shadow linking's dedicated pass (integrators/shadow_linking.h): the
// picked emitter weighted as the main path would weigh its emission (forward MIS against the
// light sample that could have found it), times the number of emitters it stands for, times
// the transmittance of a shadow ray that honours its shadow linking.
#include "integrators/path_integrator.h"
#include "integrators/ray_offset.h"
#include "integrators/transparent_shadow.h"

namespace stratum {

Rgb PathIntegrator::shadow_linked_emission(const RenderScene& scene, const ScatteredRay& ray, uint64_t& rays,
                                           uint32_t* lightgroup) const {
    const ShadowLinkedEmitter e = pick_shadow_linked_emitter(scene, ray, rays);
    if (e.met == 0) return Rgb(0.0f);
    *lightgroup = e.lightgroup;
    // The lights NEE chose among at the scattering vertex (light linking: those lighting it).
    const LightSet& lights = scene.lights_for(ray.receiver_set);
    const LightSelection selection = settings_.light_selection;
    float light_pdf = 0.0f;
    if (light_pdf_matters(ray.scatter_pdf) && e.light != kNoLight) {
        const uint32_t index = scene.light_index_for(ray.receiver_set, e.light);
        if (e.lamp) {
            // As lamp_radiance gives it: NEE's choice at the vertex × the lamp's solid-angle pdf.
            light_pdf = lights.probability(index, ray.scatter_origin, ray.scatter_normal, selection,
                                           settings_.light_tree_splits) *
                        e.solid_angle_pdf;
        } else {
            light_pdf = lights.emissive_triangle_pdf(index, ray.scatter_origin, ray.scatter_normal,
                                                     e.position, selection, settings_.triangle_sampling,
                                                     settings_.light_tree_splits);
        }
    }
    const float weight = hit_weight(ray.scatter_pdf, light_pdf) * static_cast<float>(e.met);
    if (!(weight > 0.0f)) return Rgb(0.0f);
    Rgb transmittance(1.0f);
    if (e.casts_shadow) {
        const ShadowRay shadow = shadow_ray_to(ray.origin, e.position);
        const RayReach reach = ray.track.at(0.0f, ray.bounces, ray.transparent);
        transmittance =
            shadow_transmittance(scene, ray.origin, shadow.direction, shadow.t_max, ray.shadow_query,
                                 ray.transparent_left, rays, reach.footprint, reach.path, e.shadow_sets);
    }
    return e.radiance * transmittance * weight;
}

}  // namespace stratum
