#include "integrators/path_integrator.h"

#include <algorithm>
#include <array>

#include "integrators/camera_path_passes.h"
#include "integrators/guided_direction.h"
#include "integrators/light_group_writer.h"
#include "integrators/light_path_closures.h"
#include "integrators/ray_offset.h"
#include "integrators/ray_visibility.h"
#include "integrators/shading_point.h"
#include "integrators/shadow_catcher.h"
#include "integrators/transparent_shadow.h"
#include "lights/light_registry.h"
#include "sampling/dimensions.h"
#include "sampling/hash.h"
#include "scene/visibility.h"

namespace stratum {

void PathIntegrator::prepare(const RenderScene& scene, const std::atomic<bool>&) {
    if (scene.lights().resolve(settings_.light_selection) == LightSelection::Tree)
        (void)scene.lights().tree();
    if (settings_.use_guiding) {
        guide_ = std::make_unique<GuidingTree>(scene.bounds_center(), 1.01f * scene.bounds_radius(),
                                               settings_.guiding_split);
        guiding_report_ = GuidingReport{guide_->node_count(), guide_->region_count(), guide_->bytes(), 0, 0};
    }
}

void PathIntegrator::end_pass(uint32_t begin, uint32_t end) {
    if (!guide_ || begin >= settings_.guiding_training_samples) return;
    guiding_report_.records += guide_->update();
    ++guiding_report_.training_passes;
    guiding_report_.nodes = guide_->node_count();
    guiding_report_.regions = guide_->region_count();
    // The most it holds is now, with the next pass's counters; after the last training pass
    // the counters go and the tree is read only.
    guiding_report_.bytes = std::max<uint64_t>(guiding_report_.bytes, guide_->bytes());
    if (end >= settings_.guiding_training_samples) guide_->stop_learning();
}

float PathIntegrator::hit_weight(float scatter_pdf, float light_pdf) const {
    // A camera ray or a delta scatter: no light sample could have found this emission (5.16).
    // Emission light sampling cannot reach (light_pdf 0) is found by rays alone.
    if (!(scatter_pdf > 0.0f) || !(light_pdf > 0.0f)) return 1.0f;
    switch (settings_.light_sampling) {
        case LightSampling::Bsdf:
            return 1.0f;
        case LightSampling::Nee:
            return 0.0f;
        case LightSampling::Mis:
            break;
    }
    return mis_weight(settings_.mis_heuristic, scatter_pdf, light_pdf);
}

std::vector<std::string> PathIntegrator::notices(const Scene& scene) const {
    if (settings_.light_sampling != LightSampling::Bsdf) return {};
    uint32_t unreachable = 0;
    // Delta lights (each model says whether it is one) are found by light sampling only.
    for (const LightParams& l : scene.lights)
        if (make_light(l)->is_delta()) ++unreachable;
    if (unreachable == 0) return {};
    return {"light_sampling 'bsdf' finds emission only by hitting it: " + std::to_string(unreachable) +
            " light(s) without a surface (point or spot of radius 0, sun of angle 0) add nothing; "
            "choose light_sampling 'nee' or 'mis' to see them"};
}

RadianceSample PathIntegrator::estimate(const RenderScene& scene, const Sampler& sampler,
                                        const PixelSample& pixel, const CameraRay& camera_ray,
                                        PassValues& passes, uint64_t& rays) const {
    ShadowCatcherPath catcher = ShadowCatcherPath::main(scene.has_shadow_catcher());
    const RadianceSample sample = trace(scene, sampler, pixel, camera_ray, passes, rays, catcher);
    if (!catcher.active()) return sample;
    Rgb catcher_light(0.0f);
    if (catcher.split()) {
        ShadowCatcherPath copy = catcher.copy();
        PassValues groups_only = passes.lightgroups_only();
        catcher_light = trace(scene, sampler, pixel, camera_ray, groups_only, rays, copy).radiance;
    }
    passes.write(catcher.sample(sample.radiance, sample.alpha, catcher_light));
    return sample;
}

RadianceSample PathIntegrator::trace(const RenderScene& scene, const Sampler& sampler,
                                     const PixelSample& pixel, const CameraRay& camera_ray,
                                     PassValues& passes, uint64_t& rays, ShadowCatcherPath& catcher) const {
    Rgb L(0.0f), beta(1.0f);
    float transparency = 0.0f;  // Cycles' "transparent" film value: alpha = 1 - transparency
    Vec3 origin = camera_ray.origin, dir = camera_ray.direction;
    float t_min = camera_ray.t_min, t_max = camera_ray.t_max;
    RayTrack track = RayTrack::camera(camera_ray);  // what the hits' programs see of the ray
    float scatter_pdf = 0.0f;  // solid-angle pdf of the last scattering; 0 for camera and delta rays
    Vec3 scatter_origin, scatter_normal;  // the last scattering vertex and its shading normal
    RayQuery query{camera_ray.time, kVisibleCamera};
    // Cycles' PATH_RAY_TRANSPARENT_BACKGROUND: only camera and transparent vertices so far.
    bool camera_visible_path = true;
    BounceCounts bounces;  // scatterings so far, by kind (integrators/light_path_limits.h)
    // What the path changes of its next closures: Filter Glossy, caustics (light_path_closures.h).
    PathClosureState closure_state;
    uint32_t transparent_bounce = 0;
    // Light linking's receiver of forward emission: the surface of the last scattering (Cycles'
    // mis_ray_object); camera rays see every emitter (lights/light_set.h EmitterLinkFilter).
    uint8_t receiver_set = 0;
    const LightPathLimits& limits = settings_.light_paths;
    const LightSet& lights = scene.lights();
    const LightSelection selection = settings_.light_selection;
    const uint32_t tree_splits = settings_.light_tree_splits;
    const uint32_t max_shadow_surfaces = settings_.transparent_max_bounces;
    const float ambient = settings_.control_variate;  // L_a of the control variate (5.17)
    CameraPathPasses data(passes, settings_.mist);
    LightGroupWriter groups(passes, catcher, settings_.lightgroup_split_emission);
    // Path guiding: this sample trains the tree while its index is below the training samples.
    PathRecords records(guide_ && pixel.index < settings_.guiding_training_samples && !catcher.is_copy()
                            ? guide_.get()
                            : nullptr);

    // `vertex` numbers every surface the path meets (bounces and pass-throughs), so each owns a
    // block of sample dimensions.
    for (uint32_t vertex = 0;; ++vertex) {
        SurfaceHit hit;
        ++rays;
        const bool found = scene.intersect(origin, dir, t_min, t_max, &hit, catcher.query(query));
        const EmitterLinkFilter link{!camera_visible_path, receiver_set};
        // The lights NEE chose among at the last scattering (light linking: those lighting its
        // surface), whose probabilities the MIS weights of what this ray finds take.
        const LightSet& forward_lights = camera_visible_path ? lights : scene.lights_for(receiver_set);
        // Lamps have no geometry: the emitting face of an area lamp is met analytically, in front
        // of whatever the ray hits, if the lamp is visible to this kind of ray. A camera ray takes
        // it whole (no light sample competes); a scattered ray is MIS-weighted against the NEE
        // sample that could have found the same direction (delta scattering: NEE could not).
        // What the Light Path node sees of the path as the ray arrives (Cycles' path state).
        const LightPathState arriving = track.at(0.0f, bounces, transparent_bounce).path;
        {
            float lamp_pdf = 0.0f, lamp_t = 0.0f;
            uint32_t lamp_group = 0;
            const Rgb lamp = forward_lights.lamp_radiance(
                origin, dir, found ? hit.t : t_max,
                catcher.ray_visibility_bits(camera_visible_path ? uint32_t{kVisibleCamera}
                                                                : query.visibility),
                &lamp_pdf, &lamp_t, selection, scatter_origin, scatter_normal, tree_splits,
                arriving.emission(), link, &lamp_group);
            if (!lamp.is_black()) {
                float w = 1.0f;
                if (!camera_visible_path && scatter_pdf > 0.0f) {
                    // NEE sampled from the scattering point: after transparent pass-throughs the
                    // ray started further on, and the solid-angle pdf scales with distance².
                    const Vec3 lamp_point = origin + dir * lamp_t;
                    const float scale = dot(lamp_point - scatter_origin, lamp_point - scatter_origin) /
                                        std::max(lamp_t * lamp_t, 1e-30f);
                    w = hit_weight(scatter_pdf, lamp_pdf * scale);
                }
                const Rgb found_lamp =
                    clamp_contribution(beta * lamp * w, emission_clamp(limits, bounces.total()));
                L += found_lamp;
                groups.emission(lamp_group, found_lamp);
                records.add_found(found_lamp, beta * lamp);
                data.emitted(found_lamp, camera_visible_path);
            }
        }
        if (!found) {
            const bool transparent_film = camera_visible_path && settings_.film_transparent;
            const Rgb background = scene.background(dir, arriving.background());
            if (camera_visible_path) catcher.camera_miss(beta * background);
            if (data.pending())
                data.miss(transparent_film ? Rgb(0.0f)
                                           : clamp_contribution(beta * background,
                                                                emission_clamp(limits, bounces.total())),
                          camera_visible_path);
            if (transparent_film) {
                transparency += beta.average();
                break;
            }
            // The environment is also sampled by NEE: MIS against it, as for emissive triangles.
            const float w = hit_weight(scatter_pdf, light_pdf_matters(scatter_pdf) && lights.environment()
                                                        ? forward_lights.environment_pdf(dir, selection)
                                                        : 0.0f);
            const Rgb found_background =
                clamp_contribution(beta * background * w, emission_clamp(limits, bounces.total()));
            L += found_background;
            groups.emission(scene.world_lightgroup(), found_background);
            records.add_found(found_background, beta * background);
            break;
        }
        if (catcher.splits_at(hit, camera_visible_path))
            catcher.split_here(beta, transparency, scene.background(dir, arriving.background()), L);
        const Vec3 wo_world = -dir;
        const RayReach reach = track.at(hit.t, bounces, transparent_bounce);
        const ShadingPoint sp = build_closures(scene, hit, wo_world, reach, closure_state.filter(limits));
        const ClosureSet& closures = sp.closures;
        data.surface(hit, sp.ns, wo_world, closures, beta, camera_visible_path,
                     emission_clamp(limits, bounces.total()));
        if (camera_visible_path && data.wants_ao())
            data.ao(scene, hit.position, sp.ns, sp.ng,
                    sampler.get_2d(pixel, bounce_dimension(vertex, kDimBsdfDirection)),
                    beta * (Rgb(1.0f) - closures.transparency()), query.time, settings_.ao_distance, rays);

        if (camera_visible_path) {
            const Rgb holdout = hit.holdout ? Rgb(1.0f) : closures.holdout();
            if (!holdout.is_black()) transparency += (holdout * beta).average();
            if (hit.holdout) break;
        }
        const Rgb emission = closures.emission();
        if (!emission.is_black() && link.accepts(hit.links)) {
            const float light_pdf =
                light_pdf_matters(scatter_pdf) && hit.emissive_light != kNoLight
                    ? forward_lights.emissive_triangle_pdf(
                          scene.light_index_for(receiver_set, hit.emissive_light), scatter_origin,
                          scatter_normal, hit.position, selection, settings_.triangle_sampling, tree_splits)
                    : 0.0f;
            const Rgb found_emission =
                clamp_contribution(beta * emission * hit_weight(scatter_pdf, light_pdf),
                                   emission_clamp(limits, bounces.total()));
            L += found_emission;
            groups.emission(hit.lightgroup, found_emission);
            records.add_found(found_emission, beta * emission);
        }
        if (bounces.exhausted(settings_.max_bounces, limits)) {
            // Past the last bounce (of any kind) Cycles still follows transparent closures to collect
            // the emission behind them (PATH_RAY_TERMINATE_AFTER_TRANSPARENT): continue straight on
            // with their summed weight, the expectation of picking the transparent closure.
            const Rgb pass = closures.transparency();
            if (pass.is_black() || ++transparent_bounce > settings_.transparent_max_bounces) break;
            beta *= pass;
            track.pass_through(hit.t);
            origin = offset_ray_origin(hit.position, -sp.ng);
            t_min = 0.0f;
            t_max = kInfinity;
            continue;
        }
        if (!closures.scatters()) break;

        const Frame frame = Frame::from_normal(sp.ns);
        const Vec3 wo = frame.to_local(wo_world);
        // The guide at this vertex, where the closures have a non-delta part to guide.
        GuidedVertex guide;
        if (guide_ && closures.has_non_delta())
            guide = GuidedVertex{guide_.get(), guide_->region(hit.position), settings_.guiding_bsdf_fraction,
                                 frame};

        // Next-event estimation (textbook 5.7–5.16), MIS-weighted against BSDF sampling. Lights
        // below the surface count only for closures that transmit.
        // With the tree's splitting (light_tree_splits > 1) one sample per cut node, summed.
        // Light linking: among the lights that light this surface (RenderScene::lights_for).
        const LightSet& nee_lights = scene.lights_for(hit.links.receiver_light_set);
        std::array<LightSample, LightTree::kMaxCut> light_samples;
        const uint32_t light_sample_count =
            settings_.light_sampling != LightSampling::Bsdf && closures.has_non_delta()
                ? nee_lights.sample_cut(
                      hit.position, sp.ns, sampler.get_1d(pixel, bounce_dimension(vertex, kDimLightChoice)),
                      sampler.get_2d(pixel, bounce_dimension(vertex, kDimLightPoint)), light_samples.data(),
                      selection, settings_.triangle_sampling, tree_splits, reach.path.emission())
                : 0u;
        for (uint32_t s = 0; s < light_sample_count; ++s) {
            const LightSample& ls = light_samples[s];
            const float side = dot(ls.wi, sp.ng);
            const uint32_t light_visibility = catcher.light_visibility(ls.visibility);
            const uint32_t kinds = lit_kinds(light_visibility);
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
                    if (light_visibility & kVisibleShadow) {
                        const uint32_t left =
                            max_shadow_surfaces - std::min(max_shadow_surfaces, transparent_bounce);
                        transmittance = shadow_transmittance(
                            scene, o, shadow.direction, shadow.t_max,
                            catcher.query({query.time, kVisibleShadow}), left, rays, reach.footprint,
                            reach.path, nee_lights.links(ls.light).shadow_set_membership);
                    }
                    if (!transmittance.is_black()) {
                        const float w =
                            ls.found_by_bsdf_rays && settings_.light_sampling == LightSampling::Mis
                                ? mis_weight(settings_.mis_heuristic, ls.pdf,
                                             guide.active() ? guide.mixed_pdf(f.pdf, ls.wi) : f.pdf)
                                : 1.0f;
                        const Rgb sampled_light =
                            clamp_contribution(beta * f.value * transmittance * ls.radiance * (w / ls.pdf),
                                               light_sample_clamp(limits, bounces.total()));
                        L += sampled_light;
                        groups.light_sample(ls.lightgroup, sampled_light);
                        records.add(sampled_light);
                    }
                }
            }
        }

        // Control variate (textbook 5.17–5.18): the Lambertian closures' share of the scattered
        // radiance is estimated as L_a ρ_L (known exactly) plus f_L cos (L_i − L_a)/p, so the
        // vertex adds β L_a ρ_L now and the continued path subtracts β L_a f_L cos/p below.
        const Rgb lambertian_albedo = ambient > 0.0f ? closures.lambertian_albedo() : Rgb(0.0f);
        const bool control_variate = !lambertian_albedo.is_black();
        if (control_variate) L += beta * lambertian_albedo * ambient;

        BsdfSample bs;
        const float u_lobe = sampler.get_1d(pixel, bounce_dimension(vertex, kDimBsdfLobe));
        const Vec2 u_direction = sampler.get_2d(pixel, bounce_dimension(vertex, kDimBsdfDirection));
        const bool sampled =
            guide.active() ? sample_guided(closures, wo, guide,
                                           sampler.get_1d(pixel, bounce_dimension(vertex, kDimGuideChoice)),
                                           u_lobe, u_direction, &bs, settings_.hemisphere)
                           : closures.sample(wo, u_lobe, u_direction, &bs, settings_.hemisphere);
        // A guided direction the closures do not scatter into carries 0 (its control-variate
        // part too: the Lambertian value is part of the closures' value there).
        if (!sampled) break;
        // L_a f_L cos / p of this sample: the control variate's Monte Carlo part. A delta sample
        // carries no Lambertian density (closures.sample's one-sample MIS covers f_L with the
        // non-delta picks only).
        const Rgb cv_subtract =
            control_variate && !bs.delta
                ? closures.lambertian_value(wo, bs.wi, settings_.hemisphere) * (ambient / bs.pdf)
                : Rgb(0.0f);
        const Vec3 wi = frame.to_world(bs.wi);
        // A direction the shading normal allows but the true surface does not: light cannot
        // get there, so the path ends (its incoming radiance is 0, the control variate's part stays).
        const bool below = dot(wi, sp.ng) < 0.0f;
        if ((bs.wi.z < 0.0f) != below || dot(wi, sp.ng) == 0.0f) {
            L = L - beta * cv_subtract;
            break;
        }
        const Rgb beta_at_vertex = beta;
        beta *= bs.weight;
        if (bs.kind == ScatterKind::Transparent) {
            // Pass-through: not a bounce; the MIS pdf and origin of the last real scatter stay.
            if (++transparent_bounce > settings_.transparent_max_bounces) break;
            track.pass_through(hit.t);
        } else {
            track.scatter(hit.t, light_path_rays(bs.kind, bs.delta, track.rays));
            camera_visible_path = false;
            scatter_pdf = bs.delta ? 0.0f : bs.pdf;
            scatter_origin = hit.position;
            scatter_normal = sp.ns;
            receiver_set = hit.links.receiver_light_set;
            float survive = 1.0f;
            if (settings_.rr_mode != RouletteMode::Off && bounces.total() >= settings_.rr_min_depth) {
                // (5.5): survival = throughput, or the closures' albedo (then β stays constant
                // along a Lambertian path, 5.6). A terminated path's continued term is 0, so
                // the control variate's subtraction goes with it.
                survive = std::min(1.0f, settings_.rr_mode == RouletteMode::Throughput
                                             ? beta.max_component()
                                             : closures.albedo_estimate().max_component());
                if (!(survive > 0.0f) ||
                    sampler.get_1d(pixel, bounce_dimension(vertex, kDimRussianRoulette)) >= survive)
                    break;
                beta *= 1.0f / survive;
            }
            L = L - beta_at_vertex * cv_subtract * (1.0f / survive);
            if (bs.delta)
                records.skip();
            else
                records.push(hit.position, wi, beta);
            bounces.scatter(bs.kind);
            // Filter Glossy reads the closures' own pdf, not the guided mixture's (as Cycles).
            const bool unguided = guide.active() && !bs.delta && limits.filter_glossy > 0.0f;
            closure_state.scatter(
                bs.kind, unguided ? closures.eval(wo, bs.wi, settings_.hemisphere).pdf : bs.pdf, bs.delta);
        }
        query.visibility = ray_visibility(bs.kind, query.visibility);
        origin = offset_ray_origin(hit.position, below ? -sp.ng : sp.ng);
        dir = wi;
        t_min = 0.0f;
        t_max = kInfinity;
        if (bs.kind != ScatterKind::Transparent && lights.has_shadow_linking()) {
            const uint32_t left = max_shadow_surfaces - std::min(max_shadow_surfaces, transparent_bounce);
            const ScatteredRay ray{origin,
                                   dir,
                                   catcher.query(query),
                                   catcher.query({query.time, kVisibleShadow}),
                                   track,
                                   receiver_set,
                                   hash_more(pixel.sample_key, vertex),
                                   scatter_pdf,
                                   scatter_origin,
                                   scatter_normal,
                                   left,
                                   bounces,
                                   transparent_bounce};
            uint32_t linked_group = 0;
            const Rgb found_linked =
                clamp_contribution(beta * shadow_linked_emission(scene, ray, rays, &linked_group),
                                   emission_clamp(limits, bounces.total()));
            L += found_linked;
            // Cycles writes the dedicated light as NEE (shade_dedicated_light.h): its emitter's group.
            groups.light_sample(linked_group, found_linked);
            records.add(found_linked);
        }
    }
    data.finish();
    records.flush();
    return {L, std::clamp(1.0f - transparency, 0.0f, 1.0f)};
}

}  // namespace stratum
