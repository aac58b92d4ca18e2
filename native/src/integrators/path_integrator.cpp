#include "integrators/path_integrator.h"

#include "bsdf/bsdf.h"
#include "integrators/ray_offset.h"
#include "sampling/dimensions.h"

namespace stratum {

namespace {

constexpr uint32_t kRouletteStartVertex = 3;

float power_heuristic(float pdf_a, float pdf_b) {
    const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a > 0.0f ? a / (a + b) : 0.0f;
}

}  // namespace

RadianceSample PathIntegrator::radiance(const RenderScene& scene, const Sampler& sampler,
                                        const PixelSample& pixel, const CameraRay& camera_ray,
                                        uint64_t& rays) const {
    Rgb L(0.0f), beta(1.0f);
    Vec3 origin = camera_ray.origin, dir = camera_ray.direction;
    float t_min = camera_ray.t_min, t_max = camera_ray.t_max;
    float scatter_pdf = 0.0f;  // solid-angle pdf of the last scattering; 0 for the camera ray
    Vec3 scatter_origin;
    const LightSet& lights = scene.lights();

    for (uint32_t vertex = 0;; ++vertex) {
        SurfaceHit hit;
        ++rays;
        if (!scene.intersect(origin, dir, t_min, t_max, &hit)) {
            // The environment is also sampled by NEE: MIS against it, as for emissive triangles.
            float w = 1.0f;
            if (scatter_pdf > 0.0f && lights.environment()) {
                w = power_heuristic(scatter_pdf, lights.environment_pdf(dir));
            }
            L += beta * scene.background(dir) * w;
            break;
        }
        const Material& material = *hit.material;
        if (!material.emission.is_black()) {
            float w = 1.0f;
            if (scatter_pdf > 0.0f && hit.emissive_light != kNoLight) {
                w = power_heuristic(scatter_pdf, lights.emissive_triangle_pdf(hit.emissive_light,
                                                                              scatter_origin, hit.position));
            }
            L += beta * material.emission * w;
        }
        if (vertex > settings_.max_bounces || material.model == MaterialModel::Emission) break;

        const Vec3 wo_world = -dir;
        const Vec3 ng =
            dot(hit.geometric_normal, wo_world) < 0.0f ? -hit.geometric_normal : hit.geometric_normal;
        // The shading normal is flipped to the viewer's side along with the geometric one.
        const Vec3 ns = dot(hit.shading_normal, ng) < 0.0f ? -hit.shading_normal : hit.shading_normal;
        const Frame frame = Frame::from_normal(ns);
        const Vec3 wo = frame.to_local(wo_world);

        // Next-event estimation (textbook 5.7–5.16), MIS-weighted against BSDF sampling.
        LightSample ls;
        if (lights.sample(hit.position, sampler.get_1d(pixel, bounce_dimension(vertex, kDimLightChoice)),
                          sampler.get_2d(pixel, bounce_dimension(vertex, kDimLightPoint)), &ls) &&
            dot(ls.wi, ng) > 0.0f) {
            const BsdfEval f = bsdf_eval(material, wo, frame.to_local(ls.wi), settings_.hemisphere);
            if (!f.value.is_black()) {
                const Vec3 o = offset_ray_origin(hit.position, ng);
                const ShadowRay shadow = std::isinf(ls.distance)
                                             ? ShadowRay{ls.wi, kInfinity}
                                             : shadow_ray_to(o, hit.position + ls.wi * ls.distance);
                ++rays;
                if (!scene.occluded(o, shadow.direction, 0.0f, shadow.t_max)) {
                    const float w = ls.found_by_bsdf_rays ? power_heuristic(ls.pdf, f.pdf) : 1.0f;
                    L += beta * f.value * ls.radiance * (w / ls.pdf);
                }
            }
        }

        BsdfSample bs;
        if (!bsdf_sample(material, wo, sampler.get_1d(pixel, bounce_dimension(vertex, kDimBsdfLobe)),
                         sampler.get_2d(pixel, bounce_dimension(vertex, kDimBsdfDirection)), &bs,
                         settings_.hemisphere)) {
            break;
        }
        const Vec3 wi = frame.to_world(bs.wi);
        // A direction the shading normal allows but the true surface does not: light cannot
        // get there, so the path ends.
        if (dot(wi, ng) <= 0.0f) break;
        beta *= bs.weight;
        scatter_pdf = bs.pdf;
        scatter_origin = hit.position;

        if (vertex >= kRouletteStartVertex) {
            const float survive = std::min(1.0f, beta.max_component());
            if (sampler.get_1d(pixel, bounce_dimension(vertex, kDimRussianRoulette)) >= survive) break;
            beta *= 1.0f / survive;
        }
        origin = offset_ray_origin(hit.position, ng);
        dir = wi;
        t_min = 0.0f;
        t_max = kInfinity;
    }
    return {L};
}

}  // namespace stratum
