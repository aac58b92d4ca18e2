// Sky Texture node (Blender's ShaderNodeTexSky): the daylight models of shading/sky_models.h.
//
// | node | modes                                             | inputs     | outputs    |
// |------|---------------------------------------------------|------------|------------|
// | sky  | 0 model (0 Preetham, 1 Hosek-Wilkie, 2 Nishita    | vector (3) | color (3)  |
// |      | Blender 3.x), 1 sun disc (Nishita: 0 off, 1 on)   |            |            |
//
// Data: Preetham and Hosek-Wilkie, the 32 coefficients the host computes as Cycles'
// SkyTextureNode::compile does (sun phi, sun theta, 3 zenith radiances, 3 x 9 configurations;
// sky_models.h); Nishita, 8 values: sun elevation, sun rotation, sun size (angular diameter),
// sun intensity, altitude (m), air, dust and ozone densities, as Blender's node holds them. The
// Nishita table (prepare) is the sky's XYZ at 512 x 128 texels and the sun's two pixels, looked
// up as Cycles' kernel/svm/sky.h (3.4) does: bilinear with clamped edges, rows at sqrt(elevation),
// the disc inside half the sun size with limb darkening 1 - 0.6 (1 - sqrt(1 - (angle/half)^2)),
// the ground below the horizon faded from the horizon's colour to black at z = -0.4.
#include <algorithm>
#include <cmath>
#include <string>

#include "shading/nodes/node_families.h"
#include "shading/sky_models.h"

namespace stratum {

namespace {

enum SkyModel : int32_t { Preetham, HosekWilkie, Nishita, SkyModelCount };

constexpr uint32_t kNishitaDataCount = 8;
constexpr float kHalfPi = 1.57079632679489661923f;
constexpr float kTwoPi = 6.28318530717958647692f;
// The Nishita table: the sun's bottom and top XYZ, its elevation, the rotation as Cycles stores
// it (2 pi - rotation wrapped to [0, 2 pi)), the disc's angular diameter (-1 without a disc), the
// intensity, then the sky texels.
constexpr size_t kHeader = 10;

std::string check_sky(const ShaderNode& n, const ShaderProgram& program) {
    std::string e = check_mode(n, 0, "model", SkyModelCount);
    if (e.empty()) e = check_mode(n, 1, "sun disc", 2);
    if (!e.empty()) return e;
    const uint32_t want = n.modes[0] == Nishita ? kNishitaDataCount : sky::kAnalyticDataCount;
    if (n.data_count != want)
        return "data_count is " + std::to_string(n.data_count) + "; the model takes " + std::to_string(want);
    const float* d = program.data.data() + n.data_offset;
    for (uint32_t i = 0; i < want; ++i)
        if (!std::isfinite(d[i])) return "data[" + std::to_string(i) + "] is not finite";
    if (n.modes[0] == Nishita) {
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

std::vector<float> prepare_sky(const ShaderNode& n, const std::vector<float>& data) {
    if (n.modes[0] != Nishita) return {};
    const float* d = data.data() + n.data_offset;
    sky::NishitaParams p;
    p.sun_elevation = d[0];
    p.sun_size = d[2];
    p.altitude = d[4];
    p.air_density = d[5];
    p.dust_density = d[6];
    p.ozone_density = d[7];
    Vec3 bottom, top;
    sky::nishita_sun_pixels(p, bottom, top);
    float rotation = std::fmod(d[1], kTwoPi);
    if (rotation < 0.0f) rotation += kTwoPi;
    std::vector<float> table = {bottom.x,
                                bottom.y,
                                bottom.z,
                                top.x,
                                top.y,
                                top.z,
                                d[0],
                                kTwoPi - rotation,
                                n.modes[1] ? std::max(d[2], 0.0005f) : -1.0f,
                                d[3]};
    const std::vector<float> sky_texels = sky::nishita_sky_table(p);
    table.insert(table.end(), sky_texels.begin(), sky_texels.end());
    return table;
}

// Bilinear lookup at (u, v) in [0, 1]^2 with clamped edges, as Cycles' CPU image lookup.
Vec3 lookup(const float* texels, float u, float v) {
    constexpr int w = sky::kNishitaWidth, h = sky::kNishitaHeight;
    const float fx = u * w - 0.5f, fy = v * h - 0.5f;
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

Rgb nishita(const std::vector<float>& table, Vec3 dir) {
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
    return sky::xyz_to_rec709(xyz);
}

void evaluate_sky(const ShaderNode& n, const ShaderEvalContext& context, ShaderRegisters& r) {
    const Vec3 dir = r.vec3(n.inputs[0]);
    Rgb c;
    switch (n.modes[0]) {
        case Preetham:
            c = sky::preetham(context.data(n), dir);
            break;
        case HosekWilkie:
            c = sky::hosek_wilkie(context.data(n), dir);
            break;
        default:
            c = nishita(context.table(n), dir);
            break;
    }
    r.set(n.outputs[0], c);
}

}  // namespace

NodeEntry sky_node_entry() { return {"sky", {3}, {3}, check_sky, prepare_sky, evaluate_sky}; }

}  // namespace stratum
