#include "integrators/ao_integrator.h"

#include "integrators/camera_path_passes.h"
#include "integrators/ray_offset.h"
#include "sampling/dimensions.h"
#include "scene/visibility.h"

namespace stratum {

RadianceSample AoIntegrator::estimate(const RenderScene& scene, const Sampler& sampler,
                                      const PixelSample& pixel, const CameraRay& camera_ray,
                                      PassValues& passes, uint64_t& rays) const {
    SurfaceHit hit;
    ++rays;
    CameraPathPasses data(passes, settings_.mist);
    if (!scene.intersect(camera_ray.origin, camera_ray.direction, camera_ray.t_min, camera_ray.t_max, &hit,
                         {camera_ray.time, kVisibleCamera})) {
        // The background is white for AO: its albedo too.
        data.miss(Rgb(1.0f), true);
        return {Rgb(1.0f)};
    }
    const Vec3 wo = -camera_ray.direction;
    const Vec3 ng = dot(hit.geometric_normal, wo) < 0.0f ? -hit.geometric_normal : hit.geometric_normal;
    const Vec3 ns = dot(hit.shading_normal, ng) < 0.0f ? -hit.shading_normal : hit.shading_normal;
    data.plain_surface(hit, ns);
    const Frame frame = Frame::from_normal(ns);

    const Vec3 local = sample_hemisphere(settings_.hemisphere,
                                         sampler.get_2d(pixel, bounce_dimension(0, kDimBsdfDirection)));
    // The weight cos θ / (π p): exactly 1 for `cosine` (so its samples are exactly 0 or 1,
    // even at grazing directions where p = 0). A zero density elsewhere (uniform_angles at the
    // pole) is a set of measure zero whose weight tends to 0 (π sin θ cos θ): no contribution.
    float weight = 1.0f;
    if (settings_.hemisphere != HemisphereDistribution::Cosine) {
        const float pdf = hemisphere_pdf(settings_.hemisphere, local.z);
        if (!(pdf > 0.0f)) return {Rgb(1.0f)};
        weight = kInvPi * local.z / pdf;
    }
    const Vec3 wi = frame.to_world(local);
    bool occluded = dot(wi, ng) <= 0.0f;
    if (!occluded) {
        ++rays;
        occluded = scene.occluded(offset_ray_origin(hit.position, ng), wi, 0.0f, settings_.ao_distance,
                                  {camera_ray.time, kVisibleShadow});
    }
    if (!occluded) return {Rgb(1.0f)};
    return {Rgb(1.0f - weight)};
}

}  // namespace stratum
