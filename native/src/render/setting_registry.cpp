#include "render/setting_registry.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

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

// Accessors of one member, for the table below.
#define STRATUM_UINT(member)                                               \
    [](const RenderSettings& s) { return static_cast<double>(s.member); }, \
        [](RenderSettings& s, double v) { s.member = static_cast<uint32_t>(v); }
#define STRATUM_FLOAT(member)                                              \
    [](const RenderSettings& s) { return static_cast<double>(s.member); }, \
        [](RenderSettings& s, double v) { s.member = static_cast<float>(v); }
#define STRATUM_OPTION(member, at)                                                    \
    [](const RenderSettings& s) { return static_cast<double>(choice_of(s.member)); }, \
        [](RenderSettings& s, double v) { s.member = at(static_cast<size_t>(v)); }
#define STRATUM_ENUM(member, Enum)                                         \
    [](const RenderSettings& s) { return static_cast<double>(s.member); }, \
        [](RenderSettings& s, double v) { s.member = static_cast<Enum>(static_cast<int>(v)); }

const std::array kSettings = {
    SettingSpec{{"width", "Width", "Frame width in pixels"},
                SettingKind::Int,
                1,
                kMaxResolution,
                false,
                "pixels",
                nullptr,
                STRATUM_UINT(width)},
    SettingSpec{{"height", "Height", "Frame height in pixels"},
                SettingKind::Int,
                1,
                kMaxResolution,
                false,
                "pixels",
                nullptr,
                STRATUM_UINT(height)},
    SettingSpec{{"samples", "Samples", "Number of samples per pixel"},
                SettingKind::Int,
                1,
                kMaxSamples,
                false,
                "",
                nullptr,
                STRATUM_UINT(samples)},
    SettingSpec{{"use_adaptive_sampling", "Adaptive Sampling",
                 "1: a pixel stops taking samples when its estimated error falls under the noise "
                 "threshold, checked at power-of-two sample counts (Cycles' adaptive sampling)"},
                SettingKind::Int,
                0,
                1,
                false,
                "",
                nullptr,
                [](const RenderSettings& s) { return s.adaptive.enabled ? 1.0 : 0.0; },
                [](RenderSettings& s, double v) { s.adaptive.enabled = v != 0.0; }},
    SettingSpec{{"adaptive_threshold", "Noise Threshold",
                 "Noise to fall under to stop sampling: a pixel's relative error, as Cycles' "
                 "adaptive_threshold, or with Noise Metric mse the image's RMS error relative to its mean "
                 "(0 = automatic: max(0.001, 1/samples))"},
                SettingKind::Float,
                0.0,
                1.0,
                false,
                "",
                nullptr,
                STRATUM_FLOAT(adaptive.threshold)},
    SettingSpec{
        {"adaptive_metric", "Noise Metric",
         "What adaptive sampling's noise threshold measures: each pixel's relative error (Cycles') or "
         "the image's mean squared error at equal time"},
        SettingKind::Choice,
        0,
        0,
        false,
        "",
        &adaptive_metric_choices,
        STRATUM_ENUM(adaptive.metric, AdaptiveMetric)},
    SettingSpec{{"adaptive_min_samples", "Min Samples",
                 "Samples every pixel takes before adaptive sampling may stop it, rounded up to a power "
                 "of two (0 = automatic, as Cycles: 16/threshold^0.3)"},
                SettingKind::Int,
                0,
                kMaxSamples,
                false,
                "",
                nullptr,
                STRATUM_UINT(adaptive.min_samples)},
    SettingSpec{{"max_bounces", "Max Bounces",
                 "Total maximum number of bounces (0 = direct lighting only), as Cycles' max_bounces"},
                SettingKind::Int,
                0,
                kMaxBounces,
                false,
                "",
                nullptr,
                STRATUM_UINT(estimator.max_bounces)},
    SettingSpec{{"seed", "Seed", "Seed of the sampler's scrambling and randomization"},
                SettingKind::Int,
                0,
                0xffffffff,
                false,
                "",
                nullptr,
                STRATUM_UINT(seed)},
    SettingSpec{
        {"sample_offset", "Sample Offset",
         "First sample index this render takes of the Samples sequence (a frame split over machines)"},
        SettingKind::Int,
        0,
        kMaxSamples - 1,
        false,
        "",
        nullptr,
        STRATUM_UINT(sample_offset)},
    SettingSpec{{"sample_count", "Sample Count",
                 "Sample indices this render takes from Sample Offset (0 = up to Samples)"},
                SettingKind::Int,
                0,
                kMaxSamples,
                false,
                "",
                nullptr,
                STRATUM_UINT(sample_count)},
    SettingSpec{{"threads", "Threads", "Number of render threads (0 = all cores)"},
                SettingKind::Int,
                0,
                1024,
                false,
                "",
                nullptr,
                STRATUM_UINT(threads)},
    SettingSpec{{"crop_x", "Border X", "Left edge of the border region, pixels from the frame's left"},
                SettingKind::Int,
                0,
                kMaxResolution - 1,
                false,
                "pixels",
                nullptr,
                STRATUM_UINT(crop_x)},
    SettingSpec{{"crop_y", "Border Y", "Bottom edge of the border region, pixels from the frame's bottom"},
                SettingKind::Int,
                0,
                kMaxResolution - 1,
                false,
                "pixels",
                nullptr,
                STRATUM_UINT(crop_y)},
    SettingSpec{{"crop_width", "Border Width", "Width of the border region in pixels (0 = the whole frame)"},
                SettingKind::Int,
                0,
                kMaxResolution,
                false,
                "pixels",
                nullptr,
                STRATUM_UINT(crop_width)},
    SettingSpec{{"crop_height", "Border Height", "Height of the border region in pixels"},
                SettingKind::Int,
                0,
                kMaxResolution,
                false,
                "pixels",
                nullptr,
                STRATUM_UINT(crop_height)},
    SettingSpec{{"film_transparent", "Transparent Film",
                 "1: the background seen directly has alpha 0 (Cycles' Film > Transparent)"},
                SettingKind::Int,
                0,
                1,
                false,
                "",
                nullptr,
                [](const RenderSettings& s) { return s.estimator.film_transparent ? 1.0 : 0.0; },
                [](RenderSettings& s, double v) { s.estimator.film_transparent = v != 0.0; }},
    SettingSpec{
        {"rr_min_depth", "Roulette Min Depth", "First bounce at which Russian roulette may end a path"},
        SettingKind::Int,
        0,
        kMaxBounces,
        false,
        "",
        nullptr,
        STRATUM_UINT(estimator.rr_min_depth)},
    SettingSpec{{"filter_width", "Filter Width", "Pixel filter width in pixels, as Cycles' filter_width"},
                SettingKind::Float,
                0.01,
                100.0,
                false,
                "pixels",
                nullptr,
                STRATUM_FLOAT(filter_width)},
    SettingSpec{{"ao_distance", "AO Distance",
                 "Ambient occlusion: a direction is occluded when an obstacle lies within this distance "
                 "(inf = unlimited)"},
                SettingKind::Float,
                0.0,
                kInf,
                true,
                "scene units",
                nullptr,
                STRATUM_FLOAT(estimator.ao_distance)},
    SettingSpec{{"control_variate", "Control Variate",
                 "Ambient radiance L_a of the control variate (textbook 5.17); 0 = off"},
                SettingKind::Float,
                0.0,
                kFloatMax,
                false,
                "",
                nullptr,
                STRATUM_FLOAT(estimator.control_variate)},
    SettingSpec{
        {"sampler", "Sampler", "Sampling strategy"},
        SettingKind::Choice,
        0,
        0,
        false,
        "",
        &sampler_choices,
        [](const RenderSettings& s) { return static_cast<double>(s.sampler - sampler_registry().data()); },
        [](RenderSettings& s, double v) { s.sampler = &sampler_registry()[static_cast<size_t>(v)]; }},
    SettingSpec{
        {"integrator", "Integrator", "Light transport algorithm"},
        SettingKind::Choice,
        0,
        0,
        false,
        "",
        &integrator_choices,
        [](const RenderSettings& s) {
            return static_cast<double>(s.integrator - integrator_registry().data());
        },
        [](RenderSettings& s, double v) { s.integrator = &integrator_registry()[static_cast<size_t>(v)]; }},
    SettingSpec{{"hemisphere", "Hemisphere", "Distribution of diffuse and ambient-occlusion directions"},
                SettingKind::Choice,
                0,
                0,
                false,
                "",
                &hemisphere_registry,
                STRATUM_ENUM(estimator.hemisphere, HemisphereDistribution)},
    SettingSpec{{"filter_type", "Filter Type", "Pixel reconstruction filter"},
                SettingKind::Choice,
                0,
                0,
                false,
                "",
                &filter_registry,
                STRATUM_ENUM(filter_type, FilterType)},
    SettingSpec{{"light_sampling", "Light Sampling", "How the path tracer finds emission"},
                SettingKind::Choice,
                0,
                0,
                false,
                "",
                &light_sampling_choices,
                STRATUM_OPTION(estimator.light_sampling, light_sampling_at)},
    SettingSpec{{"mis_heuristic", "MIS Heuristic",
                 "Weights of light and BSDF samples under multiple importance sampling"},
                SettingKind::Choice,
                0,
                0,
                false,
                "",
                &mis_heuristic_choices,
                STRATUM_OPTION(estimator.mis_heuristic, mis_heuristic_at)},
    SettingSpec{
        {"light_selection", "Light Selection", "Probability of choosing each light for a light sample"},
        SettingKind::Choice,
        0,
        0,
        false,
        "",
        &light_selection_choices,
        STRATUM_OPTION(estimator.light_selection, light_selection_at)},
    SettingSpec{{"light_tree_splits", "Light Tree Splits",
                 "Light tree only: most light samples per shading point, one per node of the tree's "
                 "adaptive cut (1: one light, no splitting)"},
                SettingKind::Int,
                1,
                LightTree::kMaxCut,
                false,
                "",
                nullptr,
                STRATUM_UINT(estimator.light_tree_splits)},
    SettingSpec{{"triangle_sampling", "Triangle Sampling",
                 "How a light sample takes a point on an emissive triangle"},
                SettingKind::Choice,
                0,
                0,
                false,
                "",
                &triangle_sampling_choices,
                STRATUM_OPTION(estimator.triangle_sampling, triangle_sampling_at)},
    SettingSpec{{"rr_mode", "Russian Roulette", "How a path's survival probability is chosen"},
                SettingKind::Choice,
                0,
                0,
                false,
                "",
                &rr_mode_choices,
                STRATUM_OPTION(estimator.rr_mode, rr_mode_at)},
    SettingSpec{
        {"bvh", "BVH", "How the ray-tracing hierarchy is laid out: for rendering or for live editing"},
        SettingKind::Choice,
        0,
        0,
        false,
        "",
        &bvh_choices,
        STRATUM_ENUM(bvh, BvhLayout)},
    SettingSpec{{"mist_start", "Mist Start", "Mist pass: distance from the camera where the mist begins"},
                SettingKind::Float,
                0.0,
                kFloatMax,
                false,
                "scene units",
                nullptr,
                STRATUM_FLOAT(estimator.mist.start)},
    SettingSpec{{"mist_depth", "Mist Depth", "Mist pass: distance over which the mist goes from 0 to 1"},
                SettingKind::Float,
                0.0,
                kFloatMax,
                false,
                "scene units",
                nullptr,
                STRATUM_FLOAT(estimator.mist.depth)},
    SettingSpec{{"mist_falloff", "Mist Falloff",
                 "Mist pass: exponent of the mist's rise over its depth (Blender's quadratic 2, linear 1, "
                 "inverse quadratic 0.5)"},
                SettingKind::Float,
                0.0,
                16.0,
                false,
                "",
                nullptr,
                STRATUM_FLOAT(estimator.mist.falloff)},
    SettingSpec{{"passes", "Passes", "Passes the render holds besides Combined (comma-separated)"},
                SettingKind::List,
                0,
                0,
                false,
                "",
                &pass_choices,
                nullptr,
                nullptr,
                [](const RenderSettings& s) {
                    std::vector<size_t> out;
                    for (const Pass p : s.passes) out.push_back(static_cast<size_t>(p) - 1);
                    return out;
                },
                [](RenderSettings& s, const std::vector<size_t>& choices) {
                    s.passes.clear();
                    for (const size_t c : choices) s.passes.push_back(static_cast<Pass>(c + 1));
                }},
    SettingSpec{{"radiosity_patch_size", "Patch Size",
                 "Radiosity: longest edge of a patch; triangles are split until theirs are shorter (0 = "
                 "automatic: the scene's bounding-box diagonal / 32)"},
                SettingKind::Float,
                0.0,
                kFloatMax,
                false,
                "scene units",
                nullptr,
                STRATUM_FLOAT(estimator.radiosity.patch_size)},
    SettingSpec{{"radiosity_solver", "Solver", "Radiosity: how the linear system of the patches is solved"},
                SettingKind::Choice,
                0,
                0,
                false,
                "",
                &radiosity_solver_choices,
                STRATUM_ENUM(estimator.radiosity.solver, RadiositySolver)},
    SettingSpec{{"radiosity_tolerance", "Tolerance",
                 "Radiosity: the solve stops when the textbook's error estimate Delta E is at most this "
                 "share of the scene's mean radiance"},
                SettingKind::Float,
                0.0,
                1.0,
                true,
                "",
                nullptr,
                STRATUM_FLOAT(estimator.radiosity.tolerance)},
    SettingSpec{{"radiosity_rays", "Form Factor Rays",
                 "Radiosity: rays cast from each patch to estimate its form factors (Nusselt analogy)"},
                SettingKind::Int,
                1,
                kMaxRadiosityRays,
                false,
                "",
                nullptr,
                STRATUM_UINT(estimator.radiosity.rays)},
    SettingSpec{{"use_guiding", "Path Guiding",
                 "Path tracing: 1 = draw part of the scattered directions from a 5-D tree of the incident "
                 "radiance learned during the first samples (textbook 5.19; Cycles' use_guiding)"},
                SettingKind::Int,
                0,
                1,
                false,
                "",
                nullptr,
                [](const RenderSettings& s) { return s.estimator.use_guiding ? 1.0 : 0.0; },
                [](RenderSettings& s, double v) { s.estimator.use_guiding = v != 0.0; }},
    SettingSpec{{"guiding_training_samples", "Training Samples",
                 "Path guiding: samples per pixel during which the tree learns; then it stays as it is"},
                SettingKind::Int,
                1,
                kMaxSamples,
                false,
                "",
                nullptr,
                STRATUM_UINT(estimator.guiding_training_samples)},
    SettingSpec{{"guiding_bsdf_fraction", "BSDF Fraction",
                 "Path guiding: share of directions drawn by the material's own sampling, the rest by the "
                 "tree (at least 0.05: only the material draws mirror, glass and transparent directions)"},
                SettingKind::Float,
                0.05,
                1.0,
                false,
                "",
                nullptr,
                STRATUM_FLOAT(estimator.guiding_bsdf_fraction)},
    SettingSpec{{"guiding_split", "Split",
                 "Path guiding: how a node of the tree splits once it holds enough records"},
                SettingKind::Choice,
                0,
                0,
                false,
                "",
                &guiding_split_choices,
                STRATUM_ENUM(estimator.guiding_split, GuidingSplit)},
};

#undef STRATUM_UINT
#undef STRATUM_FLOAT
#undef STRATUM_OPTION
#undef STRATUM_ENUM

std::string format_number(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

std::string choice_names(const SettingSpec& spec) {
    std::string names;
    for (const RegistryEntry& e : spec.choices()) names += (names.empty() ? "" : ", ") + std::string(e.name);
    return names;
}

// The position of `name` among the setting's choices, or choices().size().
size_t find_choice(const SettingSpec& spec, std::string_view name) {
    const std::span<const RegistryEntry> choices = spec.choices();
    for (size_t i = 0; i < choices.size(); ++i)
        if (name == choices[i].name) return i;
    return choices.size();
}

const char* kind_name(SettingKind kind) {
    switch (kind) {
        case SettingKind::Int:
            return "integer";
        case SettingKind::Float:
            return "float";
        case SettingKind::Choice:
        case SettingKind::List:
            return "string";
    }
    return "";
}

// The setting `name` of `kind`, or an error message naming what is wrong.
const SettingSpec* lookup(std::string_view name, SettingKind kind, std::string* error) {
    const SettingSpec* spec = find_setting(name);
    const bool string_kind = kind == SettingKind::Choice;
    if (!spec || (string_kind ? (spec->kind != SettingKind::Choice && spec->kind != SettingKind::List)
                              : spec->kind != kind)) {
        *error = "unknown " + std::string(kind_name(kind)) + " setting '" + std::string(name) + "'" +
                 (spec ? " (it is a " + std::string(kind_name(spec->kind)) + " setting)" : "");
        return nullptr;
    }
    return spec;
}

}  // namespace

std::span<const SettingSpec> setting_registry() { return kSettings; }

const SettingSpec* find_setting(std::string_view name) {
    for (const SettingSpec& spec : kSettings)
        if (name == spec.info.name) return &spec;
    return nullptr;
}

std::string default_value(const SettingSpec& spec) {
    const RenderSettings defaults;
    switch (spec.kind) {
        case SettingKind::Int:
        case SettingKind::Float:
            return format_number(spec.get(defaults));
        case SettingKind::Choice:
            return spec.choices()[static_cast<size_t>(spec.get(defaults))].name;
        case SettingKind::List: {
            std::string names;
            for (const size_t c : spec.get_list(defaults))
                names += (names.empty() ? "" : ",") + std::string(spec.choices()[c].name);
            return names;
        }
    }
    return {};
}

std::string set_int_setting(RenderSettings& s, std::string_view name, int64_t value) {
    std::string error;
    const SettingSpec* spec = lookup(name, SettingKind::Int, &error);
    if (!spec) return error;
    const double v = static_cast<double>(value);
    if (v < spec->minimum || v > spec->maximum) {
        return "setting '" + std::string(name) + "' = " + std::to_string(value) + " is out of range [" +
               format_number(spec->minimum) + ", " + format_number(spec->maximum) + "]";
    }
    spec->set(s, v);
    return {};
}

std::string set_float_setting(RenderSettings& s, std::string_view name, double value) {
    std::string error;
    const SettingSpec* spec = lookup(name, SettingKind::Float, &error);
    if (!spec) return error;
    // The renderer stores a float: a double that rounds to 0 where 0 is excluded, or to infinity
    // where the range is finite, is judged by what it becomes.
    const float stored = static_cast<float>(value);
    const bool above_minimum =
        spec->open_minimum ? value > spec->minimum && stored > spec->minimum : value >= spec->minimum;
    if (std::isnan(value) || !above_minimum || !(value <= spec->maximum) ||
        (!std::isinf(spec->maximum) && !std::isfinite(stored))) {
        const std::string unit = *spec->unit ? std::string(" ") + spec->unit : "";
        return "setting '" + std::string(name) + "' = " + format_number(value) + " must be in " +
               (spec->open_minimum ? "(" : "[") + format_number(spec->minimum) + ", " +
               format_number(spec->maximum) + "]" + unit;
    }
    spec->set(s, value);
    return {};
}

std::string set_string_setting(RenderSettings& s, std::string_view name, std::string_view value) {
    std::string error;
    const SettingSpec* spec = lookup(name, SettingKind::Choice, &error);
    if (!spec) return error;
    if (spec->kind == SettingKind::Choice) {
        const size_t choice = find_choice(*spec, value);
        if (choice == spec->choices().size())
            return "unknown " + std::string(name) + " '" + std::string(value) +
                   "' (known: " + choice_names(*spec) + ")";
        spec->set(s, static_cast<double>(choice));
        return {};
    }
    std::vector<size_t> choices;
    for (size_t begin = 0; begin <= value.size();) {
        const size_t comma = std::min(value.find(',', begin), value.size());
        const std::string_view item = value.substr(begin, comma - begin);
        if (!item.empty()) {
            const size_t choice = find_choice(*spec, item);
            if (choice == spec->choices().size())
                return "unknown " + std::string(name) + " item '" + std::string(item) +
                       "' (known: " + choice_names(*spec) + ")";
            if (std::find(choices.begin(), choices.end(), choice) == choices.end()) choices.push_back(choice);
        }
        begin = comma + 1;
    }
    spec->set_list(s, choices);
    return {};
}

}  // namespace stratum
