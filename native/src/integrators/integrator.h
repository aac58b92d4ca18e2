// The integrator interface and registry: an integrator estimates the radiance arriving along
// one camera ray, drawing every random number from the sampler at the named dimensions.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "film/film.h"
#include "integrators/camera_path_passes.h"
#include "integrators/estimator_options.h"
#include "integrators/guided_direction.h"
#include "integrators/light_path_limits.h"
#include "radiosity/radiosity_settings.h"
#include "radiosity/radiosity_solution.h"
#include "render_scene/render_scene.h"
#include "sampling/hemisphere.h"
#include "sampling/sampler.h"
#include "sampling/sampler_registry.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace stratum {

struct IntegratorSettings {
    // Cycles' max_bounces: vertices 0..max_bounces are shaded (light sampling and scattering);
    // the ray scattered at the last one still collects the emission it hits.
    uint32_t max_bounces = 12;
    // `ao`: the distribution AO directions are drawn from, and the distance within which an
    // obstacle occludes (scene units, > 0; infinity = unlimited).
    HemisphereDistribution hemisphere = HemisphereDistribution::Cosine;
    float ao_distance = 1.0f;
    // Cycles' transparent_max_bounces (default 8 in 3.4 and 5.0): pass-throughs of Transparent
    // closures (and transparent-shadow surfaces) allowed per path; they are not bounces.
    uint32_t transparent_max_bounces = 8;
    // Cycles' per-kind bounce limits and clamping (integrators/light_path_limits.h): unlimited
    // and off by default, so that the estimators stay unbiased.
    LightPathLimits light_paths;
    // Light groups (integrators/light_group_writer.h): whether emission met after a shadow
    // catcher split still reaches them, as in Cycles 3.x (4.x+ writes none).
    bool lightgroup_split_emission = false;
    // Cycles' Film > Transparent: background seen directly (also through transparent closures)
    // gives alpha 0 instead of its radiance, and holdouts turn into alpha.
    bool film_transparent = false;
    // The estimator ladder (integrators/estimator_options.h; textbook §4–§6).
    LightSampling light_sampling = LightSampling::Mis;
    MisHeuristic mis_heuristic = MisHeuristic::Power;
    LightSelection light_selection = LightSelection::Auto;
    // The light tree's adaptive splitting: at most this many cut nodes, each one light sample,
    // per NEE vertex (lights/light_tree.h); 1 = one light per vertex, no splitting. 8: the least
    // MSE at equal time of 1, 4, 8 and 16 on the many-lights hall (docs/study.md).
    uint32_t light_tree_splits = 8;
    TriangleSampling triangle_sampling = TriangleSampling::SolidAngle;
    RouletteMode rr_mode = RouletteMode::Throughput;
    // Roulette starts at this bounce (0 = at the first vertex).
    uint32_t rr_min_depth = 3;
    // The control variate's ambient radiance L_a (textbook 5.17–5.18); 0 = off.
    float control_variate = 0.0f;
    // The Mist pass's start, depth and falloff (Blender's world mist settings).
    MistSettings mist;
    // `radiosity`: patch size, solver, tolerance, form-factor rays (radiosity/radiosity_settings.h).
    RadiositySettings radiosity;
    // Path guiding (`path` only; integrators/guided_direction.h, guiding/guiding_tree.h): the
    // tree learns from sample indices below guiding_training_samples, then stays as it is; the
    // closures draw a share guiding_bsdf_fraction of the directions, the tree the rest.
    // 32 training samples: the passes up to 32 (1, 1, 2, 4, 8, 16 samples) are where the image is
    // noisiest anyway, and the later, larger passes (32, 64 per pass) all use a trained tree;
    // learning for 128 of 128 samples in the room lit through a door lowered the variance by 5%
    // for 3.7× the nodes. Fixed after training, the tree costs no counters and no records.
    bool use_guiding = false;
    uint32_t guiding_training_samples = 32;
    float guiding_bsdf_fraction = 0.5f;
    GuidingSplit guiding_split = GuidingSplit::Binary;
};

// One camera ray's estimate: the radiance, and the alpha the film stores (1 = covered; a
// holdout or, with a transparent film, the background gives 0).
struct RadianceSample {
    Rgb radiance;
    float alpha = 1.0f;
};

class Integrator {
public:
    virtual ~Integrator() = default;
    // Called once per render, before any sample, with the scene it renders; a long preparation
    // stops by throwing RenderScene::BuildCancelled once `cancel` (the render's) is set.
    virtual void prepare(const RenderScene& scene, const std::atomic<bool>& cancel) {
        (void)scene;
        (void)cancel;
    }
    // One camera ray's estimate; the integrator writes the extra passes the film holds into
    // `passes`. `rays` is incremented by the number of rays traced.
    virtual RadianceSample estimate(const RenderScene& scene, const Sampler& sampler,
                                    const PixelSample& pixel, const CameraRay& ray, PassValues& passes,
                                    uint64_t& rays) const = 0;
    // The estimate without extra passes.
    RadianceSample radiance(const RenderScene& scene, const Sampler& sampler, const PixelSample& pixel,
                            const CameraRay& ray, uint64_t& rays) const {
        PassValues none;
        return estimate(scene, sampler, pixel, ray, none, rays);
    }
    // Light paths traced per sample index for a frame of this size (0: the integrator traces
    // none). The renderer traces path k of sample index i as PixelSample{k mod W, k / W, i}
    // and adds the splats of each chunk of paths to the film in a fixed order.
    virtual uint64_t light_paths_per_sample(uint32_t frame_width, uint32_t frame_height) const {
        (void)frame_width;
        (void)frame_height;
        return 0;
    }
    // Traces one light path and appends its splats (Film::splat) to `splats`.
    virtual void trace_light_path(const RenderScene& scene, const Sampler& sampler, const Camera& camera,
                                  const Film& film, const PixelSample& path, std::vector<Splat>& splats,
                                  uint64_t& rays) const {
        (void)scene, (void)sampler, (void)camera, (void)film, (void)path, (void)splats, (void)rays;
    }
    // Whether camera paths split at shadow catchers (integrators/shadow_catcher.h) and write the
    // Shadow Catcher pass's sums; an integrator that does not renders catchers as plain objects
    // (the renderer says so: unsplit_catcher_notices).
    virtual bool splits_shadow_catchers() const { return false; }
    // Whether it writes the light groups' passes (film/light_groups.h); an integrator that does
    // not leaves them black (the renderer says so).
    virtual bool writes_light_groups() const { return false; }
    // What this estimator cannot render in `scene` and why (e.g. BSDF sampling alone never
    // finds a point light): one sentence each, shown to the user; the render still runs.
    virtual std::vector<std::string> notices(const Scene& scene) const {
        (void)scene;
        return {};
    }
    // Takes over what `previous` (the integrator of the same renderer's last render, prepared
    // for this render scene, which has not changed since but for the camera) computed in
    // prepare(), when that stands for what this one's prepare() would compute; then the
    // renderer does not call prepare(). A camera move in the viewport so keeps a radiosity solve.
    virtual bool adopt(const Integrator& previous) {
        (void)previous;
        return false;
    }
    // After each complete pass of camera samples [begin, end) (not a cancelled one), in the render
    // thread with no sample running: an integrator that learns from its samples (path guiding)
    // folds what they taught it in here, so every pass reads a fixed state.
    virtual void end_pass(uint32_t begin, uint32_t end) {
        (void)begin;
        (void)end;
    }
    // The path-guiding tree's size and training so far, for the render's progress; null when the
    // integrator does not guide.
    virtual const GuidingReport* guiding_report() const { return nullptr; }
    // What prepare() computed for the radiosity method (patches, memory, time), for the
    // render's progress; null for the other integrators.
    virtual const RadiosityReport* radiosity_report() const { return nullptr; }
};

struct IntegratorEntry {
    RegistryEntry info;
    std::unique_ptr<Integrator> (*create)(const IntegratorSettings&);
};

std::span<const IntegratorEntry> integrator_registry();
const IntegratorEntry* find_integrator(std::string_view name);

}  // namespace stratum
