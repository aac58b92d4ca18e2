// Render settings as the renderer reads them: every value parsed and checked once, when the host
// sets it by name (render/setting_registry.h lists the names, kinds, ranges and choices). The
// defaults are the member initialisers here and in IntegratorSettings; the registry reports them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "film/passes.h"
#include "film/pixel_filter.h"
#include "film/pixel_region.h"
#include "integrators/integrator.h"
#include "render_scene/render_scene.h"
#include "sampling/sampler_registry.h"

namespace stratum {

// Adaptive sampling (render/adaptive_sampling.h): what the settings say; the renderer resolves
// the automatic values.
enum class AdaptiveMetric : uint8_t {
    Relative,  // each pixel's error relative to its own brightness (Cycles')
    Mse,       // the image's mean squared error at equal time
};

struct AdaptiveSettings {
    bool enabled = false;
    float threshold = 0.01f;   // 0 = automatic
    uint32_t min_samples = 0;  // 0 = automatic
    AdaptiveMetric metric = AdaptiveMetric::Relative;
};

struct RenderSettings {
    uint32_t width = 64, height = 64;
    uint32_t samples = 16;
    uint32_t seed = 0;
    AdaptiveSettings adaptive;
    // A subset of the frame's sample indices, as Cycles' sample subset: the render takes indices
    // [sample_offset, sample_offset + sample_count) of the `samples` the sampler's sequence is
    // built for (sample_count = 0: up to `samples`). Renders of disjoint subsets, their exact
    // sums added (film/film.h), give the image of all `samples` bit for bit.
    uint32_t sample_offset = 0, sample_count = 0;
    uint32_t threads = 0;  // 0 = all cores
    // Border render: the region [crop_x, crop_x + crop_width) x [crop_y, crop_y + crop_height) of
    // the width x height frame, bottom-left origin; crop_width = 0 = the whole frame. Only the
    // region is rendered, read and written; its pixels are those of the full frame.
    uint32_t crop_x = 0, crop_y = 0, crop_width = 0, crop_height = 0;
    FilterType filter_type = FilterType::BlackmanHarris;
    float filter_width = 1.5f;
    const SamplerEntry* sampler = find_sampler("random");
    const IntegratorEntry* integrator = find_integrator("path");
    // The integrator's share: bounces, hemisphere, AO distance, transparent film, estimator
    // options, Russian roulette, control variate.
    IntegratorSettings estimator;
    // The passes besides Combined.
    std::vector<Pass> passes;
    // The light groups' passes (film/light_groups.h).
    uint32_t lightgroups = 0;
    // The BVH layout: static (fastest to trace) or dynamic (fast to update after live edits).
    BvhLayout bvh = BvhLayout::Static;
};

// The region the crop settings select (the whole frame when crop_width = 0), or an error
// message naming the setting that puts it outside the frame.
std::string crop_region(const RenderSettings& s, PixelRegion* out);
// The sample indices [*begin, *end) the subset settings select, or an error message naming the
// setting that puts them outside [0, samples).
std::string sample_range(const RenderSettings& s, uint32_t* begin, uint32_t* end);

}  // namespace stratum
