#include "shading/sky_models.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace stratum::sky {

namespace {

constexpr float kHalfPi = 1.57079632679489661923f;
constexpr float kTwoPi = 6.28318530717958647692f;

// ---- Preetham and Hosek-Wilkie ------------------------------------------------------------------

// Spherical angles of a direction as Cycles' direction_to_spherical (3.4): theta from +Z, phi =
// atan2(x, y). (5.0 measures phi as atan2(y, x) and then uses pi/2 minus it: the same angle.)
float safe_acos(float v) { return std::acos(std::clamp(v, -1.0f, 1.0f)); }

// Angle between the direction (theta, phi) and the sun (sun_theta, sun_phi).
float angle_to_sun(float theta, float phi, float sun_theta, float sun_phi) {
    const float c = std::sin(theta) * std::sin(sun_theta) * std::cos(sun_phi - phi) +
                    std::cos(theta) * std::cos(sun_theta);
    return safe_acos(c);
}

// Perez et al.'s luminance distribution, five coefficients.
float perez(const float* k, float theta, float gamma) {
    const float cg = std::cos(gamma);
    return (1.0f + k[0] * std::exp(k[1] / std::cos(theta))) *
           (1.0f + k[2] * std::exp(k[3] * gamma) + k[4] * cg * cg);
}

// Hosek-Wilkie's extended Perez form, nine coefficients.
float hosek_channel(const float* k, float theta, float gamma) {
    const float ct = std::cos(theta);
    const float cg = std::cos(gamma);
    const float rayleigh = cg * cg;
    const float mie = (1.0f + rayleigh) / std::pow(1.0f + k[8] * k[8] - 2.0f * k[8] * cg, 1.5f);
    const float glow = std::exp(k[4] * gamma);
    return (1.0f + k[0] * std::exp(k[1] / (ct + 0.01f))) *
           (k[2] + k[3] * glow + k[5] * rayleigh + k[6] * mie + k[7] * std::sqrt(ct));
}

// (theta clamped above the horizon, gamma) of `dir` for the sun in `data`.
void analytic_angles(const float* data, Vec3 dir, float& theta, float& gamma) {
    theta = safe_acos(dir.z);
    const float phi = std::atan2(dir.x, dir.y);
    gamma = angle_to_sun(theta, phi, data[1], data[0]);
    theta = std::min(theta, kHalfPi - 0.001f);
}

// ---- Nishita (Blender 3.x intern/sky) -----------------------------------------------------------

constexpr float kRayleighScaleHeight = 8e3f;  // m
constexpr float kMieScaleHeight = 1.2e3f;     // m
constexpr float kMieScattering = 2e-5f;       // m^-1
constexpr float kMieExtinctionRatio = 1.11f;  // Mie extinction over scattering
constexpr float kMieG = 0.76f;                // aerosols' anisotropy
constexpr float kEarthRadius = 6360e3f;       // m
constexpr float kAtmosphereRadius = 6420e3f;  // m
constexpr int kViewSteps = 32;
constexpr int kWavelengths = 21;  // 380 to 780 nm every 20 nm
constexpr float kWavelengthStep = 20.0f;

// Solar irradiance at the top of the atmosphere (W m^-2 nm^-1), per sampled wavelength.
constexpr std::array<float, kWavelengths> kSolarIrradiance = {
    1.45756829855592995315f, 1.56596305559738380175f, 1.65148449067670455293f, 1.71496242737209314555f,
    1.75797983805020541226f, 1.78256407885924539336f, 1.79095108475838560302f, 1.78541550133410664714f,
    1.76815554864306845317f, 1.74122069647250410362f, 1.70647127164943679389f, 1.66556087452739887134f,
    1.61993437242451854274f, 1.57083597368892080581f, 1.51932335059305478886f, 1.46628494965214395407f,
    1.41245852740172450623f, 1.35844961970384092709f, 1.30474913844739281998f, 1.25174963272610817455f,
    1.19975998755420620867f};
// Rayleigh scattering coefficient at sea level (m^-1).
constexpr std::array<float, kWavelengths> kRayleighScattering = {
    0.00005424820087636473f, 0.00004418549866505454f, 0.00003635151910165377f, 0.00003017929012024763f,
    0.00002526320226989157f, 0.00002130859310621843f, 0.00001809838025320633f, 0.00001547057129129042f,
    0.00001330284977336850f, 0.00001150184784075764f, 0.00000999557429990163f, 0.00000872799973630707f,
    0.00000765513700977967f, 0.00000674217203751443f, 0.00000596134125832052f, 0.00000529034598065810f,
    0.00000471115687557433f, 0.00000420910481110487f, 0.00000377218381260133f, 0.00000339051255477280f,
    0.00000305591531679811f};
// Ozone absorption coefficient at its peak density (m^-1).
constexpr std::array<float, kWavelengths> kOzoneAbsorption = {
    0.00000000325126849861f, 0.00000000585395365047f, 0.00000001977191155085f, 0.00000007309568762914f,
    0.00000020084561514287f, 0.00000040383958096161f, 0.00000063551335912363f, 0.00000096707041180970f,
    0.00000154797400424410f, 0.00000209038647223331f, 0.00000246128056164565f, 0.00000273551299461512f,
    0.00000215125863128643f, 0.00000159051840791988f, 0.00000112356197979857f, 0.00000073527551487574f,
    0.00000046450130357806f, 0.00000033096079921048f, 0.00000022512612292678f, 0.00000014879129266490f,
    0.00000016828623364192f};
// CIE 1931 colour matching functions x, y, z at the sampled wavelengths.
constexpr std::array<std::array<float, 3>, kWavelengths> kColorMatching = {{
    {0.00136800000f, 0.00003900000f, 0.00645000100f}, {0.01431000000f, 0.00039600000f, 0.06785001000f},
    {0.13438000000f, 0.00400000000f, 0.64560000000f}, {0.34828000000f, 0.02300000000f, 1.74706000000f},
    {0.29080000000f, 0.06000000000f, 1.66920000000f}, {0.09564000000f, 0.13902000000f, 0.81295010000f},
    {0.00490000000f, 0.32300000000f, 0.27200000000f}, {0.06327000000f, 0.71000000000f, 0.07824999000f},
    {0.29040000000f, 0.95400000000f, 0.02030000000f}, {0.59450000000f, 0.99500000000f, 0.00390000000f},
    {0.91630000000f, 0.87000000000f, 0.00165000100f}, {1.06220000000f, 0.63100000000f, 0.00080000000f},
    {0.85444990000f, 0.38100000000f, 0.00019000000f}, {0.44790000000f, 0.17500000000f, 0.00002000000f},
    {0.16490000000f, 0.06100000000f, 0.00000000000f}, {0.04677000000f, 0.01700000000f, 0.00000000000f},
    {0.01135916000f, 0.00410200000f, 0.00000000000f}, {0.00289932700f, 0.00104700000f, 0.00000000000f},
    {0.00069007860f, 0.00024920000f, 0.00000000000f}, {0.00016615050f, 0.00006000000f, 0.00000000000f},
    {0.00004150994f, 0.00001499000f, 0.00000000000f},
}};

using Spectrum = std::array<float, kWavelengths>;

Vec3 from_latitude_longitude(float latitude, float longitude) {
    return {std::cos(latitude) * std::cos(longitude), std::cos(latitude) * std::sin(longitude),
            std::sin(latitude)};
}

Vec3 spectrum_to_xyz(const Spectrum& s) {
    Vec3 xyz;
    for (int i = 0; i < kWavelengths; ++i) {
        xyz.x += kColorMatching[i][0] * s[i];
        xyz.y += kColorMatching[i][1] * s[i];
        xyz.z += kColorMatching[i][2] * s[i];
    }
    return xyz * kWavelengthStep;
}

// Relative densities (Rayleigh, Mie, ozone) at `height` metres above sea level. Ozone is a tent
// between 10 and 40 km peaking at 25 km.
Vec3 densities(float height) {
    float ozone = 0.0f;
    if (height >= 10000.0f && height < 25000.0f)
        ozone = height * (1.0f / 15000.0f) - 2.0f / 3.0f;
    else if (height >= 25000.0f && height < 40000.0f)
        ozone = -(height * (1.0f / 15000.0f) - 8.0f / 3.0f);
    return {std::exp(-height / kRayleighScaleHeight), std::exp(-height / kMieScaleHeight), ozone};
}

float rayleigh_phase(float mu) { return 3.0f / (16.0f * kPi) * (1.0f + mu * mu); }

float mie_phase(float mu) {  // Cornette-Shanks
    const float g2 = kMieG * kMieG;
    return (3.0f * (1.0f - g2) * (1.0f + mu * mu)) /
           (8.0f * kPi * (2.0f + g2) * std::pow(1.0f + g2 - 2.0f * kMieG * mu, 1.5f));
}

// Whether the ray from `p` along `d` meets the ground (only rays going down can).
bool hits_ground(Vec3 p, Vec3 d) {
    if (d.z >= 0.0f) return false;
    const float b = -2.0f * dot(d, -p);
    const float c = dot(p, p) - kEarthRadius * kEarthRadius;
    return b * b - 4.0f * c >= 0.0f;
}

// Where the ray from `p` (inside the atmosphere) along `d` leaves it.
Vec3 atmosphere_exit(Vec3 p, Vec3 d) {
    const float b = -2.0f * dot(d, -p);
    const float c = dot(p, p) - kAtmosphereRadius * kAtmosphereRadius;
    const float t = (-b + std::sqrt(b * b - 4.0f * c)) / 2.0f;
    return {p.x + d.x * t, p.y + d.y * t, p.z + d.z * t};
}

// Optical depth factors (Rayleigh, Mie, ozone densities integrated over metres) from `p` to the
// top of the atmosphere along `d`. Blender's intern/sky (3.0 and later; Cycles' own copy at
// v3.4.0 still marches 16 midpoints, but Blender builds with intern/sky) integrates with an 8-node
// Gauss-Laguerre rule: the densities fall roughly exponentially along the ray, so the rule for
// integral of f(x) exp(-x) over [0, inf), its nodes scaled by 1/25 to stay inside the atmosphere
// and exp(x_i)/25 folded into the weights, is exact for a density e^(-25 t).
constexpr std::array<float, 8> kLaguerreNodes = {0.006811185292f, 0.03614807107f, 0.09004346519f,
                                                 0.1706680068f,   0.2818362161f,  0.4303406404f,
                                                 0.6296271457f,   0.9145252695f};
constexpr std::array<float, 8> kLaguerreWeights = {0.01750893642f, 0.04135477391f, 0.06678839063f,
                                                   0.09507698807f, 0.1283416365f,  0.1707430204f,
                                                   0.2327233347f,  0.3562490486f};

Vec3 optical_depth_to_space(Vec3 p, Vec3 d) {
    const float length_m = length(atmosphere_exit(p, d) - p);
    const Vec3 ray = d * length_m;
    Vec3 depth;
    for (size_t i = 0; i < kLaguerreNodes.size(); ++i) {
        const Vec3 at = p + ray * kLaguerreNodes[i];
        depth += densities(length(at) - kEarthRadius) * kLaguerreWeights[i];
    }
    return depth * length_m;
}

// Single scattering of sunlight into the ray from `origin` along `dir`, per wavelength.
void single_scattering(Vec3 dir, Vec3 sun, Vec3 origin, Vec3 scale, Spectrum& out) {
    const float length_m = length(atmosphere_exit(origin, dir) - origin);
    const float step = length_m / kViewSteps;
    const Vec3 segment = dir * step;
    out.fill(0.0f);
    const float mu = dot(dir, sun);
    const float phase_r = rayleigh_phase(mu), phase_m = mie_phase(mu);
    Vec3 depth;  // optical depth factors from the origin, densities scaled
    Vec3 at = origin + segment * 0.5f;
    for (int i = 0; i < kViewSteps; ++i) {
        const Vec3 rel = densities(length(at) - kEarthRadius);
        const Vec3 density(scale.x * rel.x, scale.y * rel.y, scale.z * rel.z);
        depth += density * step;
        if (!hits_ground(at, sun)) {
            const Vec3 to_sun = optical_depth_to_space(at, sun);
            const Vec3 total(depth.x + scale.x * to_sun.x, depth.y + scale.y * to_sun.y,
                             depth.z + scale.z * to_sun.z);
            for (int w = 0; w < kWavelengths; ++w) {
                const float extinction = total.x * kRayleighScattering[w] +
                                         total.y * (kMieExtinctionRatio * kMieScattering) +
                                         total.z * kOzoneAbsorption[w];
                const float transmittance = std::exp(-extinction);
                const float scattered =
                    phase_r * (density.x * kRayleighScattering[w]) + phase_m * (density.y * kMieScattering);
                out[w] += transmittance * scattered * kSolarIrradiance[w] * step;
            }
        }
        at += segment;
    }
}

float clamped_size(float size) { return std::max(size, 0.0005f); }
float clamped_altitude(float altitude) { return std::clamp(altitude, 1.0f, 59999.0f); }

}  // namespace

Rgb xyz_to_rec709(Vec3 c, XyzMatrix m) {
    // Blender 3.x: the inverse of srgb_to_xyz.spimtx; 4.0 to 4.5 and 5.0: the config's
    // Linear CIE-XYZ D65 -> Linear Rec.709 matrix.
    static constexpr float k3[9] = {3.2404542f, -1.5371385f, -0.4985314f, -0.9692660f, 1.8760108f,
                                    0.0415560f, 0.0556434f,  -0.2040259f, 1.0572252f};
    static constexpr float k4[9] = {3.2404373564920070f,  -1.5371305409000549f, -0.4985288240756933f,
                                    -0.9692674982687597f, 1.8760136862977035f,  0.0415560804587997f,
                                    0.0556434463874256f,  -0.2040259700872272f, 1.0572254813610864f};
    static constexpr float k5[9] = {3.2409699f, -1.5373832f, -0.4986108f, -0.9692436f, 1.8759675f,
                                    0.0415551f, 0.0556301f,  -0.2039770f, 1.0569715f};
    const float* k = m == XyzMatrix::Blender3 ? k3 : (m == XyzMatrix::Blender4 ? k4 : k5);
    const float r = k[0] * c.x + k[1] * c.y + k[2] * c.z;
    const float g = k[3] * c.x + k[4] * c.y + k[5] * c.z;
    const float b = k[6] * c.x + k[7] * c.y + k[8] * c.z;
    return {std::max(r, 0.0f), std::max(g, 0.0f), std::max(b, 0.0f)};
}

Rgb preetham(const float* data, Vec3 dir, XyzMatrix m) {
    float theta = 0.0f, gamma = 0.0f;
    analytic_angles(data, dir, theta, gamma);
    const float* k = data + 5;
    const float Y = data[2] * perez(k, theta, gamma);
    const float x = data[3] * perez(k + 9, theta, gamma);
    const float y = data[4] * perez(k + 18, theta, gamma);
    // xyY to XYZ, with Cycles' guards for y == 0 and Y == 0.
    const float X = y != 0.0f ? (x / y) * Y : 0.0f;
    const float Z = (y != 0.0f && Y != 0.0f) ? (1.0f - x - y) / y * Y : 0.0f;
    return xyz_to_rec709({X, Y, Z}, m);
}

Rgb hosek_wilkie(const float* data, Vec3 dir, XyzMatrix m) {
    float theta = 0.0f, gamma = 0.0f;
    analytic_angles(data, dir, theta, gamma);
    const float* k = data + 5;
    const Vec3 xyz(hosek_channel(k, theta, gamma) * data[2], hosek_channel(k + 9, theta, gamma) * data[3],
                   hosek_channel(k + 18, theta, gamma) * data[4]);
    return xyz_to_rec709(xyz, m) * (kTwoPi / 683.0f);
}

std::vector<float> nishita_sky_table(const NishitaParams& p) {
    constexpr int w = kNishitaWidth, h = kNishitaHeight;
    std::vector<float> table(static_cast<size_t>(w) * h * 3, 0.0f);
    const Vec3 origin(0.0f, 0.0f, kEarthRadius + clamped_altitude(p.altitude));
    const Vec3 sun = from_latitude_longitude(p.sun_elevation, 0.0f);
    const Vec3 scale(p.air_density, p.dust_density, p.ozone_density);
    const float latitude_step = kHalfPi / h;
    const float longitude_step = kTwoPi / w;
    tbb::parallel_for(0, h, [&](int y) {
        Spectrum s{};
        const float t = static_cast<float>(y) / static_cast<float>(h);
        const float latitude = (kHalfPi + latitude_step / 2.0f) * (t * t);
        float* row = table.data() + static_cast<size_t>(y) * w * 3;
        for (int x = 0; x < w / 2; ++x) {
            const float longitude = longitude_step * static_cast<float>(x) - kPi;
            single_scattering(from_latitude_longitude(latitude, longitude), sun, origin, scale, s);
            const Vec3 xyz = spectrum_to_xyz(s);
            for (int side : {x, w - 1 - x}) {  // the sky is mirrored about the sun's meridian
                row[side * 3] = xyz.x;
                row[side * 3 + 1] = xyz.y;
                row[side * 3 + 2] = xyz.z;
            }
        }
    });
    return table;
}

std::vector<float> single_scattering_table(const NishitaParams& p) {
    constexpr int w = kNishitaWidth, h = kSingleScatteringHeight, half_h = h / 2;
    std::vector<float> table(static_cast<size_t>(w) * h * 3, 0.0f);
    const Vec3 origin(0.0f, 0.0f, kEarthRadius + clamped_altitude(p.altitude));
    const Vec3 sun = from_latitude_longitude(p.sun_elevation, 0.0f);
    const Vec3 scale(p.air_density, p.dust_density, p.ozone_density);
    const float longitude_step = kTwoPi / w;
    const auto latitude_of = [](int y) {
        const float t = static_cast<float>(y) / static_cast<float>(half_h) - 1.0f;
        return kHalfPi * (t * t);
    };
    tbb::parallel_for(half_h, h, [&](int y) {
        Spectrum s{};
        const float latitude = latitude_of(y);
        float* row = table.data() + static_cast<size_t>(y) * w * 3;
        for (int x = 0; x < w / 2; ++x) {
            const float longitude = longitude_step * static_cast<float>(x) - kPi;
            single_scattering(from_latitude_longitude(latitude, longitude), sun, origin, scale, s);
            const Vec3 xyz = spectrum_to_xyz(s);
            for (int side : {x, w - 1 - x}) {
                row[side * 3] = xyz.x;
                row[side * 3 + 1] = xyz.y;
                row[side * 3 + 2] = xyz.z;
            }
        }
    });
    const float* horizon = table.data() + static_cast<size_t>(half_h) * w * 3;
    for (int y = 0; y < half_h; ++y) {
        const float z = from_latitude_longitude(latitude_of(y), 0.0f).z;
        float fade = 0.0f;
        if (z < 0.4f) {
            fade = 1.0f - z * 2.5f;
            fade = fade * fade * fade;
        }
        float* row = table.data() + static_cast<size_t>(y) * w * 3;
        for (int i = 0; i < w * 3; ++i) row[i] = horizon[i] * fade;
    }
    return table;
}

float earth_intersection_angle(float altitude) {
    constexpr float kEarthRadiusKm = 6371.0f;
    return kHalfPi - std::asin(kEarthRadiusKm / (kEarthRadiusKm + altitude / 1000.0f));
}

void nishita_sun_pixels(const NishitaParams& p, Vec3& bottom, Vec3& top) {
    const float half = clamped_size(p.sun_size) / 2.0f;
    const float solid_angle = kTwoPi * (1.0f - std::cos(half));
    const Vec3 origin(0.0f, 0.0f, kEarthRadius + clamped_altitude(p.altitude));
    const auto radiance = [&](float elevation) {
        const Vec3 depth =
            optical_depth_to_space(origin, from_latitude_longitude(std::max(elevation, 0.0f), 0.0f));
        Spectrum s{};
        for (int w = 0; w < kWavelengths; ++w) {
            const float extinction = kRayleighScattering[w] * depth.x * p.air_density +
                                     kMieExtinctionRatio * kMieScattering * depth.y * p.dust_density;
            s[w] = kSolarIrradiance[w] * std::exp(-extinction) / solid_angle;
        }
        return spectrum_to_xyz(s);
    };
    bottom = radiance(p.sun_elevation - half);
    top = radiance(p.sun_elevation + half);
}

}  // namespace stratum::sky
