// The render settings' table (render/setting_registry.h): one row per setting, in ABI order,
// naming each field it sets. How a value is checked and stored is in
// render/setting_values.cpp.
#include "render/setting_registry.h"

#include <array>
#include <limits>

#include "film/light_groups.h"
#include "film/pixel_filter.h"
#include "guiding/guiding_tree.h"
#include "integrators/estimator_options.h"
#include "lights/light_tree.h"
#include "radiosity/radiosity_settings.h"
#include "sampling/hemisphere.h"
#include "sampling/sampler_registry.h"

namespace stratum {

namespace {

// Limits keep width*height*4 floats and sample indices far from 32-bit overflow.
constexpr double kMaxResolution = 65536;
constexpr double kMaxSamples = 1 << 24;
constexpr double kMaxBounces = 1024;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kFloatMax = std::numeric_limits<float>::max();

std::span<const RegistryEntry> sampler_choices() {
    // The sampler registry's entries carry a factory; the settings list needs their infos.
    static const std::vector<RegistryEntry> infos = [] {
        std::vector<RegistryEntry> out;
        for (const SamplerEntry& e : sampler_registry()) out.push_back(e.info);
        return out;
    }();
    return infos;
}

std::span<const RegistryEntry> integrator_choices() {
    static const std::vector<RegistryEntry> infos = [] {
        std::vector<RegistryEntry> out;
        for (const IntegratorEntry& e : integrator_registry()) out.push_back(e.info);
        return out;
    }();
    return infos;
}

std::span<const RegistryEntry> bvh_choices() {
    static constexpr std::array kLayouts = {
        RegistryEntry{"static", "Static",
                      "A mesh placed once is flattened into the top level: fastest to trace; moving it "
                      "rebuilds its BVH"},
        RegistryEntry{"dynamic", "Dynamic",
                      "Every mesh is an instance: moving an object only recommits the top level (for live "
                      "editing, as Cycles' viewport BVH)"},
    };
    return kLayouts;
}

std::span<const RegistryEntry> adaptive_metric_choices() {
    static constexpr std::array kMetrics = {
        RegistryEntry{"relative", "Relative",
                      "A pixel stops when its error relative to its own brightness is under the threshold, "
                      "as Cycles: noise evens out to the eye, dark pixels take the most samples"},
        RegistryEntry{
            "mse", "Mean Squared Error",
            "Samples go where they lower the image's mean squared error most (a pixel's count grows "
            "with its spread); the threshold is the image's RMS error relative to its mean "
            "brightness"},
    };
    return kMetrics;
}

std::span<const RegistryEntry> pass_choices() {
    // Combined is always there: the list names the others.
    static const std::vector<RegistryEntry> infos = [] {
        std::vector<RegistryEntry> out;
        for (size_t i = 1; i < kPasses.size(); ++i)
            out.push_back({kPasses[i].name, kPasses[i].name, kPasses[i].description});
        return out;
    }();
    return infos;
}

// Accessors of one member, for the table below: .get and .set of a number, a flag (0 or 1),
// an estimator option (by its position among the option's choices) or an enumeration.
#define STRATUM_UINT(member)                                                      \
    .get = [](const RenderSettings& s) { return static_cast<double>(s.member); }, \
    .set = [](RenderSettings& s, double v) { s.member = static_cast<uint32_t>(v); }
#define STRATUM_FLOAT(member)                                                     \
    .get = [](const RenderSettings& s) { return static_cast<double>(s.member); }, \
    .set = [](RenderSettings& s, double v) { s.member = static_cast<float>(v); }
#define STRATUM_BOOL(member)                                             \
    .get = [](const RenderSettings& s) { return s.member ? 1.0 : 0.0; }, \
    .set = [](RenderSettings& s, double v) { s.member = v != 0.0; }
#define STRATUM_OPTION(member, at)                                                           \
    .get = [](const RenderSettings& s) { return static_cast<double>(choice_of(s.member)); }, \
    .set = [](RenderSettings& s, double v) { s.member = at(static_cast<size_t>(v)); }
#define STRATUM_ENUM(member, Enum)                                                \
    .get = [](const RenderSettings& s) { return static_cast<double>(s.member); }, \
    .set = [](RenderSettings& s, double v) { s.member = static_cast<Enum>(static_cast<int>(v)); }

// In ABI order: a host lists the settings by position, so a new setting goes at the end.
const SettingSpec kSettings[] = {
    {.info = {"width", "Width", "Frame width in pixels"},
     .kind = SettingKind::Int,
     .minimum = 1,
     .maximum = kMaxResolution,
     .unit = "pixels",
     STRATUM_UINT(width)},
    {.info = {"height", "Height", "Frame height in pixels"},
     .kind = SettingKind::Int,
     .minimum = 1,
     .maximum = kMaxResolution,
     .unit = "pixels",
     STRATUM_UINT(height)},
    {.info = {"samples", "Samples", "Number of samples per pixel"},
     .kind = SettingKind::Int,
     .minimum = 1,
     .maximum = kMaxSamples,
     STRATUM_UINT(samples)},
    {.info = {"use_adaptive_sampling", "Adaptive Sampling",
              "1: a pixel stops taking samples when its estimated error falls under the noise "
              "threshold, checked at power-of-two sample counts (Cycles' adaptive sampling)"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = 1,
     STRATUM_BOOL(adaptive.enabled)},
    {.info = {"adaptive_threshold", "Noise Threshold",
              "Noise to fall under to stop sampling: a pixel's relative error, as Cycles' "
              "adaptive_threshold, or with Noise Metric mse the image's RMS error relative to its mean "
              "(0 = automatic: max(0.001, 1/samples))"},
     .kind = SettingKind::Float,
     .minimum = 0.0,
     .maximum = 1.0,
     STRATUM_FLOAT(adaptive.threshold)},
    {.info = {"adaptive_metric", "Noise Metric",
              "What adaptive sampling's noise threshold measures: each pixel's relative error (Cycles') or "
              "the image's mean squared error at equal time"},
     .kind = SettingKind::Choice,
     .choices = &adaptive_metric_choices,
     STRATUM_ENUM(adaptive.metric, AdaptiveMetric)},
    {.info = {"adaptive_min_samples", "Min Samples",
              "Samples every pixel takes before adaptive sampling may stop it, rounded up to a power "
              "of two (0 = automatic, as Cycles: 16/threshold^0.3)"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxSamples,
     STRATUM_UINT(adaptive.min_samples)},
    {.info = {"max_bounces", "Max Bounces",
              "Total maximum number of bounces (0 = direct lighting only), as Cycles' max_bounces"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxBounces,
     STRATUM_UINT(estimator.max_bounces)},
    {.info = {"seed", "Seed", "Seed of the sampler's scrambling and randomization"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = 0xffffffff,
     STRATUM_UINT(seed)},
    {.info = {"sample_offset", "Sample Offset",
              "First sample index this render takes of the Samples sequence (a frame split over machines)"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxSamples - 1,
     STRATUM_UINT(sample_offset)},
    {.info = {"sample_count", "Sample Count",
              "Sample indices this render takes from Sample Offset (0 = up to Samples)"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxSamples,
     STRATUM_UINT(sample_count)},
    {.info = {"threads", "Threads", "Number of render threads (0 = all cores)"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = 1024,
     STRATUM_UINT(threads)},
    {.info = {"crop_x", "Border X", "Left edge of the border region, pixels from the frame's left"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxResolution - 1,
     .unit = "pixels",
     STRATUM_UINT(crop_x)},
    {.info = {"crop_y", "Border Y", "Bottom edge of the border region, pixels from the frame's bottom"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxResolution - 1,
     .unit = "pixels",
     STRATUM_UINT(crop_y)},
    {.info = {"crop_width", "Border Width", "Width of the border region in pixels (0 = the whole frame)"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxResolution,
     .unit = "pixels",
     STRATUM_UINT(crop_width)},
    {.info = {"crop_height", "Border Height", "Height of the border region in pixels"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxResolution,
     .unit = "pixels",
     STRATUM_UINT(crop_height)},
    {.info = {"film_transparent", "Transparent Film",
              "1: the background seen directly has alpha 0 (Cycles' Film > Transparent)"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = 1,
     STRATUM_BOOL(estimator.film_transparent)},
    {.info = {"lightgroups", "Light Groups",
              "Light group passes the render holds (Cycles' view-layer light groups): group k of lights, "
              "instances and the world goes to pass k (stratum_renderer_read_lightgroup)"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxLightGroups,
     STRATUM_UINT(lightgroups)},
    {.info = {"lightgroup_split_emission", "Light Groups After Catcher Split",
              "1: emission met after a camera path split at a shadow catcher still reaches the light groups "
              "(Cycles 3.x); 0: it does not (Cycles 4.x and later)"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = 1,
     STRATUM_BOOL(estimator.lightgroup_split_emission)},
    {.info = {"rr_min_depth", "Roulette Min Depth", "First bounce at which Russian roulette may end a path"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxBounces,
     STRATUM_UINT(estimator.rr_min_depth)},
    {.info = {"filter_width", "Filter Width", "Pixel filter width in pixels, as Cycles' filter_width"},
     .kind = SettingKind::Float,
     .minimum = 0.01,
     .maximum = 100.0,
     .unit = "pixels",
     STRATUM_FLOAT(filter_width)},
    {.info = {"ao_distance", "AO Distance",
              "Ambient occlusion: a direction is occluded when an obstacle lies within this distance "
              "(inf = unlimited)"},
     .kind = SettingKind::Float,
     .minimum = 0.0,
     .maximum = kInf,
     .open_minimum = true,
     .unit = "scene units",
     STRATUM_FLOAT(estimator.ao_distance)},
    {.info = {"control_variate", "Control Variate",
              "Ambient radiance L_a of the control variate (textbook 5.17); 0 = off"},
     .kind = SettingKind::Float,
     .minimum = 0.0,
     .maximum = kFloatMax,
     STRATUM_FLOAT(estimator.control_variate)},
    {.info = {"sampler", "Sampler", "Sampling strategy"},
     .kind = SettingKind::Choice,
     .choices = &sampler_choices,
     .get =
         [](const RenderSettings& s) { return static_cast<double>(s.sampler - sampler_registry().data()); },
     .set = [](RenderSettings& s, double v) { s.sampler = &sampler_registry()[static_cast<size_t>(v)]; }},
    {.info = {"integrator", "Integrator", "Light transport algorithm"},
     .kind = SettingKind::Choice,
     .choices = &integrator_choices,
     .get =
         [](const RenderSettings& s) {
             return static_cast<double>(s.integrator - integrator_registry().data());
         },
     .set = [](RenderSettings& s,
               double v) { s.integrator = &integrator_registry()[static_cast<size_t>(v)]; }},
    {.info = {"hemisphere", "Hemisphere", "Distribution of diffuse and ambient-occlusion directions"},
     .kind = SettingKind::Choice,
     .choices = &hemisphere_registry,
     STRATUM_ENUM(estimator.hemisphere, HemisphereDistribution)},
    {.info = {"filter_type", "Filter Type", "Pixel reconstruction filter"},
     .kind = SettingKind::Choice,
     .choices = &filter_registry,
     STRATUM_ENUM(filter_type, FilterType)},
    {.info = {"light_sampling", "Light Sampling", "How the path tracer finds emission"},
     .kind = SettingKind::Choice,
     .choices = &light_sampling_choices,
     STRATUM_OPTION(estimator.light_sampling, light_sampling_at)},
    {.info = {"mis_heuristic", "MIS Heuristic",
              "Weights of light and BSDF samples under multiple importance sampling"},
     .kind = SettingKind::Choice,
     .choices = &mis_heuristic_choices,
     STRATUM_OPTION(estimator.mis_heuristic, mis_heuristic_at)},
    {.info = {"light_selection", "Light Selection", "Probability of choosing each light for a light sample"},
     .kind = SettingKind::Choice,
     .choices = &light_selection_choices,
     STRATUM_OPTION(estimator.light_selection, light_selection_at)},
    {.info = {"light_tree_splits", "Light Tree Splits",
              "Light tree only: most light samples per shading point, one per node of the tree's "
              "adaptive cut (1: one light, no splitting)"},
     .kind = SettingKind::Int,
     .minimum = 1,
     .maximum = LightTree::kMaxCut,
     STRATUM_UINT(estimator.light_tree_splits)},
    {.info = {"triangle_sampling", "Triangle Sampling",
              "How a light sample takes a point on an emissive triangle"},
     .kind = SettingKind::Choice,
     .choices = &triangle_sampling_choices,
     STRATUM_OPTION(estimator.triangle_sampling, triangle_sampling_at)},
    {.info = {"rr_mode", "Russian Roulette", "How a path's survival probability is chosen"},
     .kind = SettingKind::Choice,
     .choices = &rr_mode_choices,
     STRATUM_OPTION(estimator.rr_mode, rr_mode_at)},
    {.info = {"bvh", "BVH", "How the ray-tracing hierarchy is laid out: for rendering or for live editing"},
     .kind = SettingKind::Choice,
     .choices = &bvh_choices,
     STRATUM_ENUM(bvh, BvhLayout)},
    {.info = {"mist_start", "Mist Start", "Mist pass: distance from the camera where the mist begins"},
     .kind = SettingKind::Float,
     .minimum = 0.0,
     .maximum = kFloatMax,
     .unit = "scene units",
     STRATUM_FLOAT(estimator.mist.start)},
    {.info = {"mist_depth", "Mist Depth", "Mist pass: distance over which the mist goes from 0 to 1"},
     .kind = SettingKind::Float,
     .minimum = 0.0,
     .maximum = kFloatMax,
     .unit = "scene units",
     STRATUM_FLOAT(estimator.mist.depth)},
    {.info = {"mist_falloff", "Mist Falloff",
              "Mist pass: exponent of the mist's rise over its depth (Blender's quadratic 2, linear 1, "
              "inverse quadratic 0.5)"},
     .kind = SettingKind::Float,
     .minimum = 0.0,
     .maximum = 16.0,
     STRATUM_FLOAT(estimator.mist.falloff)},
    {.info = {"passes", "Passes", "Passes the render holds besides Combined (comma-separated)"},
     .kind = SettingKind::List,
     .choices = &pass_choices,
     .get_list =
         [](const RenderSettings& s) {
             std::vector<size_t> out;
             for (const Pass p : s.passes) out.push_back(static_cast<size_t>(p) - 1);
             return out;
         },
     .set_list =
         [](RenderSettings& s, const std::vector<size_t>& choices) {
             s.passes.clear();
             for (const size_t c : choices) s.passes.push_back(static_cast<Pass>(c + 1));
         }},
    {.info = {"radiosity_patch_size", "Patch Size",
              "Radiosity: longest edge of a patch; triangles are split until theirs are shorter (0 = "
              "automatic: the scene's bounding-box diagonal / 32)"},
     .kind = SettingKind::Float,
     .minimum = 0.0,
     .maximum = kFloatMax,
     .unit = "scene units",
     STRATUM_FLOAT(estimator.radiosity.patch_size)},
    {.info = {"radiosity_solver", "Solver", "Radiosity: how the linear system of the patches is solved"},
     .kind = SettingKind::Choice,
     .choices = &radiosity_solver_choices,
     STRATUM_ENUM(estimator.radiosity.solver, RadiositySolver)},
    {.info = {"radiosity_tolerance", "Tolerance",
              "Radiosity: the solve stops when the textbook's error estimate Delta E is at most this "
              "share of the scene's mean radiance"},
     .kind = SettingKind::Float,
     .minimum = 0.0,
     .maximum = 1.0,
     .open_minimum = true,
     STRATUM_FLOAT(estimator.radiosity.tolerance)},
    {.info = {"radiosity_rays", "Form Factor Rays",
              "Radiosity: rays cast from each patch to estimate its form factors (Nusselt analogy)"},
     .kind = SettingKind::Int,
     .minimum = 1,
     .maximum = kMaxRadiosityRays,
     STRATUM_UINT(estimator.radiosity.rays)},
    {.info = {"use_guiding", "Path Guiding",
              "Path tracing: 1 = draw part of the scattered directions from a 5-D tree of the incident "
              "radiance learned during the first samples (textbook 5.19; Cycles' use_guiding)"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = 1,
     STRATUM_BOOL(estimator.use_guiding)},
    {.info = {"guiding_training_samples", "Training Samples",
              "Path guiding: samples per pixel during which the tree learns; then it stays as it is"},
     .kind = SettingKind::Int,
     .minimum = 1,
     .maximum = kMaxSamples,
     STRATUM_UINT(estimator.guiding_training_samples)},
    {.info = {"guiding_bsdf_fraction", "BSDF Fraction",
              "Path guiding: share of directions drawn by the material's own sampling, the rest by the "
              "tree (at least 0.05: only the material draws mirror, glass and transparent directions)"},
     .kind = SettingKind::Float,
     .minimum = 0.05,
     .maximum = 1.0,
     STRATUM_FLOAT(estimator.guiding_bsdf_fraction)},
    {.info = {"guiding_split", "Split",
              "Path guiding: how a node of the tree splits once it holds enough records"},
     .kind = SettingKind::Choice,
     .choices = &guiding_split_choices,
     STRATUM_ENUM(estimator.guiding_split, GuidingSplit)},
    {.info = {"diffuse_bounces", "Diffuse",
              "Maximum number of diffuse reflection bounces, bounded by Max Bounces, as Cycles' "
              "diffuse_bounces"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxBounces,
     STRATUM_UINT(estimator.light_paths.diffuse)},
    {.info = {"glossy_bounces", "Glossy",
              "Maximum number of glossy and mirror reflection bounces, bounded by Max Bounces, as "
              "Cycles' glossy_bounces"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxBounces,
     STRATUM_UINT(estimator.light_paths.glossy)},
    {.info = {"transmission_bounces", "Transmission",
              "Maximum number of refraction bounces, bounded by Max Bounces, as Cycles' "
              "transmission_bounces"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxBounces,
     STRATUM_UINT(estimator.light_paths.transmission)},
    {.info = {"transparent_max_bounces", "Transparent",
              "Maximum number of transparent surfaces a path (and each shadow ray) passes through; "
              "they are not bounces. As Cycles' transparent_max_bounces"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = kMaxBounces,
     STRATUM_UINT(estimator.transparent_max_bounces)},
    {.info = {"clamp_direct", "Direct Light",
              "Clamps each direct light contribution so that the mean of its channels is at most this "
              "(0 = off). Biased: removes fireflies by darkening. As Cycles' sample_clamp_direct"},
     .kind = SettingKind::Float,
     .minimum = 0.0,
     .maximum = 1e8,
     STRATUM_FLOAT(estimator.light_paths.clamp_direct)},
    {.info = {"clamp_indirect", "Indirect Light",
              "Clamps each indirect light contribution so that the mean of its channels is at most "
              "this (0 = off). Biased: removes fireflies by darkening. As Cycles' sample_clamp_indirect"},
     .kind = SettingKind::Float,
     .minimum = 0.0,
     .maximum = 1e8,
     STRATUM_FLOAT(estimator.light_paths.clamp_indirect)},
    {.info = {"filter_glossy", "Filter Glossy",
              "Widens glossy lobes met after blurry bounces: each microfacet lobe's alpha becomes at least "
              "0.5 sqrt(1 - p/this), p the path's least scattering pdf so far (0 = off). Biased: removes "
              "fireflies of caustics by blurring them. As Cycles' blur_glossy"},
     .kind = SettingKind::Float,
     .minimum = 0.0,
     .maximum = 10.0,
     STRATUM_FLOAT(estimator.light_paths.filter_glossy)},
    {.info = {"caustics_reflective", "Reflective Caustics",
              "Path tracing: 1 = glossy reflection after a diffuse bounce; 0 drops those lobes (biased: "
              "no light through mirrors onto diffuse surfaces). As Cycles' caustics_reflective"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = 1,
     STRATUM_BOOL(estimator.light_paths.caustics_reflective)},
    {.info = {"caustics_refractive", "Refractive Caustics",
              "Path tracing: 1 = glossy refraction after a diffuse bounce; 0 drops those lobes (biased: "
              "no light through glass onto diffuse surfaces). As Cycles' caustics_refractive"},
     .kind = SettingKind::Int,
     .minimum = 0,
     .maximum = 1,
     STRATUM_BOOL(estimator.light_paths.caustics_refractive)},
};

#undef STRATUM_UINT
#undef STRATUM_FLOAT
#undef STRATUM_BOOL
#undef STRATUM_OPTION
#undef STRATUM_ENUM

}  // namespace

std::span<const SettingSpec> setting_registry() { return kSettings; }

const SettingSpec* find_setting(std::string_view name) {
    for (const SettingSpec& spec : kSettings)
        if (name == spec.info.name) return &spec;
    return nullptr;
}

}  // namespace stratum
