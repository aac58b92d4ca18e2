#include "render/render_settings.h"

#include <algorithm>
#include <cmath>

#include "film/pixel_filter.h"
#include "integrators/integrator.h"
#include "sampling/hemisphere.h"
#include "sampling/sampler_registry.h"

namespace stratum {

namespace {

// Limits keep width*height*4 floats and sample indices far from 32-bit overflow.
constexpr int64_t kMaxResolution = 65536;
constexpr int64_t kMaxSamples = 1 << 24;
constexpr int64_t kMaxBounces = 1024;

std::string out_of_range(std::string_view name, int64_t value, int64_t lo, int64_t hi) {
    return "setting '" + std::string(name) + "' = " + std::to_string(value) + " is out of range [" +
           std::to_string(lo) + ", " + std::to_string(hi) + "]";
}

template <typename Registry>
std::string registry_names(const Registry& registry) {
    std::string names;
    for (const auto& e : registry) names += (names.empty() ? "" : ", ") + std::string(e.info.name);
    return names;
}

}  // namespace

std::string set_int_setting(RenderSettings& s, std::string_view name, int64_t value) {
    struct Field {
        std::string_view name;
        uint32_t RenderSettings::*member;
        int64_t lo, hi;
    };
    static constexpr Field kFields[] = {
        {"width", &RenderSettings::width, 1, kMaxResolution},
        {"height", &RenderSettings::height, 1, kMaxResolution},
        {"samples", &RenderSettings::samples, 1, kMaxSamples},
        {"max_bounces", &RenderSettings::max_bounces, 0, kMaxBounces},
        {"seed", &RenderSettings::seed, 0, 0xffffffffll},
        {"threads", &RenderSettings::threads, 0, 1024},
        {"crop_x", &RenderSettings::crop_x, 0, kMaxResolution - 1},
        {"crop_y", &RenderSettings::crop_y, 0, kMaxResolution - 1},
        {"crop_width", &RenderSettings::crop_width, 0, kMaxResolution},
        {"crop_height", &RenderSettings::crop_height, 0, kMaxResolution},
        {"film_transparent", &RenderSettings::film_transparent, 0, 1},
        {"rr_min_depth", &RenderSettings::rr_min_depth, 0, kMaxBounces},
    };
    for (const Field& f : kFields) {
        if (f.name != name) continue;
        if (value < f.lo || value > f.hi) return out_of_range(name, value, f.lo, f.hi);
        s.*f.member = static_cast<uint32_t>(value);
        return {};
    }
    return "unknown integer setting '" + std::string(name) + "'";
}

std::string set_float_setting(RenderSettings& s, std::string_view name, double value) {
    if (name == "filter_width") {
        if (!std::isfinite(value) || value < 0.01 || value > 100.0) {
            return "setting 'filter_width' = " + std::to_string(value) + " must be in [0.01, 100] pixels";
        }
        s.filter_width = static_cast<float>(value);
        return {};
    }
    if (name == "ao_distance") {
        // +inf means unlimited (seed 000's d = infinity); NaN, 0 and negatives are rejected.
        if (std::isnan(value) || value <= 0.0 || static_cast<float>(value) <= 0.0f) {
            return "setting 'ao_distance' = " + std::to_string(value) + " must be > 0 (scene units)";
        }
        s.ao_distance = static_cast<float>(value);
        return {};
    }
    if (name == "control_variate") {
        if (!std::isfinite(value) || value < 0.0 || !std::isfinite(static_cast<float>(value))) {
            return "setting 'control_variate' = " + std::to_string(value) +
                   " must be a finite ambient radiance >= 0 (0 = off)";
        }
        s.control_variate = static_cast<float>(value);
        return {};
    }
    return "unknown float setting '" + std::string(name) + "'";
}

std::string set_string_setting(RenderSettings& s, std::string_view name, std::string_view value) {
    if (name == "sampler") {
        if (!find_sampler(value)) {
            return "unknown sampler '" + std::string(value) +
                   "' (known: " + registry_names(sampler_registry()) + ")";
        }
        s.sampler = value;
        return {};
    }
    if (name == "integrator") {
        if (!find_integrator(value)) {
            return "unknown integrator '" + std::string(value) +
                   "' (known: " + registry_names(integrator_registry()) + ")";
        }
        s.integrator = value;
        return {};
    }
    if (name == "hemisphere") {
        HemisphereDistribution d;
        if (!parse_hemisphere(value, &d)) {
            std::string names;
            for (const RegistryEntry& e : hemisphere_registry())
                names += (names.empty() ? "" : ", ") + std::string(e.name);
            return "unknown hemisphere '" + std::string(value) + "' (known: " + names + ")";
        }
        s.hemisphere = value;
        return {};
    }
    // The estimator options: each name is checked by its parser, the message lists the choices.
    struct Option {
        std::string_view name;
        std::string RenderSettings::*member;
        std::span<const std::string_view> (*names)();
        bool (*valid)(std::string_view);
    };
    static constexpr Option kOptions[] = {
        {"light_sampling", &RenderSettings::light_sampling, &light_sampling_names,
         [](std::string_view v) {
             LightSampling x;
             return parse_light_sampling(v, &x);
         }},
        {"mis_heuristic", &RenderSettings::mis_heuristic, &mis_heuristic_names,
         [](std::string_view v) {
             MisHeuristic x;
             return parse_mis_heuristic(v, &x);
         }},
        {"light_selection", &RenderSettings::light_selection, &light_selection_names,
         [](std::string_view v) {
             LightSelection x;
             return parse_light_selection(v, &x);
         }},
        {"triangle_sampling", &RenderSettings::triangle_sampling, &triangle_sampling_names,
         [](std::string_view v) {
             TriangleSampling x;
             return parse_triangle_sampling(v, &x);
         }},
        {"rr_mode", &RenderSettings::rr_mode, &rr_mode_names,
         [](std::string_view v) {
             RouletteMode x;
             return parse_rr_mode(v, &x);
         }},
    };
    for (const Option& o : kOptions) {
        if (o.name != name) continue;
        if (!o.valid(value)) {
            std::string names;
            for (std::string_view n : o.names()) names += (names.empty() ? "" : ", ") + std::string(n);
            return "unknown " + std::string(name) + " '" + std::string(value) + "' (known: " + names + ")";
        }
        s.*o.member = value;
        return {};
    }
    if (name == "passes") {
        std::vector<Pass> passes;
        for (size_t begin = 0; begin <= value.size();) {
            const size_t comma = std::min(value.find(',', begin), value.size());
            const std::string_view item = value.substr(begin, comma - begin);
            Pass pass;
            if (!item.empty()) {
                if (!find_pass(item, &pass)) {
                    std::string names;
                    for (const PassInfo& info : kPasses)
                        names += (names.empty() ? "" : ", ") + std::string(info.name);
                    return "unknown pass '" + std::string(item) + "' in setting 'passes' (known: " + names +
                           ")";
                }
                if (std::find(passes.begin(), passes.end(), pass) == passes.end()) passes.push_back(pass);
            }
            begin = comma + 1;
        }
        s.passes = std::move(passes);
        return {};
    }
    if (name == "filter_type") {
        FilterType type;
        if (!parse_filter_type(value, &type)) {
            return "unknown filter_type '" + std::string(value) + "' (known: box, blackman_harris)";
        }
        s.filter_type = value;
        return {};
    }
    return "unknown string setting '" + std::string(name) + "'";
}

std::string crop_region(const RenderSettings& s, PixelRegion* out) {
    if (s.crop_width == 0) {
        if (s.crop_height != 0 || s.crop_x != 0 || s.crop_y != 0) {
            return "border region: crop_width = 0 (the whole frame) but crop_x = " +
                   std::to_string(s.crop_x) + ", crop_y = " + std::to_string(s.crop_y) +
                   ", crop_height = " + std::to_string(s.crop_height) + " (all must be 0)";
        }
        *out = {0, 0, s.width, s.height};
        return {};
    }
    if (s.crop_height == 0)
        return "border region: crop_height = 0 with crop_width = " + std::to_string(s.crop_width);
    const auto outside = [](const char* axis, uint32_t start, uint32_t size, uint32_t frame) {
        return std::string("border region outside the frame: crop_") + axis + " = " + std::to_string(start) +
               " + crop_" + (axis[0] == 'x' ? "width" : "height") + " = " + std::to_string(size) +
               " exceeds " + (axis[0] == 'x' ? "width" : "height") + " = " + std::to_string(frame);
    };
    if (static_cast<uint64_t>(s.crop_x) + s.crop_width > s.width)
        return outside("x", s.crop_x, s.crop_width, s.width);
    if (static_cast<uint64_t>(s.crop_y) + s.crop_height > s.height)
        return outside("y", s.crop_y, s.crop_height, s.height);
    *out = {s.crop_x, s.crop_y, s.crop_width, s.crop_height};
    return {};
}

IntegratorSettings integrator_settings(const RenderSettings& s) {
    IntegratorSettings out;
    out.max_bounces = s.max_bounces;
    parse_hemisphere(s.hemisphere, &out.hemisphere);
    out.ao_distance = s.ao_distance;
    out.film_transparent = s.film_transparent != 0;
    parse_light_sampling(s.light_sampling, &out.light_sampling);
    parse_mis_heuristic(s.mis_heuristic, &out.mis_heuristic);
    parse_light_selection(s.light_selection, &out.light_selection);
    parse_triangle_sampling(s.triangle_sampling, &out.triangle_sampling);
    parse_rr_mode(s.rr_mode, &out.rr_mode);
    out.rr_min_depth = s.rr_min_depth;
    out.control_variate = s.control_variate;
    return out;
}

}  // namespace stratum
