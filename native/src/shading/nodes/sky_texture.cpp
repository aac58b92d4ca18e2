// Sky Texture node (Blender's ShaderNodeTexSky): the daylight models of shading/sky_models.h.
//
// | node | modes                                             | inputs     | outputs    |
// |------|---------------------------------------------------|------------|------------|
// | sky  | 0 model (0 Preetham, 1 Hosek-Wilkie, 2 Nishita    | vector (3) | color (3)  |
// |      | Blender 3.x/4.x, 3 single scattering Blender 5.x), |            |            |
// |      | 1 sun disc (2 and 3: 0 off, 1 on), 2 XYZ matrix   |            |            |
// |      | (0 Blender 3.x, 1 4.0-4.5, 2 5.0 and later)       |            |            |
// |      | (model 4: multiple scattering, Blender 5.x)        |            |            |
//
// Data: Preetham and Hosek-Wilkie, the 32 coefficients the host computes as Cycles'
// SkyTextureNode::compile does (sun phi, sun theta, 3 zenith radiances, 3 x 9 configurations;
// sky_models.h); Nishita, 8 values: sun elevation, sun rotation, sun size (angular diameter),
// sun intensity, altitude (m), air, dust and ozone densities, as Blender's node holds them. The
// Nishita table (prepare) is the sky's XYZ at 512 x 128 texels and the sun's two pixels, looked
// up as Cycles' kernel/svm/sky.h (3.4) does: bilinear with clamped edges, rows at sqrt(elevation),
// the disc inside half the sun size with limb darkening 1 - 0.6 (1 - sqrt(1 - (angle/half)^2)),
// the ground below the horizon faded from the horizon's colour to black at z = -0.4. Model 3,
// Blender 5.x's SINGLE_SCATTERING, the same atmosphere in a 512 x 256 table over the whole
// sphere, the sun's angles wrapped as Cycles 5.0 wraps them, the disc added to the sky above the
// Earth's limb (kernel/svm/sky.h at v5.0.0). Model 4, 5.x's MULTIPLE_SCATTERING, looked up the
// same way (shading/sky_multiple_scattering.cpp builds its table).
#include <algorithm>
#include <cmath>
#include <string>

#include "shading/node_registry.h"
#include "shading/sky_models.h"

namespace stratum {

namespace {

enum SkyModel : int32_t {
    Preetham,
    HosekWilkie,
    Nishita,
    SingleScattering,
    MultipleScattering,
    SkyModelCount
};

constexpr uint32_t kNishitaDataCount = 8;
constexpr float kHalfPi = 1.57079632679489661923f;
constexpr float kTwoPi = 6.28318530717958647692f;
// The Nishita tables: the sun's bottom and top XYZ, its elevation, the rotation as Cycles stores
// it (2 pi - rotation wrapped to [0, 2 pi)), the disc's angular diameter (-1 without a disc), the
// intensity, minus the Earth's intersection angle (5.x), then the sky texels.
constexpr size_t kHeader = 11;

std::string check_sky(const ShaderNode& n, const ShaderProgram& program) {
    std::string e = check_mode(n, 0, "model", SkyModelCount);
    if (e.empty()) e = check_mode(n, 1, "sun disc", 2);
    if (e.empty()) e = check_mode(n, 2, "xyz matrix", 3);
    if (!e.empty()) return e;
    const bool scattering = n.modes[0] >= Nishita;
    const uint32_t want = scattering ? kNishitaDataCount : sky::kAnalyticDataCount;
    if (n.data_count != want)
        return "data_count is " + std::to_string(n.data_count) + "; the model takes " + std::to_string(want);
    const float* d = program.data.data() + n.data_offset;
    for (uint32_t i = 0; i < want; ++i)
        if (!std::isfinite(d[i])) return "data[" + std::to_string(i) + "] is not finite";
    if (scattering) {
        // Blender's limits (the sun's angles are unbounded: the node wraps them).
        if (d[2] < 0.0f || d[2] > kHalfPi) return "data[2] (sun size) is outside [0, pi/2]";
        if (d[3] < 0.0f || d[3] > 1e6f) return "data[3] (sun intensity) is outside [0, 1e6]";
        if (d[4] < 0.0f || d[4] > 1e5f) return "data[4] (altitude) is outside [0, 1e5] m";
        for (int i = 5; i < 8; ++i)
            if (d[i] < 0.0f || d[i] > 10.0f)
                return "data[" + std::to_string(i) + "] (air/dust/ozone density) is outside [0, 10]";
        if (std::fabs(d[0]) > 1e4f || std::fabs(d[1]) > 1e4f) return "sun elevation or rotation exceeds 1e4";
    }
    return "";
}

// Cycles 5.x's SkyTextureNode::simplify_settings: the elevation into [-pi/2, pi/2] (past a pole
// the sun comes down on the other side), the rotation to 2 pi - rotation in [0, 2 pi).
void wrap_sun(float& elevation, float& rotation) {
    elevation = std::fmod(elevation, kTwoPi);
    if (std::fabs(elevation) >= kPi) elevation -= std::copysign(2.0f, elevation) * kPi;
    if (elevation >= kHalfPi || elevation <= -kHalfPi) {
        elevation = std::copysign(kPi, elevation) - elevation;
        rotation += kPi;
    }
}

std::vector<float> prepare_sky(const ShaderNode& n, const std::vector<float>& data) {
    if (n.modes[0] < Nishita) return {};
    const bool v5 = n.modes[0] >= SingleScattering;
    const bool multiple = n.modes[0] == MultipleScattering;
    const float* d = data.data() + n.data_offset;
    float elevation = d[0], rotation = d[1];
    if (v5) wrap_sun(elevation, rotation);
    sky::NishitaParams p;
    p.sun_elevation = elevation;
    p.sun_size = d[2];
    p.altitude = d[4];
    p.air_density = d[5];
    p.dust_density = d[6];
    p.ozone_density = d[7];
    Vec3 bottom, top;
    if (multiple)
        sky::multiple_scattering_sun_pixels(p, bottom, top);
    else
        sky::nishita_sun_pixels(p, bottom, top);
    const float size = std::max(d[2], 0.0005f);
    // 5.x single scattering: a set sun is black (multiple scattering keeps the pixels).
    if (n.modes[0] == SingleScattering && !(elevation + size / 2.0f > 0.0f)) bottom = top = Vec3();
    rotation = std::fmod(rotation, kTwoPi);
    if (rotation < 0.0f) rotation += kTwoPi;
    std::vector<float> table = {bottom.x,
                                bottom.y,
                                bottom.z,
                                top.x,
                                top.y,
                                top.z,
                                elevation,
                                kTwoPi - rotation,
                                n.modes[1] ? size : -1.0f,
                                d[3],
                                v5 ? -sky::earth_intersection_angle(d[4]) : 0.0f};
    const std::vector<float> texels =
        multiple ? sky::multiple_scattering_table(p)
                 : (v5 ? sky::single_scattering_table(p) : sky::nishita_sky_table(p));
    table.insert(table.end(), texels.begin(), texels.end());
    return table;
}

// Bilinear lookup at (u, v) in [0, 1]^2 with clamped edges, as Cycles' CPU image lookup.
Vec3 lookup(const float* texels, float u, float v, int h = sky::kNishitaHeight) {
    constexpr int w = sky::kNishitaWidth;
    const float fx = u * w - 0.5f, fy = v * static_cast<float>(h) - 0.5f;
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float tx = fx - x0f, ty = fy - y0f;
    const int x0 = static_cast<int>(x0f), y0 = static_cast<int>(y0f);
    const int xa = std::clamp(x0, 0, w - 1), xb = std::clamp(x0 + 1, 0, w - 1);
    const int ya = std::clamp(y0, 0, h - 1), yb = std::clamp(y0 + 1, 0, h - 1);
    const auto at = [&](int x, int y) {
        const float* t = texels + (static_cast<size_t>(y) * w + x) * 3;
        return Vec3(t[0], t[1], t[2]);
    };
    return (at(xa, ya) * (1.0f - tx) + at(xb, ya) * tx) * (1.0f - ty) +
           (at(xa, yb) * (1.0f - tx) + at(xb, yb) * tx) * ty;
}

float angle_between(Vec3 a, Vec3 b) { return 2.0f * std::atan2(length(a - b), length(a + b)); }

Rgb nishita(const std::vector<float>& table, Vec3 dir, sky::XyzMatrix matrix) {
    const Vec3 bottom(table[0], table[1], table[2]), top(table[3], table[4], table[5]);
    const float elevation = table[6], rotation = table[7], diameter = table[8], intensity = table[9];
    const float* texels = table.data() + kHeader;
    const float theta = std::acos(std::clamp(dir.z, -1.0f, 1.0f));
    const float phi = std::atan2(dir.x, dir.y);
    float u = (phi + kPi + rotation) / kTwoPi;
    if (u > 1.0f) u -= 1.0f;
    Vec3 xyz;
    if (dir.z >= 0.0f) {
        const float lon = rotation + kHalfPi;
        const Vec3 sun(std::cos(elevation) * std::cos(lon), std::cos(elevation) * std::sin(lon),
                       std::sin(elevation));
        const float angle = angle_between(dir, sun);
        const float half = diameter / 2.0f;
        const float dir_elevation = kHalfPi - theta;
        if (diameter >= 0.0f && angle < half) {
            // Across the disc from its lowest to its highest pixel (from the horizon when it sets).
            if (elevation + half > 0.0f) {
                const float t = elevation - half > 0.0f ? (dir_elevation - elevation) / diameter + 0.5f
                                                        : dir_elevation / (elevation + half);
                xyz = (bottom + (top - bottom) * t) * intensity;
            }
            const float r = angle / half;
            xyz *= 1.0f - 0.6f * (1.0f - std::sqrt(1.0f - r * r));
        } else {
            xyz = lookup(texels, u, std::sqrt(std::max(dir_elevation / kHalfPi, 0.0f)));
        }
    } else if (dir.z >= -0.4f) {
        const float f = 1.0f + dir.z * 2.5f;
        xyz = lookup(texels, u, -0.5f) * (f * f * f);
    }
    return sky::xyz_to_rec709(xyz, matrix);
}

// Blender 5.x (kernel/svm/sky.h): the sky over the whole sphere, the disc added to it above the
// Earth's limb.
Rgb single_scattering(const std::vector<float>& table, Vec3 dir, sky::XyzMatrix matrix) {
    const Vec3 bottom(table[0], table[1], table[2]), top(table[3], table[4], table[5]);
    const float elevation = table[6], rotation = table[7], diameter = table[8], intensity = table[9];
    const float earth_angle = table[10];
    const float theta = std::acos(std::clamp(dir.z, -1.0f, 1.0f));
    const float phi = std::atan2(dir.y, dir.x);
    const float st = std::sin(elevation - kHalfPi);
    const Vec3 sun(st * std::cos(rotation - kHalfPi), st * std::sin(rotation - kHalfPi),
                   std::cos(elevation - kHalfPi));
    const float angle = angle_between(dir, sun);
    const float half = diameter * 0.5f;
    const float dir_elevation = kHalfPi - theta;
    Vec3 xyz;
    if (diameter >= 0.0f && angle < half && dir_elevation > earth_angle) {
        const float t = (dir_elevation - elevation) / diameter + 0.5f;
        const float r = angle / half;
        const float limb = 1.0f - 0.6f * (1.0f - std::sqrt(1.0f - r * r));
        xyz = (bottom + (top - bottom) * t) * intensity * limb;
    }
    float u = (-phi - kHalfPi + rotation) * (1.0f / kTwoPi);
    u -= std::floor(u);
    const float v =
        std::copysign(std::sqrt(std::fabs(dir_elevation) * (2.0f / kPi)), dir_elevation) * 0.5f + 0.5f;
    xyz += lookup(table.data() + kHeader, u, v, sky::kSingleScatteringHeight);
    return sky::xyz_to_rec709(xyz, matrix);
}

void evaluate_sky(const ShaderNode& n, const ShaderEvalContext& context, ShaderRegisters& r) {
    const Vec3 dir = r.vec3(n.inputs[0]);
    // Cycles converts every model through its film's XYZ -> scene linear (xyz_to_rgb_clamped).
    const auto matrix = static_cast<sky::XyzMatrix>(n.modes[2]);
    Rgb c;
    switch (n.modes[0]) {
        case Preetham:
            c = sky::preetham(context.data(n), dir, matrix);
            break;
        case HosekWilkie:
            c = sky::hosek_wilkie(context.data(n), dir, matrix);
            break;
        case Nishita:
            c = nishita(context.table(n), dir, matrix);
            break;
        default:
            c = single_scattering(context.table(n), dir, matrix);
            break;
    }
    r.set(n.outputs[0], c);
}

}  // namespace

const NodeRegistration kSkyNode{{.value = 28,
                                 .name = "sky",
                                 .input_widths = {3},
                                 .output_widths = {3},
                                 .check = check_sky,
                                 .prepare = prepare_sky,
                                 .evaluate = evaluate_sky}};

}  // namespace stratum
