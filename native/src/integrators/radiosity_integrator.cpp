#include "integrators/radiosity_integrator.h"

#include <array>
#include <cmath>
#include <string>

#include "bsdf/bsdf.h"
#include "integrators/camera_path_passes.h"
#include "integrators/light_path_limits.h"
#include "integrators/light_path_readers.h"
#include "integrators/linking_notice.h"
#include "integrators/ray_offset.h"
#include "integrators/shading_point.h"
#include "sampling/dimensions.h"
#include "scene/visibility.h"

namespace stratum {

namespace {

// The registry name of a closure model ("principled_v2"), for the notice.
std::string model_name(int32_t model) {
    const ClosureModels& models = closure_models();
    for (int32_t k = 0; k < models.count(); ++k) {
        const auto* e = models.entry(k);
        if (e->value == model) return e->name;
    }
    return std::to_string(model);
}

}  // namespace

void RadiosityIntegrator::prepare(const RenderScene& scene, const std::atomic<bool>& cancel) {
    solution_ = std::make_shared<const RadiositySolution>(scene, settings_.radiosity, &cancel);
}

bool RadiosityIntegrator::adopt(const Integrator& previous) {
    const auto* other = dynamic_cast<const RadiosityIntegrator*>(&previous);
    if (!other || !other->solution_ || !(other->settings_.radiosity == settings_.radiosity)) return false;
    solution_ = other->solution_;
    return true;
}

std::vector<std::string> RadiosityIntegrator::notices(const Scene& scene) const {
    std::vector<bool> used(scene.materials.size(), false);
    for (const Instance& inst : scene.instances)
        for (const uint32_t m : scene.meshes[inst.mesh_id].material_ids) used[m] = true;
    std::string listed;
    for (uint32_t m = 0; m < scene.materials.size(); ++m) {
        if (!used[m] || !radiosity_approximates(scene.materials[m])) continue;
        std::string models;
        for (const WeightedClosure& c : scene.materials[m].closures)
            models += (models.empty() ? "" : ", ") + model_name(c.params.model);
        listed +=
            (listed.empty() ? "" : "; ") + std::string("material ") + std::to_string(m) + " (" + models + ")";
    }
    std::vector<std::string> out;
    if (!listed.empty())
        out.push_back(
            "radiosity treats every surface as diffuse: " + listed +
            " rendered by its diffuse albedo alone, without its glossy, glass or transparent closures");
    // The solve carries every diffuse interreflection; a sample's light is not split into
    // contributions that could be counted or clamped as the path tracer's are, and it has no
    // glossy lobe that Filter Glossy or the caustics switches could change.
    const LightPathLimits& l = settings_.light_paths;
    const LightPathLimits unlimited;
    if (l.diffuse != unlimited.diffuse || l.clamp_direct > 0.0f || l.clamp_indirect > 0.0f ||
        l.filter_glossy > 0.0f || !l.caustics_reflective || !l.caustics_refractive)
        out.emplace_back(
            "radiosity solves every diffuse interreflection: diffuse_bounces, clamp_direct, clamp_indirect, "
            "filter_glossy and the caustics switches do not apply (choose the path tracer to have them)");
    if (const std::string lp = light_path_notice(scene, "radiosity"); !lp.empty()) out.push_back(lp);
    if (const auto linking = unsupported_linking_notice(scene, "radiosity")) out.push_back(*linking);
    return out;
}

RadianceSample RadiosityIntegrator::estimate(const RenderScene& scene, const Sampler& sampler,
                                             const PixelSample& pixel, const CameraRay& camera_ray,
                                             PassValues& passes, uint64_t& rays) const {
    const LightSet& lights = scene.lights();
    CameraPathPasses data(passes, settings_.mist);
    SurfaceHit hit;
    ++rays;
    const bool found = scene.intersect(camera_ray.origin, camera_ray.direction, camera_ray.t_min,
                                       camera_ray.t_max, &hit, {camera_ray.time, kVisibleCamera});
    Rgb L = lights.lamp_radiance(camera_ray.origin, camera_ray.direction, found ? hit.t : camera_ray.t_max,
                                 kVisibleCamera);
    data.emitted(L, true);
    if (!found) {
        const bool transparent = settings_.film_transparent;
        const Rgb background = scene.background(camera_ray.direction);
        data.miss(transparent ? Rgb(0.0f) : background, true);
        data.finish();
        if (transparent) return {L, 0.0f};
        return {L + background};
    }
    const Vec3 wo = -camera_ray.direction;
    const ShadingPoint sp = build_closures(scene, hit, wo, RayTrack::camera(camera_ray).at(hit.t));
    data.surface(hit, sp.ns, wo, sp.closures, Rgb(1.0f), true);
    if (hit.holdout) {
        data.finish();
        return {Rgb(0.0f), settings_.film_transparent ? 0.0f : 1.0f};
    }
    const Rgb emission = sp.closures.emission();
    L += emission;
    const Frame frame = Frame::from_normal(sp.ns);
    const Rgb albedo = sp.closures.colors(frame.to_local(wo)).diffuse;
    data.finish();
    if (albedo.is_black() || !solution_) return {L};

    Rgb irradiance(0.0f);
    const Vec3 origin = offset_ray_origin(hit.position, sp.ng);
    // Direct light: the path tracer's next-event estimation at its first vertex (one light
    // sample, or one per cut node of the light tree with splitting).
    std::array<LightSample, LightTree::kMaxCut> light_samples;
    const uint32_t light_sample_count = lights.sample_cut(
        hit.position, sp.ns, sampler.get_1d(pixel, bounce_dimension(0, kDimLightChoice)),
        sampler.get_2d(pixel, bounce_dimension(0, kDimLightPoint)), light_samples.data(),
        settings_.light_selection, settings_.triangle_sampling, settings_.light_tree_splits);
    for (uint32_t k = 0; k < light_sample_count; ++k) {
        const LightSample& ls = light_samples[k];
        const float cosine = dot(ls.wi, sp.ns);
        if (!(ls.pdf > 0.0f) || !(ls.visibility & kVisibleDiffuse) || !(cosine > 0.0f) ||
            !(dot(ls.wi, sp.ng) > 0.0f))
            continue;
        if (ls.visibility & kVisibleShadow) {
            const ShadowRay shadow = std::isinf(ls.distance)
                                         ? ShadowRay{ls.wi, kInfinity}
                                         : shadow_ray_to(origin, hit.position + ls.wi * ls.distance);
            ++rays;
            if (scene.occluded(origin, shadow.direction, 0.0f, shadow.t_max,
                               {camera_ray.time, kVisibleShadow}))
                continue;
        }
        irradiance += ls.radiance * (cosine / ls.pdf);
    }
    // Indirect light: one gather ray reads the patch solution.
    const Vec3 dir = frame.to_world(
        sample_cosine_hemisphere(sampler.get_2d(pixel, bounce_dimension(0, kDimBsdfDirection))));
    if (dot(dir, sp.ng) > 0.0f) {
        RayHit gathered;
        ++rays;
        if (scene.intersect_triangle(origin, dir, 0.0f, kInfinity, &gathered,
                                     {camera_ray.time, kVisibleDiffuse})) {
            const uint32_t patch = solution_->patches().patch_of(gathered, dir);
            if (patch != kNoPatch) irradiance += solution_->reflected(patch);
        } else if (!lights.environment()) {
            irradiance += scene.background(dir) * kPi;
        }
    }
    return {L + albedo * irradiance * kInvPi};
}

}  // namespace stratum
