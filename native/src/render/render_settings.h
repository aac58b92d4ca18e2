// Render settings as they cross the C ABI: named values, each with one kind (int, float,
// string). An unknown name or a value out of range is rejected with a message naming it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace stratum {

struct RenderSettings {
    uint32_t width = 64, height = 64;
    uint32_t samples = 16;
    uint32_t max_bounces = 12;
    uint32_t seed = 0;
    uint32_t threads = 0;  // 0 = all cores
    float filter_width = 1.5f;
    float ao_distance = 1.0f;  // `ao` integrator: occlusion distance, scene units, > 0 (inf allowed)
    std::string sampler = "random";
    std::string filter_type = "blackman_harris";
    std::string integrator = "path";
    std::string hemisphere = "cosine";  // sampling/hemisphere.h registry name
};

struct IntegratorSettings;
// The integrator's share of the settings (names already validated).
IntegratorSettings integrator_settings(const RenderSettings& s);

// Each returns an empty string on success, else the error message.
std::string set_int_setting(RenderSettings& s, std::string_view name, int64_t value);
std::string set_float_setting(RenderSettings& s, std::string_view name, double value);
std::string set_string_setting(RenderSettings& s, std::string_view name, std::string_view value);

}  // namespace stratum
