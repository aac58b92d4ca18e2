// The passes (AOVs) a film can hold: the one list, named as Cycles names them so Blender's
// compositor and multilayer EXR read them unchanged. `Combined` (RGBA) is always there; the
// others exist in a render when the `passes` setting names them. docs/passes.md says what each
// holds and how it compares with Cycles'.
//
// | kind          | per pixel                                                                 |
// |---------------|---------------------------------------------------------------------------|
// | Radiance      | mean of the camera samples' values, plus light-path splats / sample indices |
// | Average       | mean of the camera samples' values (normals, albedo, ...)                 |
// | FirstSample   | the value of sample index 0 (Cycles writes Depth, Position only then:     |
// |               | kernel/film/data_passes.h, film_overwrite_pass_* at sample 0)             |
// | SampleCount   | the number of camera samples the pixel holds (the film counts them)       |
// | StandardError | per RGB channel, the estimated standard error of the mean of Combined's   |
// |               | camera samples, sqrt(G·(Σx²/n − x̄²)/(n − 1)), from the sums of squares   |
// |               | the film keeps and the gain G of film/error_estimate.h (0 below 2 samples) |
// | ShadowCatcher | Cycles' Shadow Catcher: from the sums of the catcher-only light, the matte |
// |               | and the splits of the camera samples (film/shadow_catcher_film.h)         |
//
// Average and FirstSample passes are written by the integrator (PassValues::write); the film
// derives SampleCount and StandardError itself. Adding a pass: a line here (at the end: the
// `passes` setting stores positions), the integrator line that writes it, a test.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

namespace stratum {

enum class PassKind : uint8_t { Radiance, Average, FirstSample, SampleCount, StandardError, ShadowCatcher };

struct PassInfo {
    const char* name;
    uint32_t channels;
    PassKind kind;
    const char* description;
};

// Index into kPasses.
enum class Pass : uint32_t {
    Combined,
    Normal,
    Depth,
    Position,
    DenoisingAlbedo,
    DenoisingNormal,
    SampleCount,
    Error,
    Uv,
    Emit,
    Env,
    Mist,
    Ao,
    ObjectIndex,
    MaterialIndex,
    DiffuseColor,
    GlossyColor,
    TransmissionColor,
    ShadowCatcher
};

// Cycles' Depth of a camera ray that meets nothing (kernel/film/read.h: a stored 0 reads 1e10).
inline constexpr float kBackgroundDepth = 1e10f;

inline constexpr std::array kPasses = {
    PassInfo{"Combined", 4, PassKind::Radiance, "The rendered image: radiance (RGB) and alpha"},
    PassInfo{
        "Normal", 3, PassKind::Average,
        "World-space shading normal of the first opaque surface a camera ray meets (0 where it meets none)"},
    PassInfo{"Depth", 1, PassKind::FirstSample,
             "Camera-space depth (distance along the view axis; distance for panoramic cameras) of the first "
             "opaque surface, of sample 0 as in Cycles (1e10 where the ray meets none)"},
    PassInfo{"Position", 3, PassKind::FirstSample,
             "World-space position of the first opaque surface, of sample 0 as in Cycles (0 where none)"},
    PassInfo{"Denoising Albedo", 3, PassKind::Average,
             "Albedo for a denoiser: the closures' albedo at the first non-mirror surface, tinted by the "
             "mirrors, glass and transparency passed on the way, plus the emission and background seen"},
    PassInfo{"Denoising Normal", 3, PassKind::Average,
             "Shading normal of the first non-mirror surface in Cycles' camera space (x right, y up, z "
             "forward), as Cycles gives a denoiser (0 where none)"},
    PassInfo{"Debug Sample Count", 1, PassKind::SampleCount, "Camera samples taken in each pixel"},
    PassInfo{"Stratum Error", 3, PassKind::StandardError,
             "Estimated standard error of each pixel's Combined RGB mean: its samples' spread s/sqrt(n), "
             "times the sampler's gain measured from the pixel's power-of-two prefixes (docs/passes.md)"},
    PassInfo{"UV", 3, PassKind::Average,
             "Texture coordinates (u, v, 0) of the first opaque surface's UV map (0 where none)"},
    PassInfo{"Emit", 3, PassKind::Average,
             "Emission seen directly: of surfaces and lamps a camera ray meets before its first bounce"},
    PassInfo{"Env", 3, PassKind::Average,
             "Background seen directly: where a camera ray leaves the scene before its first bounce"},
    PassInfo{
        "Mist", 1, PassKind::Average,
        "Cycles' mist: 1 − the surfaces' transparency-weighted closeness, from the distance to the camera "
        "through the mist start, depth and falloff (1 where a ray meets nothing)"},
    PassInfo{"AO", 3, PassKind::Average,
             "Cycles' AO pass: the share of cosine-distributed directions above the surfaces a camera ray "
             "meets before its first bounce that no obstacle blocks within ao_distance, times their opacity"},
    PassInfo{"IndexOB", 1, PassKind::FirstSample,
             "Object > Relations > Pass Index of the first opaque surface, of sample 0 as in Cycles (0 "
             "where none)"},
    PassInfo{"IndexMA", 1, PassKind::FirstSample,
             "Material > Settings > Pass Index of the first opaque surface's material, of sample 0 as in "
             "Cycles (0 where none)"},
    PassInfo{
        "DiffCol", 3, PassKind::Average,
        "Cycles' Diffuse Color: the diffuse closures' colour (weight in 3.x, albedo in 4.x) of the surfaces "
        "a camera ray meets before its first bounce, times the path's throughput"},
    PassInfo{
        "GlossCol", 3, PassKind::Average,
        "Cycles' Glossy Color: the glossy closures' colour (glass: its reflection share) of the surfaces a "
        "camera ray meets before its first bounce, times the path's throughput"},
    PassInfo{"TransCol", 3, PassKind::Average,
             "Cycles' Transmission Color: the transmission closures' colour (glass: its refraction share) of "
             "the surfaces a camera ray meets before its first bounce, times the path's throughput"},
    PassInfo{"Shadow Catcher", 3, PassKind::ShadowCatcher,
             "Cycles' Shadow Catcher: the light on shadow catchers with every object there over their light "
             "with only catchers there (0 in full shadow, 1 unshadowed), alpha-overed on white"},
};

inline constexpr const PassInfo& pass_info(Pass pass) { return kPasses[static_cast<uint32_t>(pass)]; }
// Channels the integrator writes per camera sample (Average and FirstSample passes), and
// doubles the film keeps per pixel for the pass.
// The Shadow Catcher pass sums kShadowCatcherSums values per sample (film/shadow_catcher_film.h).
inline constexpr uint32_t kShadowCatcherSums = 11;
inline constexpr uint32_t sample_channels(const PassInfo& info) {
    if (info.kind == PassKind::ShadowCatcher) return kShadowCatcherSums;
    return info.kind == PassKind::Average || info.kind == PassKind::FirstSample ? info.channels : 0;
}
inline constexpr uint32_t stored_channels(const PassInfo& info) {
    if (info.kind == PassKind::ShadowCatcher) return kShadowCatcherSums;
    return info.kind == PassKind::SampleCount ? 0 : info.channels;
}
// The pass of this name, or false.
inline bool find_pass(std::string_view name, Pass* out) {
    for (uint32_t i = 0; i < kPasses.size(); ++i) {
        if (name == kPasses[i].name) {
            *out = static_cast<Pass>(i);
            return true;
        }
    }
    return false;
}

}  // namespace stratum
