// Blender 5.x's MULTIPLE_SCATTERING sky (intern/sky sky_multiple_scattering.cpp, Cycles'
// third_party/sky at v5.0.0): four wavelengths (630, 560, 490, 430 nm), molecules, ozone and
// aerosols with measured profiles, single scattering marched in 64 steps with the energy-conserving
// step integral of Hillaire ("Physically Based Sky, Atmosphere and Cloud Rendering in Frostbite",
// 2016), transmittance to the sun from a 256 x 64 table, and multiple scattering as a fitted term
// plus light the ground (albedo 0.3) reflects. Lengths in km.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "shading/sky_models.h"

namespace stratum::sky {

namespace {

using Spectrum4 = std::array<float, 4>;

constexpr float kEarthKm = 6371.0f;
constexpr float kThicknessKm = 100.0f;
constexpr float kTopKm = kEarthKm + kThicknessKm;
constexpr float kGroundAlbedo = 0.3f;
constexpr float kInv4Pi4 = 0.07957747154594766788f;
constexpr float kRayleighPhaseScale = (3.0f / 16.0f) * 0.31830988618379067154f;
constexpr float kAerosolG = 0.8f;
constexpr int kTransmittanceSteps = 64;
constexpr int kInscatteringSteps = 64;
constexpr int kLutX = 256, kLutY = 64;

constexpr Spectrum4 kSunIrradiance = {1.679f, 1.828f, 1.986f, 1.307f};
constexpr Spectrum4 kMolecularScattering = {6.605e-3f, 1.067e-2f, 1.842e-2f, 3.156e-2f};
constexpr Spectrum4 kOzoneCrossSection = {3.472e-25f, 3.914e-25f, 1.349e-25f, 11.03e-27f};
constexpr float kOzoneDobson = 334.5f;
constexpr Spectrum4 kAerosolAbsorption = {2.8722e-24f, 4.6168e-24f, 7.9706e-24f, 1.3578e-23f};
constexpr Spectrum4 kAerosolScattering = {1.5908e-22f, 1.7711e-22f, 2.0942e-22f, 2.4033e-22f};
constexpr float kAerosolBase = 1.3681e20f, kAerosolBackground = 2e6f, kAerosolScaleHeight = 0.73f;
// The four wavelengths' contributions to X, Y, Z.
constexpr std::array<std::array<float, 3>, 4> kToXyz = {
    {{53.386917738564668023f, 22.981337506691024754f, 0.0f},
     {43.904844466369358263f, 71.347795700053393866f, 0.102506867965741307f},
     {1.6137278251608962005f, 18.422960591455485011f, 31.742921188390805758f},
     {20.762668673810577145f, 2.3614213523314368527f, 110.48009643252140334f}}};

Spectrum4 operator*(Spectrum4 a, float s) { return {a[0] * s, a[1] * s, a[2] * s, a[3] * s}; }
Spectrum4 operator*(Spectrum4 a, Spectrum4 b) { return {a[0] * b[0], a[1] * b[1], a[2] * b[2], a[3] * b[3]}; }
Spectrum4 operator+(Spectrum4 a, Spectrum4 b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2], a[3] + b[3]}; }
Spectrum4 operator-(Spectrum4 a, Spectrum4 b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2], a[3] - b[3]}; }
Spectrum4 operator/(Spectrum4 a, Spectrum4 b) { return {a[0] / b[0], a[1] / b[1], a[2] / b[2], a[3] / b[3]}; }
Spectrum4 exp4(Spectrum4 a) { return {std::exp(a[0]), std::exp(a[1]), std::exp(a[2]), std::exp(a[3])}; }
Spectrum4 lerp4(Spectrum4 a, Spectrum4 b, float t) { return a + (b - a) * t; }

Vec3 to_xyz(Spectrum4 l) {
    Vec3 xyz;
    for (int i = 0; i < 4; ++i) xyz += Vec3(kToXyz[i][0], kToXyz[i][1], kToXyz[i][2]) * l[i];
    return xyz;
}

Vec3 sun_at(float cos_zenith) { return {-std::sqrt(1.0f - cos_zenith * cos_zenith), 0.0f, cos_zenith}; }

// Distance along `dir` from `pos` to the sphere of `radius` (the far side from inside), or -1.
float sphere_distance(Vec3 pos, Vec3 dir, float radius) {
    const float b = dot(pos, dir);
    const float c = dot(pos, pos) - radius * radius;
    if (c > 0.0f && b > 0.0f) return -1.0f;
    const float d = b * b - c;
    if (d < 0.0f) return -1.0f;
    return d >= b * b ? -b + std::sqrt(d) : -b - std::sqrt(d);
}

class Atmosphere {
public:
    Atmosphere(float air, float aerosol, float ozone) : air_(air), aerosol_(aerosol), ozone_(ozone) {}

    Spectrum4 transmittance(float cos_zenith, float normalized_altitude) const {
        const Vec3 dir = sun_at(cos_zenith);
        const Vec3 origin(0.0f, 0.0f, kEarthKm + (kTopKm - kEarthKm) * normalized_altitude);
        const float step = sphere_distance(origin, dir, kTopKm) / kTransmittanceSteps;
        Spectrum4 depth{};
        for (int i = 0; i < kTransmittanceSteps; ++i) {
            const Vec3 at = origin + dir * ((static_cast<float>(i) + 0.5f) * step);
            depth = depth + extinction(std::max(length(at) - kEarthKm, 0.0f)) * step;
        }
        return exp4(depth * -1.0f);
    }

    void build_table() {
        table_.resize(static_cast<size_t>(kLutX) * kLutY);
        tbb::parallel_for(0, kLutY, [&](int y) {
            for (int x = 0; x < kLutX; ++x)
                table_[static_cast<size_t>(y) * kLutX + x] =
                    transmittance(static_cast<float>(x) / float(kLutX - 1) * 2.0f - 1.0f,
                                  static_cast<float>(y) / float(kLutY - 1));
        });
    }

    Spectrum4 inscattering(Vec3 sun, Vec3 origin, Vec3 dir, float distance) const {
        const float mu = dot(-dir, sun);
        const float phase_m = kRayleighPhaseScale * (1.0f + mu * mu);
        const float den = 1.0f + kAerosolG * kAerosolG + 2.0f * kAerosolG * mu;
        const float phase_a = kInv4Pi4 * (1.0f - kAerosolG * kAerosolG) / (den * std::sqrt(den));
        const float dt = distance / kInscatteringSteps;
        Spectrum4 radiance{}, through{1.0f, 1.0f, 1.0f, 1.0f};
        for (int i = 0; i < kInscatteringSteps; ++i) {
            const Vec3 at = origin + dir * ((static_cast<float>(i) + 0.5f) * dt);
            const float r = length(at);
            const float altitude = std::max(r - kEarthKm, 0.0f);
            const float h = altitude / kThicknessKm;
            const float cos_sun = dot(at / r, sun);
            Spectrum4 aer_abs, aer_sca, mol_abs, mol_sca;
            coefficients(altitude, aer_abs, aer_sca, mol_abs, mol_sca);
            const Spectrum4 ext = aer_abs + aer_sca + mol_abs + mol_sca;
            const Spectrum4 to_sun = lookup(cos_sun, h);
            const Spectrum4 ms = multiple(cos_sun, h, r);
            const Spectrum4 source =
                kSunIrradiance * (mol_sca * (to_sun * phase_m + ms) + aer_sca * (to_sun * phase_a + ms));
            const Spectrum4 step_t = exp4(ext * -dt);
            Spectrum4 cut;
            for (int k = 0; k < 4; ++k) cut[k] = std::fmax(ext[k], 1e-7f);
            radiance = radiance + through * ((source - source * step_t) / cut);
            through = through * step_t;
        }
        return radiance;
    }

private:
    void coefficients(float altitude, Spectrum4& aer_abs, Spectrum4& aer_sca, Spectrum4& mol_abs,
                      Spectrum4& mol_sca) const {
        const float aerosol =
            kAerosolBase * (std::exp(-altitude / kAerosolScaleHeight) + kAerosolBackground / kAerosolBase) *
            aerosol_;
        aer_abs = kAerosolAbsorption * aerosol;
        aer_sca = kAerosolScattering * aerosol;
        const float log_h = std::log(std::fmax(altitude, 1e-4f));
        const float d = log_h - 3.22261f;
        const float ozone = 3.78547397e20f * std::exp(-(d * d) * 5.55555555f - log_h);
        mol_abs = kOzoneCrossSection * kOzoneDobson * ozone * ozone_;
        mol_sca = kMolecularScattering * std::exp(-0.07771971f * std::pow(altitude, 1.16364243f)) * air_;
    }
    Spectrum4 extinction(float altitude) const {
        Spectrum4 a, b, c, d;
        coefficients(altitude, a, b, c, d);
        return a + b + c + d;
    }
    const Spectrum4& at(int x, int y) const { return table_[static_cast<size_t>(y) * kLutX + x]; }
    Spectrum4 lookup(float cos_zenith, float h) const {
        const float x = float(kLutX - 1) * std::clamp(cos_zenith * 0.5f + 0.5f, 0.0f, 1.0f);
        const float y = float(kLutY - 1) * std::clamp(h, 0.0f, 1.0f);
        const int x1 = static_cast<int>(x), y1 = static_cast<int>(y);
        const int x2 = std::min(x1 + 1, kLutX - 1), y2 = std::min(y1 + 1, kLutY - 1);
        const float fx = x - static_cast<float>(x1), fy = y - static_cast<float>(y1);
        return lerp4(lerp4(at(x1, y1), at(x2, y1), fx), lerp4(at(x1, y2), at(x2, y2), fx), fy);
    }
    Spectrum4 at_ground(float cos_zenith) const {
        const float x = float(kLutX - 1) * std::clamp(cos_zenith * 0.5f + 0.5f, 0.0f, 1.0f);
        const int x1 = static_cast<int>(x), x2 = std::min(x1 + 1, kLutX - 1);
        return lerp4(at(x1, 0), at(x2, 0), x - static_cast<float>(x1));
    }
    Spectrum4 straight_up(float h) const {
        const float y = float(kLutY - 1) * std::clamp(h, 0.0f, 1.0f);
        const int y1 = static_cast<int>(y), y2 = std::min(y1 + 1, kLutY - 1);
        return lerp4(at(kLutX - 1, y1), at(kLutX - 1, y2), y - static_cast<float>(y1));
    }
    // Higher orders: the fitted term for the rest of the atmosphere and the ground's bounce.
    Spectrum4 multiple(float cos_sun, float h, float r) const {
        const float q = kEarthKm / r;
        const float omega = 2.0f * kPi * (1.0f - std::sqrt(std::max(1.0f - q * q, 0.0f)));
        const Spectrum4 ground_to_sample = straight_up(0.0f) / straight_up(h);
        const Spectrum4 ground = at_ground(cos_sun) * ground_to_sample *
                                 (kInv4Pi4 * omega * (kGroundAlbedo * 0.31830988618379067154f) * cos_sun);
        const float fit = 0.02f * (1.0f / (1.0f + 5.0f * std::exp(-17.92f * cos_sun)));
        const Spectrum4 rest = Spectrum4{0.217f, 0.347f, 0.594f, 1.0f} * fit;
        return rest + ground;
    }

    float air_, aerosol_, ozone_;
    std::vector<Spectrum4> table_;
};

}  // namespace

std::vector<float> multiple_scattering_table(const NishitaParams& p) {
    constexpr int w = kNishitaWidth, h = kSingleScatteringHeight;
    Atmosphere atmosphere(p.air_density, p.dust_density, p.ozone_density);
    atmosphere.build_table();
    const float altitude_km = std::clamp(p.altitude, 1.0f, 99999.0f) / 1000.0f;
    const Vec3 sun = sun_at(std::cos(kPi / 2.0f - p.sun_elevation));
    const Vec3 origin(0.0f, 0.0f, kEarthKm + altitude_km);
    std::vector<float> table(static_cast<size_t>(w) * h * 3, 0.0f);
    tbb::parallel_for(0, h, [&](int y) {
        float* row = table.data() + static_cast<size_t>(y) * w * 3;
        for (int x = 0; x < w / 2; ++x) {
            const float azimuth = 2.0f * kPi * ((static_cast<float>(x) + 0.5f) / float(w));
            const float l = ((static_cast<float>(y) + 0.5f) / float(h)) * 2.0f - 1.0f;
            const float elevation = std::copysign(l * l, l) * (kPi / 2.0f);
            const Vec3 dir(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                           std::sin(elevation));
            const float to_top = sphere_distance(origin, dir, kTopKm);
            const float to_ground = sphere_distance(origin, dir, kEarthKm);
            const Vec3 xyz =
                to_xyz(atmosphere.inscattering(sun, origin, dir, to_ground < 0.0f ? to_top : to_ground));
            for (int side : {x, w - 1 - x}) {
                row[side * 3] = xyz.x;
                row[side * 3 + 1] = xyz.y;
                row[side * 3 + 2] = xyz.z;
            }
        }
    });
    return table;
}

void multiple_scattering_sun_pixels(const NishitaParams& p, Vec3& bottom, Vec3& top) {
    const Atmosphere atmosphere(p.air_density, p.dust_density, p.ozone_density);
    const float altitude_km = std::clamp(p.altitude, 1.0f, 99999.0f) / 1000.0f;
    const float half = std::max(p.sun_size, 0.0005f) / 2.0f;
    const float solid_angle = 2.0f * kPi * (1.0f - std::cos(half));
    const auto radiance = [&](float elevation) {
        const Spectrum4 t =
            atmosphere.transmittance(std::cos(kPi / 2.0f - elevation), altitude_km / kThicknessKm);
        return to_xyz(kSunIrradiance * t * (1.0f / solid_angle));
    };
    bottom = radiance(p.sun_elevation - half);
    top = radiance(p.sun_elevation + half);
}

}  // namespace stratum::sky
