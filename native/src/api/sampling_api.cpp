// C entry points for sampling without a scene (`stratum points`, studies, the add-on's
// plots): the named dimension layout, raw sampler points, hemisphere warps. Every input is
// validated and every exception stops here (api/abi_guard.h).
#include <array>
#include <cmath>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "api/abi_guard.h"
#include "sampling/bluenoise_sampler.h"
#include "sampling/dimensions.h"
#include "sampling/hemisphere.h"
#include "sampling/sampler_registry.h"
#include "stratum/stratum.h"

namespace {

using stratum::require;
using stratum::abi::guarded;

// Limits of the render settings (render_settings.cpp): the same image sizes and sample counts.
constexpr uint32_t kMaxResolution = 65536;
constexpr uint32_t kMaxSamples = 1u << 24;
// At most this many points per call: 8 MiB of output, enough for any plot or study.
constexpr uint32_t kMaxPoints = 1u << 20;
// Names of dimensions below this are cached for the life of the process; names of higher
// dimensions (far beyond any bounce the renderer reaches) live until the next call on the
// calling thread, so a caller cannot grow the cache without bound.
constexpr uint32_t kCachedDimensions = 1u << 16;

// Names of the camera block, indexed by dimension; built from the enum constants of
// dimensions.h so the names follow the layout when it changes.
std::array<std::string_view, stratum::kCameraDimensions> camera_names() {
    using namespace stratum;
    static_assert(kDimFilter + 1 < kCameraDimensions && kDimLens + 1 < kCameraDimensions &&
                  kDimTime < kCameraDimensions);
    std::array<std::string_view, kCameraDimensions> names;
    names.fill("camera.unused");
    names[kDimFilter] = "filter.x";
    names[kDimFilter + 1] = "filter.y";
    names[kDimLens] = "lens.u";
    names[kDimLens + 1] = "lens.v";
    names[kDimTime] = "time";
    return names;
}

// Names of one bounce block without the "bounce<k>." prefix, indexed by offset in the block.
std::array<std::string_view, stratum::kBounceStride> bounce_names() {
    using namespace stratum;
    static_assert(kDimLightChoice < kBounceStride && kDimRussianRoulette < kBounceStride &&
                  kDimLightPoint + 1 < kBounceStride && kDimBsdfDirection + 1 < kBounceStride &&
                  kDimBsdfLobe < kBounceStride);
    std::array<std::string_view, kBounceStride> names;
    names.fill("unused");
    names[kDimLightChoice] = "light_choice";
    names[kDimRussianRoulette] = "russian_roulette";
    names[kDimLightPoint] = "light.u";
    names[kDimLightPoint + 1] = "light.v";
    names[kDimBsdfDirection] = "bsdf.u";
    names[kDimBsdfDirection + 1] = "bsdf.v";
    names[kDimBsdfLobe] = "bsdf_lobe";
    return names;
}

std::string dimension_name(uint32_t dimension) {
    static const auto camera = camera_names();
    static const auto bounce = bounce_names();
    if (dimension < stratum::kCameraDimensions) return std::string(camera[dimension]);
    const uint32_t rest = dimension - stratum::kCameraDimensions;
    return "bounce" + std::to_string(rest / stratum::kBounceStride) + "." +
           std::string(bounce[rest % stratum::kBounceStride]);
}

// A stable pointer to the name of `dimension` (see kCachedDimensions).
const char* cached_dimension_name(uint32_t dimension) {
    if (dimension >= kCachedDimensions) {
        thread_local std::string name;
        name = dimension_name(dimension);
        return name.c_str();
    }
    static std::mutex mutex;
    // Node-based: pointers to the stored strings survive rehashing.
    static std::unordered_map<uint32_t, std::string> cache;
    const std::lock_guard lock(mutex);
    auto it = cache.find(dimension);
    if (it == cache.end()) it = cache.emplace(dimension, dimension_name(dimension)).first;
    return it->second.c_str();
}

std::string sampler_names() {
    std::string names;
    for (const stratum::SamplerEntry& e : stratum::sampler_registry()) {
        names += (names.empty() ? "" : ", ") + std::string(e.info.name);
    }
    return names;
}

std::string hemisphere_names() {
    std::string names;
    for (const stratum::RegistryEntry& e : stratum::hemisphere_registry()) {
        names += (names.empty() ? "" : ", ") + std::string(e.name);
    }
    return names;
}

void require_in_range(const char* what, uint32_t value, uint32_t lo, uint32_t hi) {
    require(value >= lo && value <= hi, std::string(what) + " = " + std::to_string(value) +
                                            " is out of range [" + std::to_string(lo) + ", " +
                                            std::to_string(hi) + "]");
}

// Formats a float for an error message ("nan", "inf", "1.5").
std::string format_value(float v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return std::to_string(v);
}

}  // namespace

extern "C" {

StratumStatus stratum_dimension_name(uint32_t dimension, const char** out_name) {
    return guarded("stratum_dimension_name", [&] {
        require(out_name != nullptr, "out_name is NULL");
        *out_name = cached_dimension_name(dimension);
        return STRATUM_OK;
    });
}

uint32_t stratum_camera_dimensions(void) { return stratum::kCameraDimensions; }

uint32_t stratum_bounce_dimension_stride(void) { return stratum::kBounceStride; }

// Points with indices beyond `samples` are allowed: every sampler is defined for any sample
// index (a stratified sampler then starts a new pass over its strata), and a study may want
// to see what the next samples look like. `samples` only parameterizes the sampler, as in a
// render with that sample count.
StratumStatus stratum_sampler_points(const char* sampler, uint32_t samples, uint32_t seed, uint32_t width,
                                     uint32_t height, uint32_t pixel_x, uint32_t pixel_y, uint32_t dim_a,
                                     uint32_t dim_b, uint32_t count, float* out_xy) {
    return guarded("stratum_sampler_points", [&] {
        require(sampler != nullptr, "sampler is NULL");
        const stratum::SamplerEntry* entry = stratum::find_sampler(sampler);
        require(entry != nullptr,
                "unknown sampler '" + std::string(sampler) + "' (known: " + sampler_names() + ")");
        require_in_range("samples", samples, 1, kMaxSamples);
        require_in_range("width", width, 1, kMaxResolution);
        require_in_range("height", height, 1, kMaxResolution);
        require(pixel_x < width && pixel_y < height,
                "pixel (" + std::to_string(pixel_x) + ", " + std::to_string(pixel_y) + ") is outside the " +
                    std::to_string(width) + "x" + std::to_string(height) + " image");
        require_in_range("count", count, 0, kMaxPoints);
        require(out_xy != nullptr, "out_xy is NULL");

        stratum::SamplerSettings settings;
        settings.samples = samples;
        settings.seed = seed;
        settings.width = width;
        settings.height = height;
        const std::unique_ptr<stratum::Sampler> s = entry->create(settings);
        require(s != nullptr, "sampler '" + std::string(sampler) + "' could not be created");
        // The integrators read a 2D quantity as the sampler's pair (even dimension, next one).
        const bool pair = dim_a % 2 == 0 && dim_b == dim_a + 1;
        for (uint32_t i = 0; i < count; ++i) {
            const stratum::PixelSample ps(pixel_x, pixel_y, i);
            if (pair) {
                const stratum::Vec2 p = s->get_2d(ps, dim_a);
                out_xy[2 * size_t{i}] = p.x;
                out_xy[2 * size_t{i} + 1] = p.y;
            } else {
                out_xy[2 * size_t{i}] = s->get_1d(ps, dim_a);
                out_xy[2 * size_t{i} + 1] = s->get_1d(ps, dim_b);
            }
        }
        return STRATUM_OK;
    });
}

// uv values must be finite and in [0, 1]; 1 is accepted (a float32 just below 1 in the
// caller's double precision rounds to it) and clamped below 1, as the integrators clamp samples.
StratumStatus stratum_warp_hemisphere(const char* distribution, const float* uv, uint32_t count,
                                      float* out_xyz, float* out_pdf) {
    return guarded("stratum_warp_hemisphere", [&] {
        require(distribution != nullptr, "distribution is NULL");
        stratum::HemisphereDistribution d;
        require(stratum::parse_hemisphere(distribution, &d), "unknown hemisphere distribution '" +
                                                                 std::string(distribution) +
                                                                 "' (known: " + hemisphere_names() + ")");
        require_in_range("count", count, 0, kMaxPoints);
        require(uv != nullptr && out_xyz != nullptr, "uv or out_xyz is NULL");
        for (uint32_t i = 0; i < count; ++i) {
            for (int c = 0; c < 2; ++c) {
                const float v = uv[2 * size_t{i} + c];
                require(std::isfinite(v) && v >= 0.0f && v <= 1.0f,
                        "uv[" + std::to_string(i) + "]." + (c == 0 ? "u" : "v") + " = " + format_value(v) +
                            " is outside [0, 1]");
            }
        }
        for (uint32_t i = 0; i < count; ++i) {
            const stratum::Vec2 u{std::fmin(uv[2 * size_t{i}], stratum::kOneMinusEpsilon),
                                  std::fmin(uv[2 * size_t{i} + 1], stratum::kOneMinusEpsilon)};
            const stratum::Vec3 w = stratum::sample_hemisphere(d, u);
            out_xyz[3 * size_t{i}] = w.x;
            out_xyz[3 * size_t{i} + 1] = w.y;
            out_xyz[3 * size_t{i} + 2] = w.z;
            if (out_pdf) out_pdf[i] = stratum::hemisphere_pdf(d, w.z);
        }
        return STRATUM_OK;
    });
}

// The texture is a fixed function of the library (not of any seed), so there is nothing to
// choose: the caller passes the size it expects, and a mismatch is an error, not a truncation.
StratumStatus stratum_bluenoise_texture(float* out, uint32_t count) {
    return guarded("stratum_bluenoise_texture", [&] {
        constexpr uint32_t kTexels = stratum::BlueNoiseSampler::kSize * stratum::BlueNoiseSampler::kSize;
        require(count == kTexels,
                "count = " + std::to_string(count) + " is not " + std::to_string(kTexels) + " (128 x 128)");
        require(out != nullptr, "out is NULL");
        const std::vector<uint32_t>& ranks = stratum::BlueNoiseSampler::ranks();
        for (uint32_t i = 0; i < kTexels; ++i) out[i] = stratum::BlueNoiseSampler::rank_to_value(ranks[i]);
        return STRATUM_OK;
    });
}

}  // extern "C"
