// Render settings as they cross the C ABI: named values, each with one kind (int, float,
// string). An unknown name or a value out of range is rejected with a message naming it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "film/passes.h"
#include "film/pixel_region.h"

namespace stratum {

struct RenderSettings {
    uint32_t width = 64, height = 64;
    uint32_t samples = 16;
    uint32_t max_bounces = 12;
    uint32_t seed = 0;
    uint32_t threads = 0;  // 0 = all cores
    // Border render: the region [crop_x, crop_x + crop_width) x [crop_y, crop_y + crop_height) of
    // the width x height frame, bottom-left origin; crop_width = 0 = the whole frame. Only the
    // region is rendered, read and written; its pixels are those of the full frame.
    uint32_t crop_x = 0, crop_y = 0, crop_width = 0, crop_height = 0;
    uint32_t film_transparent = 0;  // 1: the background has alpha 0 (Cycles' Film > Transparent)
    float filter_width = 1.5f;
    float ao_distance = 1.0f;      // `ao` integrator: occlusion distance, scene units, > 0 (inf allowed)
    uint32_t rr_min_depth = 3;     // first bounce at which Russian roulette may end a path
    float control_variate = 0.0f;  // ambient radiance L_a of the control variate, >= 0; 0 = off
    std::string sampler = "random";
    std::string filter_type = "blackman_harris";
    std::string integrator = "path";
    std::string hemisphere = "cosine";  // sampling/hemisphere.h registry name
    // integrators/estimator_options.h names.
    std::string light_sampling = "mis";
    std::string mis_heuristic = "power";
    std::string light_selection = "mixed";
    std::string triangle_sampling = "solid_angle";
    std::string rr_mode = "throughput";
    // The passes besides Combined (setting `passes`: comma-separated names of film/passes.h).
    std::vector<Pass> passes;
};

// The region the crop settings select (the whole frame when crop_width = 0), or an error
// message naming the setting that puts it outside the frame.
std::string crop_region(const RenderSettings& s, PixelRegion* out);

struct IntegratorSettings;
// The integrator's share of the settings (names already validated).
IntegratorSettings integrator_settings(const RenderSettings& s);

// Each returns an empty string on success, else the error message.
std::string set_int_setting(RenderSettings& s, std::string_view name, int64_t value);
std::string set_float_setting(RenderSettings& s, std::string_view name, double value);
std::string set_string_setting(RenderSettings& s, std::string_view name, std::string_view value);

}  // namespace stratum
