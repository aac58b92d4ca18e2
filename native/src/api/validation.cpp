#include "api/validation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "api/validation_checks.h"
#include "lights/light_registry.h"
#include "scene/scene_limits.h"
#include "scene/visibility.h"

namespace stratum {

// The core's visibility bits are the ABI's.
static_assert(kVisibleCamera == STRATUM_VISIBLE_CAMERA && kVisibleDiffuse == STRATUM_VISIBLE_DIFFUSE &&
              kVisibleGlossy == STRATUM_VISIBLE_GLOSSY &&
              kVisibleTransmission == STRATUM_VISIBLE_TRANSMISSION &&
              kVisibleShadow == STRATUM_VISIBLE_SHADOW && kVisibleAll == STRATUM_VISIBLE_ALL &&
              kVisibleShadowCatcher == STRATUM_VISIBLE_SHADOW_CATCHER);
static_assert(kMaxLightGroups == STRATUM_MAX_LIGHT_GROUPS);

using namespace abi_checks;

namespace {

float finite_in(float v, float lo, float hi, const char* what) {
    require(std::isfinite(v) && v >= lo && v <= hi,
            std::string(what) + " = " + fmt(v) + " must be in [" + fmt(lo) + ", " + fmt(hi) + "]");
    return v;
}

// v in (lo, hi].
float finite_in_open(float v, float lo, float hi, const char* what) {
    require(std::isfinite(v) && v > lo && v <= hi,
            std::string(what) + " = " + fmt(v) + " must be in (" + fmt(lo) + ", " + fmt(hi) + "]");
    return v;
}

float finite_positive(float v, const char* what) {
    require(std::isfinite(v) && v > 0.0f, std::string(what) + " = " + fmt(v) + " must be finite and > 0");
    return v;
}

Rgb rgb_in(const float* c, float lo, float hi, const char* what) {
    for (int i = 0; i < 3; ++i) {
        require(std::isfinite(c[i]) && c[i] >= lo && c[i] <= hi, std::string(what) + "[" + std::to_string(i) +
                                                                     "] = " + fmt(c[i]) + " must be in [" +
                                                                     fmt(lo) + ", " + fmt(hi) + "]");
    }
    return {c[0], c[1], c[2]};
}

// A camera's view directions are its linear part applied to view-plane vectors, then
// normalised: each axis needs a length that neither underflows nor overflows, and the three
// must span space (Blender's camera matrices are rotations; the exporter drops their scale, as
// Cycles does). The bound 1e-6 on |det| / (|a0| |a1| |a2|) (the sine-like volume of the unit
// axes) refuses frames flat enough to map two view directions onto one.
void check_camera_frame(const Transform& t) {
    const Vec3 a0 = t.column(0), a1 = t.column(1), a2 = t.column(2);
    const float l0 = length(a0), l1 = length(a1), l2 = length(a2);
    for (float l : {l0, l1, l2}) {
        require(l >= 1e-6f && l <= 1e6f, "camera transform has an axis of length " + fmt(l) +
                                             " (its linear part must be a rotation, scale in [1e-6, 1e6])");
    }
    const float volume = std::abs(dot(a0, cross(a1, a2))) / (l0 * l1 * l2);
    require(volume >= 1e-6f, "camera transform is (nearly) singular: its axes span a volume of " +
                                 fmt(volume) + " of a rotation's");
}

}  // namespace

Rgb validate_radiance(const float* rgb, const char* what) {
    return rgb_in(rgb, 0.0f, std::numeric_limits<float>::max(), what);
}

Environment validate_environment(const float* rgb, uint32_t width, uint32_t height, float strength,
                                 const float* rotation) {
    require(rgb != nullptr, "environment rgb is NULL");
    require(width > 0 && height > 0, "environment size " + std::to_string(width) + " x " +
                                         std::to_string(height) + " must be at least 1 x 1");
    require(static_cast<uint64_t>(width) * height <= (uint64_t(1) << 28),
            "environment size " + std::to_string(width) + " x " + std::to_string(height) + " is too large");
    require(std::isfinite(strength) && strength >= 0.0f,
            "environment strength = " + fmt(strength) + " must be finite and >= 0");
    Environment e;
    e.width = width;
    e.height = height;
    e.strength = strength;
    const size_t n = static_cast<size_t>(width) * height * 3;
    for (size_t k = 0; k < n; ++k) {
        if (!(std::isfinite(rgb[k]) && rgb[k] >= 0.0f)) {
            const size_t texel = k / 3;
            throw ValidationError("environment pixel (" + std::to_string(texel % width) + ", " +
                                  std::to_string(texel / width) + ") channel " + std::to_string(k % 3) +
                                  " = " + fmt(rgb[k]) + " must be finite and >= 0");
        }
    }
    e.rgb.assign(rgb, rgb + n);
    if (rotation) {
        for (int i = 0; i < 9; ++i) {
            require(std::isfinite(rotation[i]), "environment rotation element " + std::to_string(i) + " = " +
                                                    fmt(rotation[i]) + " is not finite");
            e.rotation[static_cast<size_t>(i)] = rotation[i];
        }
        // R Rᵀ = I within float rounding: a rotation, not a scale or shear.
        for (int a = 0; a < 3; ++a) {
            for (int b = 0; b < 3; ++b) {
                float d = 0.0f;
                for (int k = 0; k < 3; ++k) d += rotation[3 * a + k] * rotation[3 * b + k];
                require(std::abs(d - (a == b ? 1.0f : 0.0f)) < 1e-4f,
                        "environment rotation is not a rotation: row " + std::to_string(a) + " · row " +
                            std::to_string(b) + " = " + fmt(d));
            }
        }
    }
    return e;
}

Transform validate_transform(const float* m, const char* what) {
    // Runs once per instance (10 000s per export): each test comes first and its message is
    // composed only when it fails.
    for (int i = 0; i < 16; ++i) {
        if (!std::isfinite(m[i])) {
            throw ValidationError(std::string(what) + " element " + std::to_string(i) + " = " + fmt(m[i]) +
                                  " is not finite");
        }
    }
    if (!(m[12] == 0.0f && m[13] == 0.0f && m[14] == 0.0f && m[15] == 1.0f))
        throw ValidationError(std::string(what) + " is not affine: its last row must be (0, 0, 0, 1)");
    // Bounds of scene/scene_limits.h: no ray of the scene can leave Embree's valid range.
    for (int row = 0; row < 3; ++row) {
        for (int col = 0; col < 3; ++col) {
            const float v = m[4 * row + col];
            if (!(std::abs(v) <= kMaxLinear)) {
                throw ValidationError(std::string(what) + " element " + std::to_string(4 * row + col) +
                                      " = " + fmt(v) + " is beyond the largest scale " + fmt(kMaxLinear));
            }
        }
    }
    const float t[3] = {m[3], m[7], m[11]};
    if (!(std::abs(t[0]) <= kMaxCoordinate && std::abs(t[1]) <= kMaxCoordinate &&
          std::abs(t[2]) <= kMaxCoordinate)) {
        throw ValidationError(std::string(what) + " places its origin at " + triple(t) + ", more than " +
                              fmt(kMaxCoordinate) + " from the world origin");
    }
    return Transform::from_row_major(m);
}

Material validate_material(const StratumMaterialDesc& d) {
    require(find_closure_model(d.model) != nullptr,
            "material model " + std::to_string(d.model) + " is not a StratumMaterialModel");
    Material m{};
    m.model = d.model;
    m.base_color = rgb_in(d.base_color, 0.0f, 1.0f, "material base_color");
    m.roughness = finite_in(d.roughness, 0.0f, 1.0f, "material roughness");
    m.metallic = finite_in(d.metallic, 0.0f, 1.0f, "material metallic");
    m.specular = finite_in(d.specular, 0.0f, 1e6f, "material specular");
    m.ior = finite_positive(d.ior, "material ior");
    m.emission = validate_radiance(d.emission, "material emission");
    require(d.distribution == STRATUM_MICROFACET_GGX || d.distribution == STRATUM_MICROFACET_MULTISCATTER_GGX,
            "material distribution " + std::to_string(d.distribution) +
                " is not a StratumMicrofacetDistribution");
    m.distribution = static_cast<MicrofacetDistribution>(d.distribution);
    m.transmission = finite_in(d.transmission, 0.0f, 1.0f, "material transmission");
    m.coat = finite_in(d.coat, 0.0f, 1e6f, "material coat");
    m.coat_roughness = finite_in(d.coat_roughness, 0.0f, 1.0f, "material coat_roughness");
    // All-zero appended fields mean "no coat" (callers written before they existed), so the
    // coat's IOR and tint are checked only where a coat is present.
    if (m.coat > 0.0f) {
        m.coat_ior = finite_positive(d.coat_ior, "material coat_ior");
        m.coat_tint = rgb_in(d.coat_tint, 0.0f, 1.0f, "material coat_tint");
    }
    require(d.bump_shadowing >= STRATUM_BUMP_SHADOWING_NONE &&
                d.bump_shadowing <= STRATUM_BUMP_SHADOWING_CONTY_UNSMOOTHED,
            "material bump_shadowing " + std::to_string(d.bump_shadowing) + " is not a StratumBumpShadowing");
    m.bump_shadowing = static_cast<BumpShadowing>(d.bump_shadowing);
    return m;
}

SceneMaterial validate_closure_material(const StratumClosureDesc* closures, uint32_t count) {
    require(closures != nullptr, "closures is NULL");
    require(count >= 1 && count <= kMaxClosures, "closure_count " + std::to_string(count) +
                                                     " is not in [1, " + std::to_string(kMaxClosures) + "]");
    SceneMaterial material;
    for (uint32_t i = 0; i < count; ++i) {
        const std::string what = "closure " + std::to_string(i);
        try {
            const Rgb weight = validate_radiance(closures[i].weight, (what + " weight").c_str());
            material.closures.push_back({weight, validate_material(closures[i].closure)});
        } catch (const ValidationError& e) {
            throw ValidationError(what + ": " + e.what());
        }
    }
    return material;
}

uint32_t validate_visibility(uint32_t bits, const char* what) {
    if ((bits & ~static_cast<uint32_t>(STRATUM_VISIBLE_ALL | STRATUM_VISIBLE_SHADOW_CATCHER)) != 0)
        throw ValidationError(std::string(what) + " = " + std::to_string(bits) +
                              " has bits outside STRATUM_VISIBLE_ALL | STRATUM_VISIBLE_SHADOW_CATCHER (63)");
    return bits;
}

uint32_t validate_lightgroup(uint32_t group, const char* what) {
    if (group > STRATUM_MAX_LIGHT_GROUPS)
        throw ValidationError(std::string(what) + " = " + std::to_string(group) +
                              " is above STRATUM_MAX_LIGHT_GROUPS (" +
                              std::to_string(STRATUM_MAX_LIGHT_GROUPS) + ")");
    return group;
}

LightParams validate_light(const StratumLightDesc& d) {
    const LightModel* model = find_light_model(d.type);
    require(model != nullptr, "light type " + std::to_string(d.type) + " is not a StratumLightType");
    LightParams l;
    l.type = d.type;
    l.color = validate_radiance(d.color, "light color");
    l.strength = finite_in(d.strength, 0.0f, std::numeric_limits<float>::max(), "light strength");
    l.radius = finite_in(d.radius, 0.0f, kMaxCoordinate, "light radius");
    l.angle = finite_in(d.angle, 0.0f, kPi, "light angle");
    if (model->check_own_params) {
        // The parameters only some types read, as given: the type's model checks and keeps those
        // it reads; the others keep LightParams' defaults.
        LightParams given = l;
        given.size_x = d.size_x;
        given.size_y = d.size_y;
        given.spot_size = d.spot_size;
        given.spot_blend = d.spot_blend;
        given.spread = d.spread;
        try {
            model->check_own_params(given, &l);
        } catch (const std::invalid_argument& e) {
            throw ValidationError(e.what());
        }
    }
    l.light_to_world = validate_transform(d.transform, "light transform");
    l.visibility = d.visibility == 0
                       ? static_cast<uint32_t>(STRATUM_VISIBLE_ALL | STRATUM_VISIBLE_SHADOW_CATCHER)
                       : validate_visibility(d.visibility, "light visibility");
    l.lightgroup = validate_lightgroup(d.lightgroup, "light lightgroup");
    return l;
}

CameraParams validate_camera(const StratumCameraDesc& d) {
    CameraParams c;
    c.lens_mm = finite_in(d.lens_mm, kMinLensMm, kMaxLensMm, "camera lens_mm");
    c.sensor_width_mm = finite_in(d.sensor_width_mm, kMinSensorMm, kMaxSensorMm, "camera sensor_width_mm");
    c.sensor_height_mm = finite_in(d.sensor_height_mm, kMinSensorMm, kMaxSensorMm, "camera sensor_height_mm");
    require(d.sensor_fit >= STRATUM_SENSOR_FIT_AUTO && d.sensor_fit <= STRATUM_SENSOR_FIT_VERTICAL,
            "camera sensor_fit " + std::to_string(d.sensor_fit) + " is not a StratumSensorFit");
    c.fit = static_cast<SensorFit>(d.sensor_fit);
    c.shift_x = finite_in(d.shift_x, -1e3f, 1e3f, "camera shift_x");
    c.shift_y = finite_in(d.shift_y, -1e3f, 1e3f, "camera shift_y");
    c.clip_start = finite_positive(d.clip_start, "camera clip_start");
    c.clip_end = finite_positive(d.clip_end, "camera clip_end");
    require(c.clip_start < c.clip_end,
            "camera clip_start = " + fmt(c.clip_start) + " must be below clip_end = " + fmt(c.clip_end));
    c.camera_to_world = validate_transform(d.transform, "camera transform");
    check_camera_frame(c.camera_to_world);
    require(d.type == STRATUM_CAMERA_PERSPECTIVE || d.type == STRATUM_CAMERA_ORTHOGRAPHIC ||
                d.type == STRATUM_CAMERA_EQUIRECTANGULAR,
            "camera type " + std::to_string(d.type) + " is not a StratumCameraType");
    c.type = static_cast<CameraType>(d.type);
    if (c.type == CameraType::Equirectangular) {
        // Blender's ranges: latitude within [-pi/2, pi/2], longitude within [-2 pi, 2 pi]
        // (a span of at most 2 pi); min = max would give a zero-width image.
        c.latitude_min = finite_in(d.latitude_min, -0.5f * kPi, 0.5f * kPi, "camera latitude_min");
        c.latitude_max = finite_in(d.latitude_max, -0.5f * kPi, 0.5f * kPi, "camera latitude_max");
        c.longitude_min = finite_in(d.longitude_min, -2.0f * kPi, 2.0f * kPi, "camera longitude_min");
        c.longitude_max = finite_in(d.longitude_max, -2.0f * kPi, 2.0f * kPi, "camera longitude_max");
        require(c.latitude_min < c.latitude_max, "camera latitude_min = " + fmt(c.latitude_min) +
                                                     " must be below latitude_max = " + fmt(c.latitude_max));
        require(c.longitude_min < c.longitude_max,
                "camera longitude_min = " + fmt(c.longitude_min) +
                    " must be below longitude_max = " + fmt(c.longitude_max));
    }
    if (c.type == CameraType::Orthographic)
        c.ortho_scale = finite_in_open(d.ortho_scale, 0.0f, kMaxCoordinate, "camera ortho_scale");
    c.aperture_radius = finite_in(d.aperture_radius, 0.0f, kMaxCoordinate, "camera aperture_radius");
    if (c.aperture_radius > 0.0f) {
        c.focus_distance = finite_in_open(d.focus_distance, 0.0f, kMaxCoordinate,
                                          "camera focus_distance (with an aperture)");
        require(d.aperture_blades == 0 || (d.aperture_blades >= 3 && d.aperture_blades <= 1000000),
                "camera aperture_blades = " + std::to_string(d.aperture_blades) +
                    " must be 0 (round) or in [3, 1000000]");
        c.aperture_blades = d.aperture_blades;
        c.aperture_rotation = finite_in(d.aperture_rotation, -1e6f, 1e6f, "camera aperture_rotation");
    }
    return c;
}

std::unique_ptr<Film> validate_film_sums(const void* bytes, size_t size) {
    require(bytes != nullptr && size > 0, "film sums are NULL or empty");
    std::string error;
    std::unique_ptr<Film> film =
        Film::from_sums_bytes(std::span<const uint8_t>(static_cast<const uint8_t*>(bytes), size), &error);
    require(film != nullptr, error);
    return film;
}

}  // namespace stratum
