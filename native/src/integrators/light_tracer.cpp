#include "integrators/light_tracer.h"

#include <algorithm>
#include <cmath>

#include "integrators/camera_path_passes.h"
#include "integrators/light_path_readers.h"
#include "integrators/linking_notice.h"
#include "integrators/ray_offset.h"
#include "integrators/ray_visibility.h"
#include "integrators/shading_point.h"
#include "integrators/transparent_shadow.h"
#include "lights/light_registry.h"
#include "sampling/dimensions.h"
#include "sampling/warps.h"
#include "scene/visibility.h"

namespace stratum {

namespace {

bool is_finite(Rgb c) { return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b); }

constexpr uint32_t kNonCameraRays = kVisibleDiffuse | kVisibleGlossy | kVisibleTransmission | kVisibleShadow;

// Veach 1997 eq. 5.19: the adjoint BSDF with shading normals is f(ω_l, ω_o) |ω_l·n_s| |ω_o·n_g|
// / (|ω_l·n_g| |ω_o·n_s|) times the radiance form's |ω_o·n_s|; this returns the ratio (1 where
// shading and true normals agree), 0 where a cosine vanishes.
float adjoint_correction(Vec3 arrival, Vec3 out, Vec3 ns, Vec3 ng) {
    const float den = std::abs(dot(arrival, ng)) * std::abs(dot(out, ns));
    return den > 0.0f ? std::abs(dot(arrival, ns)) * std::abs(dot(out, ng)) / den : 0.0f;
}

// The adjoint BSDF times the connection cosine, f*(ω_l → ω_o) |ω_o·n_s| with Veach's shading-normal
// correction (eq. 5.19): f(ω_o, ω_l) |ω_l·n_s| |ω_o·n_g| / |ω_l·n_g|. Evaluating the closures
// with wo = ω_o (the direction toward the camera side of the path), as a camera path evaluates
// them, keeps non-reciprocal closures exact: Principled v2 scales its diffuse base by what its
// coat reflects toward wo (Kulla–Conty layering), so f(ω_l, ω_o) ≠ f(ω_o, ω_l). The closures
// take wo above the shading surface only; a transmitted ω_o (refraction toward the camera side)
// is evaluated the other way round, exact for reciprocal lobes.
Rgb adjoint_value(const ClosureSet& closures, Vec3 wo_local, Vec3 out_local, Vec3 arrival, Vec3 out,
                  const ShadingPoint& sp, HemisphereDistribution hemisphere, uint32_t kinds) {
    if (out_local.z > 0.0f && wo_local.z > 0.0f) {
        const float den = std::abs(dot(arrival, sp.ng));
        if (!(den > 0.0f)) return Rgb(0.0f);
        return closures.eval(out_local, wo_local, hemisphere, kinds).value *
               (std::abs(dot(out, sp.ng)) / den);
    }
    return closures.eval(wo_local, out_local, hemisphere, kinds).value *
           adjoint_correction(arrival, out, sp.ns, sp.ng);
}

// A constant background (no environment image) lights the scene like a uniform sky of radiance
// L: the direction toward the sky uniform on the sphere (p_ω = 1/(4π)), then a parallel beam over
// the disk of radius R tangent to the bounding sphere (p_A = 1/(πR²)): weight 4π·πR²·L.
void sample_sky_emission(Rgb radiance, Vec2 u_position, Vec2 u_direction, Vec3 center, float radius,
                         EmissionSample* out) {
    const Vec3 toward_sky = sample_uniform_sphere(u_direction);
    const Frame frame = Frame::from_normal(toward_sky);
    const Vec2 d = sample_uniform_disk_concentric(u_position);
    out->position = center + toward_sky * radius + (frame.s * d.x + frame.t * d.y) * radius;
    out->direction = -toward_sky;
    out->normal = toward_sky;
    out->weight = radiance * (kPi * radius * radius / uniform_sphere_pdf());
    out->soft_radius = 0.0f;
}

}  // namespace

RadianceSample LightTracer::estimate(const RenderScene& scene, const Sampler& sampler,
                                     const PixelSample& pixel, const CameraRay& camera_ray,
                                     PassValues& passes, uint64_t& rays) const {
    (void)sampler;
    (void)pixel;
    Rgb L(0.0f), beta(1.0f);
    float transparency = 0.0f;
    Vec3 origin = camera_ray.origin;
    const Vec3 dir = camera_ray.direction;
    float t_min = camera_ray.t_min, t_max = camera_ray.t_max;
    const RayQuery query{camera_ray.time, kVisibleCamera};
    const LightSet& lights = scene.lights();
    CameraPathPasses data(passes, settings_.mist);
    RayTrack track = RayTrack::camera(camera_ray);
    const float clamp = settings_.light_paths.clamp_direct;
    for (uint32_t passed = 0;; ++passed) {
        SurfaceHit hit;
        ++rays;
        const bool found = scene.intersect(origin, dir, t_min, t_max, &hit, query);
        // What the camera sees directly is direct light (clamp_direct), as on a camera path.
        const Rgb lamp = clamp_contribution(
            beta * lights.lamp_radiance(origin, dir, found ? hit.t : t_max, kVisibleCamera), clamp);
        data.emitted(lamp, true);
        if (!found) {
            if (data.pending())
                data.miss(settings_.film_transparent
                              ? Rgb(0.0f)
                              : clamp_contribution(beta * scene.background(dir), clamp),
                          true);
            if (settings_.film_transparent) {
                transparency += beta.average();
            } else {
                L += clamp_contribution(beta * scene.background(dir), clamp);
            }
            break;
        }
        const ShadingPoint sp = build_closures(scene, hit, -dir, track.at(hit.t));
        const ClosureSet& closures = sp.closures;
        data.surface(hit, sp.ns, -dir, closures, beta, true, clamp);
        const Rgb holdout = hit.holdout ? Rgb(1.0f) : closures.holdout();
        if (!holdout.is_black()) transparency += (holdout * beta).average();
        if (hit.holdout) break;
        L += clamp_contribution(beta * closures.emission(), clamp);
        // Straight on through Transparent closures (not a bounce), as a camera path goes on.
        const Rgb pass = closures.transparency();
        if (pass.is_black() || passed >= settings_.transparent_max_bounces) break;
        beta *= pass;
        track.pass_through(hit.t);
        origin = offset_ray_origin(hit.position, -sp.ng);
        t_min = 0.0f;
        t_max = kInfinity;
    }
    data.finish();
    return {L, std::clamp(1.0f - transparency, 0.0f, 1.0f)};
}

void LightTracer::trace_light_path(const RenderScene& scene, const Sampler& sampler, const Camera& camera,
                                   const Film& film, const PixelSample& particle, std::vector<Splat>& splats,
                                   uint64_t& rays) const {
    const LightSet& lights = scene.lights();
    EmissionSample e;
    const float u_choice = sampler.get_1d(particle, kDimEmissionLight);
    const Vec2 u_position = sampler.get_2d(particle, kDimEmissionPoint);
    const Vec2 u_direction = sampler.get_2d(particle, kDimEmissionDirection);
    const float p_sky = sky_probability_;
    if (u_choice < p_sky) {
        sample_sky_emission(scene.background(Vec3(0.0f, 0.0f, 1.0f)), u_position, u_direction,
                            scene.bounds_center(), scene.bounds_radius(), &e);
        e.weight = e.weight * (1.0f / p_sky);
    } else {
        // u_choice rescaled to [0, 1) for the lights' own choice.
        const float u_light = std::min((u_choice - p_sky) / (1.0f - p_sky), kOneMinusEpsilon);
        if (!lights.sample_emission(u_light, u_position, u_direction, settings_.light_selection,
                                    scene.bounds_center(), scene.bounds_radius(), &e)) {
            return;
        }
        e.weight = e.weight * (1.0f / (1.0f - p_sky));
    }
    if (e.weight.is_black()) return;
    // W×H particles per sample index: each carries 1/(W H) of the flux estimate.
    const Rgb beta0 =
        e.weight *
        (1.0f / (static_cast<float>(film.frame_width()) * static_cast<float>(film.frame_height())));
    Rgb throughput(1.0f);  // β / β₀: what Russian roulette by throughput looks at
    const float time = scene.has_motion() ? sampler.get_1d(particle, kDimTime) : 0.5f;
    RayQuery query{time, kNonCameraRays};
    Vec3 origin = dot(e.normal, e.normal) > 0.0f ? offset_ray_origin(e.position, e.normal) : e.position;
    Vec3 dir = e.direction;
    const uint32_t first_kinds = lit_kinds(e.visibility);
    uint32_t depth = 0, transparent = 0;  // scattering vertices so far; pass-throughs so far
    RayTrack track;                       // ray lengths; no footprint (light paths have no pixel)
    bool first_hit = true;
    const uint32_t max_passes = settings_.transparent_max_bounces;
    // The per-kind bounce limits (integrators/light_path_limits.h) read along the camera path this
    // particle's connection at depth d makes: its scatterings are the connection's and those of
    // the vertices at depths d−1 .. 1, whose counts must stay within the limits; the first hit's
    // scattering toward the lamp is the camera path's last, which no limit stops (a light sample).
    const LightPathLimits& limits = settings_.light_paths;
    BounceCounts beyond_first;

    for (uint32_t vertex = 0;; ++vertex) {
        SurfaceHit hit;
        ++rays;
        if (!scene.intersect(origin, dir, 0.0f, kInfinity, &hit, query)) break;
        if (first_hit && e.soft_radius > 0.0f) {
            const Vec3 d = hit.position - e.position;
            const float d2 = dot(d, d);
            throughput *= d2 / (d2 + e.soft_radius * e.soft_radius);
        }
        // A lamp's program (its node tree) at the distance the particle travelled from the lamp.
        // A lamp's program sees the Light Path inputs of direct light (notices()).
        if (first_hit && e.program)
            throughput *= e.program->scale(length(hit.position - e.position), kDirectLightPath);
        first_hit = false;
        const Vec3 arrival = -dir;  // toward the light
        const ShadingPoint sp = build_closures(scene, hit, arrival, track.at(hit.t));
        const ClosureSet& closures = sp.closures;
        const Frame frame = Frame::from_normal(sp.ns);
        const Vec3 wo = frame.to_local(arrival);
        const uint32_t kinds = depth == 0 ? first_kinds : beyond_first.kinds_within(limits);

        // Camera connection (6.8–6.9): the scattering of this vertex toward the lens.
        if (closures.has_non_delta() && !hit.holdout && (hit.visibility & kVisibleCamera) &&
            depth <= settings_.max_bounces && kinds != 0) {
            const Vec2 lens = camera.has_aperture()
                                  ? sampler.get_2d(particle, bounce_dimension(vertex, kDimConnectionLens))
                                  : Vec2{0.5f, 0.5f};
            CameraConnection c;
            if (camera.connect(hit.position, lens, &c)) {
                const float side = dot(c.to_camera, sp.ng);
                const Vec3 wc = frame.to_local(c.to_camera);
                if ((side > 0.0f || (side < 0.0f && closures.has_transmission())) &&
                    (wc.z > 0.0f) == (side > 0.0f)) {
                    const Rgb f = adjoint_value(closures, wo, wc, arrival, c.to_camera, sp,
                                                settings_.hemisphere, kinds);
                    const Rgb value = beta0 * throughput * f * c.importance;
                    if (!value.is_black() && is_finite(value)) {
                        const Vec3 o = offset_ray_origin(hit.position, side > 0.0f ? sp.ng : -sp.ng);
                        const float t_max = std::max(0.0f, c.unclipped - offset_distance(hit.position));
                        const Rgb transmittance =
                            shadow_transmittance(scene, o, c.to_camera, t_max, {time, kVisibleCamera},
                                                 max_passes - std::min(max_passes, transparent), rays);
                        film.splat(c.film, value * transmittance, splats);
                    }
                }
            }
        }

        if (depth >= settings_.max_bounces && closures.transparency().is_black()) break;
        if (!closures.scatters()) break;
        BsdfSample bs;
        if (!closures.sample(wo, sampler.get_1d(particle, bounce_dimension(vertex, kDimBsdfLobe)),
                             sampler.get_2d(particle, bounce_dimension(vertex, kDimBsdfDirection)), &bs,
                             settings_.hemisphere)) {
            break;
        }
        const Vec3 wi = frame.to_world(bs.wi);
        const bool below = dot(wi, sp.ng) < 0.0f;
        if ((bs.wi.z < 0.0f) != below || dot(wi, sp.ng) == 0.0f) break;
        if (bs.kind == ScatterKind::Transparent) {
            if (++transparent > max_passes) break;
            throughput *= bs.weight;
            track.pass_through(hit.t);
        } else {
            track.scatter(hit.t, 0u);  // a particle's ray has no Cycles kind (notices())
            // A scattering past the cap would lead to a vertex that may not connect; the light
            // lights only the kinds its visibility allows at the first vertex.
            if (depth >= settings_.max_bounces) break;
            if (depth == 0 && !(first_kinds & scatter_kind_bit(bs.kind))) break;
            if (depth > 0) beyond_first.scatter(bs.kind);
            if (beyond_first.exhausted(settings_.max_bounces, limits)) break;
            // The adjoint scattering weight f(ω_o, ω_l) |ω_l·n_s| |ω_o·n_g| / (|ω_l·n_g| p), by the
            // same evaluation as the connection; delta lobes (mirror, refraction) keep the sampled
            // weight with the shading-normal correction.
            const Rgb scattering = bs.delta || bs.wi.z <= 0.0f
                                       ? bs.weight * adjoint_correction(arrival, wi, sp.ns, sp.ng)
                                       : adjoint_value(closures, wo, bs.wi, arrival, wi, sp,
                                                       settings_.hemisphere, ClosureSet::kAllKinds) *
                                             (1.0f / bs.pdf);
            throughput *= scattering;
            if (depth >= settings_.rr_min_depth && settings_.rr_mode != RouletteMode::Off) {
                const float survive = std::min(1.0f, settings_.rr_mode == RouletteMode::Throughput
                                                         ? throughput.max_component()
                                                         : scattering.max_component());
                if (!(sampler.get_1d(particle, bounce_dimension(vertex, kDimRussianRoulette)) < survive))
                    break;
                throughput *= 1.0f / survive;
            }
            ++depth;
        }
        if (throughput.is_black()) break;
        query.visibility = ray_visibility(bs.kind, query.visibility);
        origin = offset_ray_origin(hit.position, below ? -sp.ng : sp.ng);
        dir = wi;
    }
}

float LightTracer::sky_probability(const RenderScene& scene) {
    const LightSet& lights = scene.lights();
    if (lights.environment()) return 0.0f;  // the environment is one of the lights
    const float sky = scene.background(Vec3(0.0f, 0.0f, 1.0f)).average();
    if (!(sky > 0.0f)) return 0.0f;
    double total = 0.0;
    for (uint32_t i = 0; i < lights.size(); ++i) total += lights.power(i);
    // The sky's power as LightSet rates an environment: π R² L̄.
    const double sky_power = kPi * sqr(scene.bounds_radius()) * sky;
    return total > 0.0 ? static_cast<float>(sky_power / (sky_power + total)) : 1.0f;
}

std::vector<std::string> LightTracer::notices(const Scene& scene) const {
    std::vector<std::string> out;
    const LightPathLimits& paths = settings_.light_paths;
    if (paths.filter_glossy > 0.0f || !paths.caustics_reflective || !paths.caustics_refractive) {
        out.emplace_back(
            "light tracing does not apply filter_glossy or the caustics switches: they change a camera "
            "path's closures by what the path did before, which a particle cannot know; every glossy "
            "lobe is taken unblurred");
    }
    if (settings_.light_paths.clamp_indirect > 0.0f) {
        out.emplace_back(
            "light tracing does not clamp indirect light: clamping scales a camera sample's contributions, "
            "and "
            "a particle's splat is none (clamp_direct still applies to what the camera sees directly)");
    }
    if (scene.camera && scene.camera->type == CameraType::Orthographic) {
        out.emplace_back(
            "light tracing cannot connect to an orthographic camera: only what the camera sees directly is "
            "rendered");
    } else if (scene.camera && scene.camera->type == CameraType::Equirectangular) {
        out.emplace_back(
            "light tracing cannot connect to an equirectangular camera: only what the camera sees directly "
            "is "
            "rendered");
    }
    bool transmissive = false;
    for (const SceneMaterial& m : scene.materials) {
        for (const WeightedClosure& c : m.closures) transmissive |= bsdf_has_transmission(c.params);
    }
    if (transmissive) {
        out.emplace_back(
            "light tracing does not apply the refraction factor eta^2 to particles: what is seen through "
            "refracting (glass, transmission) surfaces is too bright or too dark by that factor");
    }
    if (const std::string lp = light_path_notice(scene, "light tracing"); !lp.empty()) out.push_back(lp);
    // RenderScene makes lights only of static emissive triangles (a moving triangle has no single
    // position to sample); camera and BSDF rays still find moving ones, particles never leave them.
    for (const Instance& inst : scene.instances) {
        if (!inst.motion || inst.object_to_world.m == inst.object_to_world_end.m) continue;
        bool emits = false;
        for (const uint32_t id : scene.meshes[inst.mesh_id].material_ids)
            emits |= !material_emission(scene.materials[id]).is_black();
        if (emits) {
            out.emplace_back(
                "light tracing emits no particles from moving emissive objects: the light they cast on other "
                "surfaces is missing (the camera still sees them)");
            break;
        }
    }
    if (const auto linking = unsupported_linking_notice(scene, "light tracing")) out.push_back(*linking);
    if (scene.lights.size() > 0) {
        for (const LightParams& l : scene.lights) {
            if (make_light(l)->emits_from_its_centre()) {
                out.emplace_back(
                    "light tracing emits point and spot lamps with a radius from their centre: their shadows "
                    "are "
                    "hard and their light on surfaces not facing them is approximate");
                break;
            }
        }
    }
    return out;
}

}  // namespace stratum
