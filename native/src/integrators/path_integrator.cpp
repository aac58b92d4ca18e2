#include "integrators/path_integrator.h"

#include "integrators/ray_offset.h"
#include "integrators/shading_point.h"
#include "integrators/transparent_shadow.h"
#include "sampling/dimensions.h"
#include "stratum/stratum.h"

namespace stratum {

namespace {

constexpr uint32_t kRouletteStartBounce = 3;

float power_heuristic(float pdf_a, float pdf_b) {
    const float a = pdf_a * pdf_a, b = pdf_b * pdf_b;
    return a > 0.0f ? a / (a + b) : 0.0f;
}

// The ray visibility bit of a ray scattered by a lobe of this kind (StratumVisibility).
uint32_t ray_visibility(ScatterKind kind, uint32_t previous) {
    switch (kind) {
        case ScatterKind::Diffuse:
            return STRATUM_VISIBLE_DIFFUSE;
        case ScatterKind::Glossy:
            return STRATUM_VISIBLE_GLOSSY;
        case ScatterKind::Transmission:
            return STRATUM_VISIBLE_TRANSMISSION;
        case ScatterKind::Transparent:
            break;  // a pass-through keeps the kind of the ray that arrived
    }
    return previous;
}

// The closure kinds a light's visibility bits let NEE illuminate.
uint32_t lit_kinds(uint32_t light_visibility) {
    uint32_t kinds = 0;
    if (light_visibility & STRATUM_VISIBLE_DIFFUSE) kinds |= scatter_kind_bit(ScatterKind::Diffuse);
    if (light_visibility & STRATUM_VISIBLE_GLOSSY) kinds |= scatter_kind_bit(ScatterKind::Glossy);
    if (light_visibility & STRATUM_VISIBLE_TRANSMISSION) kinds |= scatter_kind_bit(ScatterKind::Transmission);
    return kinds;
}

}  // namespace

RadianceSample PathIntegrator::radiance(const RenderScene& scene, const Sampler& sampler,
                                        const PixelSample& pixel, const CameraRay& camera_ray,
                                        uint64_t& rays) const {
    Rgb L(0.0f), beta(1.0f);
    float transparency = 0.0f;  // Cycles' "transparent" film value: alpha = 1 - transparency
    Vec3 origin = camera_ray.origin, dir = camera_ray.direction;
    float t_min = camera_ray.t_min, t_max = camera_ray.t_max;
    float scatter_pdf = 0.0f;  // solid-angle pdf of the last scattering; 0 for camera and delta rays
    Vec3 scatter_origin;
    RayQuery query{camera_ray.time, STRATUM_VISIBLE_CAMERA};
    // Cycles' PATH_RAY_TRANSPARENT_BACKGROUND: only camera and transparent vertices so far.
    bool camera_visible_path = true;
    uint32_t bounce = 0, transparent_bounce = 0;
    const LightSet& lights = scene.lights();
    const uint32_t max_shadow_surfaces = settings_.transparent_max_bounces;

    // `vertex` numbers every surface the path meets (bounces and pass-throughs), so each owns a
    // block of sample dimensions.
    for (uint32_t vertex = 0;; ++vertex) {
        SurfaceHit hit;
        ++rays;
        const bool found = scene.intersect(origin, dir, t_min, t_max, &hit, query);
        // Lamps have no geometry: the emitting face of an area lamp whose camera visibility is on
        // is met analytically, in front of whatever the ray hits (NEE never samples it for the
        // camera, so there is nothing to weight against).
        if (camera_visible_path) {
            L += beta * lights.lamp_radiance(origin, dir, found ? hit.t : t_max, STRATUM_VISIBLE_CAMERA);
        }
        if (!found) {
            if (camera_visible_path && settings_.film_transparent) {
                transparency += beta.average();
                break;
            }
            // The environment is also sampled by NEE: MIS against it, as for emissive triangles.
            float w = 1.0f;
            if (scatter_pdf > 0.0f && lights.environment()) {
                w = power_heuristic(scatter_pdf, lights.environment_pdf(dir));
            }
            L += beta * scene.background(dir) * w;
            break;
        }
        const Vec3 wo_world = -dir;
        const ShadingPoint sp = build_closures(scene, hit, wo_world);
        const ClosureSet& closures = sp.closures;

        if (camera_visible_path) {
            const Rgb holdout = hit.holdout ? Rgb(1.0f) : closures.holdout();
            if (!holdout.is_black()) transparency += (holdout * beta).average();
            if (hit.holdout) break;
        }
        const Rgb emission = closures.emission();
        if (!emission.is_black()) {
            float w = 1.0f;
            if (scatter_pdf > 0.0f && hit.emissive_light != kNoLight) {
                w = power_heuristic(scatter_pdf, lights.emissive_triangle_pdf(hit.emissive_light,
                                                                              scatter_origin, hit.position));
            }
            L += beta * emission * w;
        }
        if (bounce > settings_.max_bounces) {
            // Past the last bounce Cycles still follows transparent closures to collect the
            // emission behind them (PATH_RAY_TERMINATE_AFTER_TRANSPARENT): continue straight on
            // with their summed weight, the expectation of picking the transparent closure.
            const Rgb pass = closures.transparency();
            if (pass.is_black() || ++transparent_bounce > settings_.transparent_max_bounces) break;
            beta *= pass;
            origin = offset_ray_origin(hit.position, -sp.ng);
            t_min = 0.0f;
            t_max = kInfinity;
            continue;
        }
        if (!closures.scatters()) break;

        const Frame frame = Frame::from_normal(sp.ns);
        const Vec3 wo = frame.to_local(wo_world);

        // Next-event estimation (textbook 5.7–5.16), MIS-weighted against BSDF sampling. Lights
        // below the surface count only for closures that transmit.
        LightSample ls;
        if (closures.has_non_delta() &&
            lights.sample(hit.position, sampler.get_1d(pixel, bounce_dimension(vertex, kDimLightChoice)),
                          sampler.get_2d(pixel, bounce_dimension(vertex, kDimLightPoint)), &ls)) {
            const float side = dot(ls.wi, sp.ng);
            const uint32_t kinds = lit_kinds(ls.visibility);
            if ((side > 0.0f || (side < 0.0f && closures.has_transmission())) && kinds != 0) {
                const Vec3 wi_local = frame.to_local(ls.wi);
                // A direction on the other side of the shading normal than of the true surface
                // cannot be reached by light: the shading hemisphere must agree with ng.
                const BsdfEval f = (wi_local.z > 0.0f) == (side > 0.0f)
                                       ? closures.eval(wo, wi_local, settings_.hemisphere, kinds)
                                       : BsdfEval{Rgb(0.0f), 0.0f};
                if (!f.value.is_black()) {
                    const Vec3 o = offset_ray_origin(hit.position, side > 0.0f ? sp.ng : -sp.ng);
                    const ShadowRay shadow = std::isinf(ls.distance)
                                                 ? ShadowRay{ls.wi, kInfinity}
                                                 : shadow_ray_to(o, hit.position + ls.wi * ls.distance);
                    Rgb transmittance(1.0f);
                    if (ls.visibility & STRATUM_VISIBLE_SHADOW) {
                        const uint32_t left =
                            max_shadow_surfaces - std::min(max_shadow_surfaces, transparent_bounce);
                        transmittance =
                            shadow_transmittance(scene, o, shadow.direction, shadow.t_max,
                                                 {query.time, STRATUM_VISIBLE_SHADOW}, left, rays);
                    }
                    if (!transmittance.is_black()) {
                        const float w = ls.found_by_bsdf_rays ? power_heuristic(ls.pdf, f.pdf) : 1.0f;
                        L += beta * f.value * transmittance * ls.radiance * (w / ls.pdf);
                    }
                }
            }
        }

        BsdfSample bs;
        if (!closures.sample(wo, sampler.get_1d(pixel, bounce_dimension(vertex, kDimBsdfLobe)),
                             sampler.get_2d(pixel, bounce_dimension(vertex, kDimBsdfDirection)), &bs,
                             settings_.hemisphere)) {
            break;
        }
        const Vec3 wi = frame.to_world(bs.wi);
        // A direction the shading normal allows but the true surface does not: light cannot
        // get there, so the path ends.
        const bool below = dot(wi, sp.ng) < 0.0f;
        if ((bs.wi.z < 0.0f) != below || dot(wi, sp.ng) == 0.0f) break;
        beta *= bs.weight;
        if (bs.kind == ScatterKind::Transparent) {
            // Pass-through: not a bounce; the MIS pdf and origin of the last real scatter stay.
            if (++transparent_bounce > settings_.transparent_max_bounces) break;
        } else {
            camera_visible_path = false;
            scatter_pdf = bs.delta ? 0.0f : bs.pdf;
            scatter_origin = hit.position;
            if (bounce >= kRouletteStartBounce) {
                const float survive = std::min(1.0f, beta.max_component());
                if (sampler.get_1d(pixel, bounce_dimension(vertex, kDimRussianRoulette)) >= survive) break;
                beta *= 1.0f / survive;
            }
            ++bounce;
        }
        query.visibility = ray_visibility(bs.kind, query.visibility);
        origin = offset_ray_origin(hit.position, below ? -sp.ng : sp.ng);
        dir = wi;
        t_min = 0.0f;
        t_max = kInfinity;
    }
    return {L, std::clamp(1.0f - transparency, 0.0f, 1.0f)};
}

}  // namespace stratum
