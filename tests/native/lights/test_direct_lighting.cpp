// Direct lighting of a diffuse floor by each light model, against closed forms. The floor
// (reflectance k, z = 0) is seen straight down through a very long lens; with max_bounces 0
// and non-reflecting emitters its radiance is exactly (k/π)·E, E the irradiance at the
// origin:
//   sun, strength E_s, overhead:             E = E_s
//   point light, power P, height h:          E = P / (4π h²)
//   same with radius r (disk facing the point): E = P / (4π (h² + r²))
//   disk area light, power P, radius R:      E = L π R² / (h² + R²),  L = P / (π A)
//   emissive square, radiance L, side 2a:    E = 4 L X/√(1+X²) atan(X/√(1+X²)), X = a/h
// (the last two are the disk and rectangle form factors times πL).
//
// Tolerance: 4·s/√P (s the spread of the pixel values, P pixels) plus the bias of seeing a
// footprint instead of a point: the view covers |x| ≤ w = 0.5·36/5000·d around the origin
// (d the camera height), where E falls by at most 3w²/h² relative (second-order Taylor of
// each formula in x/h, h the light height).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "render_helpers.h"
#include "scene_handle.h"

using namespace stratum_test;

namespace {

constexpr float kPiF = 3.14159265358979f;
constexpr float kFloorReflectance = 0.5f;

struct Floor : SceneHandle {
    Floor() { add_quad(diffuse_grey(kFloorReflectance), 0.0f, 10.0f); }
    // A square of half side `half` at height z.
    void add_quad(const StratumMaterialDesc& material, float z, float half) {
        uint32_t mat = 0;
        EXPECT_EQ(stratum_scene_add_material(scene, &material, &mat), STRATUM_OK);
        EXPECT_TRUE(add_square_instance(scene, z, half, mat)) << stratum_last_error();
    }
    // Mean floor radiance seen from height `camera_z`, its standard error, and the largest
    // relative bias of averaging over the footprint for a light at height `light_z`.
    struct Measurement {
        double mean, standard_error, footprint_bias;
    };
    Measurement measure(float camera_z, float light_z) {
        StratumCameraDesc camera = camera_at(0, 0, camera_z);
        camera.lens_mm = 5000.0f;
        EXPECT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK);
        const RenderOutput out =
            render(scene, {{"width", 16}, {"height", 16}, {"samples", 64}, {"max_bounces", 0}});
        const size_t n = out.rgba.size() / 4;
        EXPECT_EQ(n, 256u);
        double sum = 0, sum2 = 0;
        for (size_t i = 0; i < n; ++i) {
            sum += out.rgba[4 * i + 1];
            sum2 += static_cast<double>(out.rgba[4 * i + 1]) * out.rgba[4 * i + 1];
        }
        const double mean = sum / static_cast<double>(n);
        const double var =
            std::max(0.0, (sum2 - static_cast<double>(n) * mean * mean) / static_cast<double>(n - 1));
        const double w = 0.5 * 36.0 / 5000.0 * camera_z;
        return {mean, std::sqrt(var / static_cast<double>(n)), 3.0 * w * w / (light_z * light_z)};
    }
};

StratumLightDesc light_at(int32_t type, float strength, float z) {
    StratumLightDesc l{};
    l.type = type;
    l.color[0] = l.color[1] = l.color[2] = 1.0f;
    l.strength = strength;
    std::copy(kIdentity, kIdentity + 16, l.transform);
    l.transform[11] = z;
    return l;
}

void expect_radiance(const Floor::Measurement& m, double irradiance) {
    const double expected = kFloorReflectance / kPiF * irradiance;
    EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error + m.footprint_bias * expected)
        << "measured " << m.mean << " expected " << expected << " (se " << m.standard_error << ")";
}

}  // namespace

TEST(DirectLighting, SunOverhead) {
    for (const float angle : {0.0f, 0.1f}) {
        Floor f;
        StratumLightDesc sun = light_at(STRATUM_LIGHT_SUN, 3.0f, 5.0f);
        sun.angle = angle;
        ASSERT_EQ(stratum_scene_add_light(f.scene, &sun), STRATUM_OK);
        // A cone of half-angle α/2 around the normal delivers E_s exactly (radiance E/(π sin²)).
        expect_radiance(f.measure(2.0f, 5.0f), 3.0);
    }
}

TEST(DirectLighting, PointLightInverseSquare) {
    Floor f;
    const StratumLightDesc point = light_at(STRATUM_LIGHT_POINT, 100.0f, 2.0f);
    ASSERT_EQ(stratum_scene_add_light(f.scene, &point), STRATUM_OK);
    expect_radiance(f.measure(3.0f, 2.0f), 100.0 / (4.0 * kPiF * 4.0));
}

// A point light of radius r is Cycles' disk of radius r facing the shading point, radiance
// L = I/(π r²), I = P/(4π) (docs/cycles_models.md §4). Directly below at height h the disk is
// parallel to the floor and its form factor gives E = L·π r²/(h² + r²) = I/(h² + r²), the
// value measured in Cycles 3.4 and 5.0.1 — also with r > h, since the disk has no inside.
TEST(DirectLighting, PointLightWithRadiusIsADiskFacingTheShadingPoint) {
    for (const auto& [h, r] : {std::pair{2.0f, 0.5f}, std::pair{0.5f, 1.0f}}) {
        Floor f;
        StratumLightDesc point = light_at(STRATUM_LIGHT_POINT, 100.0f, h);
        point.radius = r;
        ASSERT_EQ(stratum_scene_add_light(f.scene, &point), STRATUM_OK);
        expect_radiance(f.measure(0.5f, h), 100.0 / (4.0 * kPiF) / (h * h + r * r));
    }
}

namespace {

// Irradiance at the floor's origin (normal +z) from the disk of radius r centred at c that faces
// the origin, radiance I/(π r²) times factor(cos t), t the angle between the emission direction
// (disk point → origin) and −z (the spot axis; factor ≡ 1 for a point light):
//     E = ∫disk L · factor · cos θ_floor · cos θ_disk / dist² dA,
// by the midpoint rule in polar coordinates (ρ, φ) on the disk, dA = ρ dρ dφ. The integrand is
// smooth and the rule's relative error is O(1/n²) ≈ 1e-6 at n = 512, far below the tolerance.
template <class Factor>
double facing_disk_irradiance(double intensity, const double c[3], double r, Factor factor) {
    const double dc = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    const double n[3] = {-c[0] / dc, -c[1] / dc, -c[2] / dc};  // disk normal, toward the origin
    // An orthonormal basis (u, v) of the disk's plane.
    double u[3] = {n[1], -n[0], 0.0};
    const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1]);
    for (double& x : u) x /= lu;
    const double v[3] = {n[1] * u[2] - n[2] * u[1], n[2] * u[0] - n[0] * u[2], n[0] * u[1] - n[1] * u[0]};
    const int steps = 512;
    const double L = intensity / (kPiF * r * r), d_rho = r / steps, d_phi = 2.0 * kPiF / steps;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double rho = (i + 0.5) * d_rho;
        for (int j = 0; j < steps; ++j) {
            const double phi = (j + 0.5) * d_phi, a = rho * std::cos(phi), b = rho * std::sin(phi);
            const double q[3] = {c[0] + a * u[0] + b * v[0], c[1] + a * u[1] + b * v[1],
                                 c[2] + a * u[2] + b * v[2]};
            const double dist = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
            const double cos_floor = q[2] / dist;
            const double cos_disk = -(q[0] * n[0] + q[1] * n[1] + q[2] * n[2]) / dist;
            sum += L * factor(q[2] / dist) * cos_floor * cos_disk / (dist * dist) * rho * d_rho * d_phi;
        }
    }
    return sum;
}

}  // namespace

TEST(DirectLighting, PointLightWithRadiusOffAxisMatchesTheFacingDiskQuadrature) {
    // The light 1.5 m to the side and 1 m up: the disk is tilted 56° from the floor, so the
    // floor's cosine varies across it; a sphere of the same radiance would give I·cos/d² instead.
    Floor f;
    StratumLightDesc point = light_at(STRATUM_LIGHT_POINT, 100.0f, 1.0f);
    point.transform[3] = 1.5f;
    point.radius = 0.6f;
    ASSERT_EQ(stratum_scene_add_light(f.scene, &point), STRATUM_OK);
    const double c[3] = {1.5, 0.0, 1.0};
    const double expected = facing_disk_irradiance(100.0 / (4.0 * kPiF), c, 0.6, [](double) { return 1.0; });
    const double sphere = 100.0 / (4.0 * kPiF) * (1.0 / std::sqrt(3.25)) / 3.25;
    ASSERT_GT(std::abs(expected / sphere - 1.0), 0.02);  // the two models differ measurably here
    expect_radiance(f.measure(0.5f, 1.0f), expected);
}

TEST(DirectLighting, DiskAreaLightEmitsItsPowerLambertian) {
    Floor f;
    StratumLightDesc disk = light_at(STRATUM_LIGHT_AREA_ELLIPSE, 50.0f, 1.0f);
    disk.size_x = disk.size_y = 1.0f;  // diameter 1: R = 0.5
    ASSERT_EQ(stratum_scene_add_light(f.scene, &disk), STRATUM_OK);
    const double R = 0.5, h = 1.0, area = kPiF * R * R;
    const double L = 50.0 / (kPiF * area);
    expect_radiance(f.measure(0.5f, 1.0f), L * kPiF * R * R / (h * h + R * R));
}

TEST(DirectLighting, RectangleAreaLightFacesDown) {
    Floor f;
    StratumLightDesc rect = light_at(STRATUM_LIGHT_AREA_RECTANGLE, 40.0f, 1.0f);
    rect.size_x = rect.size_y = 0.8f;
    ASSERT_EQ(stratum_scene_add_light(f.scene, &rect), STRATUM_OK);
    const double X = 0.4, L = 40.0 / (kPiF * 0.64), s = X / std::sqrt(1 + X * X);
    expect_radiance(f.measure(0.5f, 1.0f), 4.0 * L * s * std::atan(s));
    // Turned upside down (emitting up, away from the floor) it lights nothing.
    Floor g;
    rect.transform[5] = -1.0f;
    rect.transform[10] = -1.0f;
    ASSERT_EQ(stratum_scene_add_light(g.scene, &rect), STRATUM_OK);
    EXPECT_EQ(g.measure(0.5f, 1.0f).mean, 0.0);
}

TEST(DirectLighting, EmissiveSquareThroughNeeAndMis) {
    Floor f;
    const float L = 2.0f;
    const StratumMaterialDesc emitter{STRATUM_MATERIAL_EMISSION, {0, 0, 0}, 1, 0, 0, 1.5f, {L, L, L},
                                      STRATUM_MICROFACET_GGX};
    f.add_quad(emitter, 1.0f, 0.4f);
    const double X = 0.4, s = X / std::sqrt(1 + X * X);
    expect_radiance(f.measure(0.5f, 1.0f), 4.0 * L * s * std::atan(s));
}

// Several lights of very different power: NEE chooses among them (half by power, half uniform
// over light objects) and must stay unbiased; the irradiances simply add. The sun and the point
// light stand off to the side, so the emissive square above the origin does not shadow them:
//   sun tilted 45 degrees: E = 3 cos 45;  point at (1.5, 0, 1): E = P cos / (4 pi d^2),
//   cos = 1/sqrt(3.25), d^2 = 3.25.
TEST(DirectLighting, SeveralLightsAdd) {
    Floor f;
    StratumLightDesc sun = light_at(STRATUM_LIGHT_SUN, 3.0f, 5.0f);
    const float c = std::sqrt(0.5f);
    const float tilt[12] = {c, 0, c, 0, 0, 1, 0, 0, -c, 0, c, 5};
    std::copy(tilt, tilt + 12, sun.transform);
    StratumLightDesc point = light_at(STRATUM_LIGHT_POINT, 1.0f, 1.0f);
    point.transform[3] = 1.5f;
    ASSERT_EQ(stratum_scene_add_light(f.scene, &sun), STRATUM_OK);
    ASSERT_EQ(stratum_scene_add_light(f.scene, &point), STRATUM_OK);
    const float L = 2.0f;
    const StratumMaterialDesc emitter{STRATUM_MATERIAL_EMISSION, {0, 0, 0}, 1, 0, 0, 1.5f, {L, L, L},
                                      STRATUM_MICROFACET_GGX};
    f.add_quad(emitter, 1.0f, 0.4f);
    const double X = 0.4, s = X / std::sqrt(1 + X * X);
    const double irradiance =
        3.0 * std::sqrt(0.5) + 1.0 / std::sqrt(3.25) / (4.0 * kPiF * 3.25) + 4.0 * L * s * std::atan(s);
    expect_radiance(f.measure(0.5f, 1.0f), irradiance);
}

// Spot lights (docs/cycles_models.md §4 "Spot light"): intensity P/(4π) · S(cos θ) toward angle θ
// from the axis, S the smoothstep over the blend band, times cos θ for the Cycles 3.x model. The
// spot hangs at (x0, 0, h) pointing straight down, so the floor's origin sees it at
// cos θ = h / d, d² = x0² + h², and E = I · S(cos θ) [· cos θ] · cos θ / d². The expected value
// is that closed form averaged over the square footprint the camera sees (its curvature in the
// blend band exceeds the 3w²/h² bound used for smooth falloffs, which stays as slack).
namespace {

constexpr double kSpotSize = 60.0 * kPiF / 180.0;  // half angle 30 degrees
constexpr double kSpotBlend = 0.5;

double spot_factor(double cos_theta, bool cosine_falloff) {
    const double cos_half = std::cos(0.5 * kSpotSize), smooth = (1.0 - cos_half) * kSpotBlend;
    if (cos_theta <= cos_half) return 0.0;
    const double x = std::min(1.0, (cos_theta - cos_half) / smooth);
    return x * x * (3.0 - 2.0 * x) * (cosine_falloff ? cos_theta : 1.0);
}

// Irradiance at the floor point (x, y, 0) from the spot of power P at (x0, 0, h).
double spot_irradiance(double power, double x0, double h, double x, double y, bool cosine_falloff) {
    const double d2 = (x - x0) * (x - x0) + y * y + h * h, c = h / std::sqrt(d2);
    return power / (4.0 * kPiF) * spot_factor(c, cosine_falloff) * c / d2;
}

// Mean of spot_irradiance over the square footprint |x|, |y| <= w seen from height camera_z.
double spot_footprint_irradiance(double power, double x0, double h, float camera_z, bool cosine_falloff) {
    const double w = 0.5 * 36.0 / 5000.0 * camera_z;
    const int n = 64;
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            sum += spot_irradiance(power, x0, h, w * (2.0 * (i + 0.5) / n - 1.0),
                                   w * (2.0 * (j + 0.5) / n - 1.0), cosine_falloff);
    return sum / (n * n);
}

StratumLightDesc spot_at(int32_t type, float power, float x0, float h) {
    StratumLightDesc spot = light_at(type, power, h);
    spot.transform[3] = x0;
    spot.spot_size = static_cast<float>(kSpotSize);
    spot.spot_blend = static_cast<float>(kSpotBlend);
    return spot;
}

}  // namespace

TEST(DirectLighting, SpotLightCentreIsThePointLightIntensity) {
    for (const int32_t type : {STRATUM_LIGHT_SPOT, STRATUM_LIGHT_SPOT_V1}) {
        for (const float radius : {0.0f, 0.1f}) {
            Floor f;
            StratumLightDesc spot = spot_at(type, 100.0f, 0.0f, 2.0f);
            spot.radius = radius;
            ASSERT_EQ(stratum_scene_add_light(f.scene, &spot), STRATUM_OK) << stratum_last_error();
            // On the axis S = 1 (the disk's directions stay within 3° of the axis, the blend band
            // starts at 21°). The disk faces the floor point: with ρ the radius on the disk,
            // dist² = h² + ρ², cos t = h/dist is the floor's and the disk's cosine, so
            //     E = ∫0^r (I/(π r²)) cos²t (· cos t for 3.x) / dist² 2πρ dρ
            //       = I/(h² + r²)                 (4.x/5.x),
            //       = 2I (1 − c³) / (3 r²),  c = h/√(h² + r²)   (3.x),
            // and both are I/h² at r = 0.
            const double h = 2.0, I = 100.0 / (4.0 * kPiF);
            const double c = h / std::sqrt(h * h + radius * radius);
            const double expected = radius == 0.0f ? I / (h * h)
                                    : type == STRATUM_LIGHT_SPOT_V1
                                        ? 2.0 * I * (1.0 - c * c * c) / (3.0 * radius * radius)
                                        : I / (h * h + radius * radius);
            expect_radiance(f.measure(3.0f, 2.0f), expected);
        }
    }
}

TEST(DirectLighting, SpotLightBlendBandFollowsTheSmoothstep) {
    // θ = 25 degrees: inside the band [21.1, 30] degrees, S = 0.65.
    const float h = 2.0f, x0 = h * std::tan(25.0f * kPiF / 180.0f);
    ASSERT_GT(spot_factor(std::cos(25.0 * kPiF / 180.0), false), 0.3);
    ASSERT_LT(spot_factor(std::cos(25.0 * kPiF / 180.0), false), 0.9);
    for (const int32_t type : {STRATUM_LIGHT_SPOT, STRATUM_LIGHT_SPOT_V1}) {
        Floor f;
        const StratumLightDesc spot = spot_at(type, 100.0f, x0, h);
        ASSERT_EQ(stratum_scene_add_light(f.scene, &spot), STRATUM_OK);
        expect_radiance(f.measure(0.5f, h),
                        spot_footprint_irradiance(100.0, x0, h, 0.5f, type == STRATUM_LIGHT_SPOT_V1));
    }
}

TEST(DirectLighting, SpotLightWithRadiusInTheBlendBandMatchesTheFacingDiskQuadrature) {
    // θ = 25 degrees with a radius of 0.4 m: the disk spans 24..26 degrees as seen from the floor
    // point, so S varies across it; the factor is taken per disk point (Cycles: −ls->D).
    const float h = 2.0f, x0 = h * std::tan(25.0f * kPiF / 180.0f), r = 0.4f;
    for (const int32_t type : {STRATUM_LIGHT_SPOT, STRATUM_LIGHT_SPOT_V1}) {
        Floor f;
        StratumLightDesc spot = spot_at(type, 100.0f, x0, h);
        spot.radius = r;
        ASSERT_EQ(stratum_scene_add_light(f.scene, &spot), STRATUM_OK);
        const bool v1 = type == STRATUM_LIGHT_SPOT_V1;
        const double c[3] = {x0, 0.0, h};
        const double expected = facing_disk_irradiance(100.0 / (4.0 * kPiF), c, r,
                                                       [v1](double cos_t) { return spot_factor(cos_t, v1); });
        expect_radiance(f.measure(0.5f, h), expected);
    }
}

TEST(DirectLighting, SpotLightIsDarkOutsideItsCone) {
    // θ = 45 degrees > 30: nothing, with or without a radius (the sphere stays outside too).
    for (const float radius : {0.0f, 0.1f}) {
        Floor f;
        StratumLightDesc spot = spot_at(STRATUM_LIGHT_SPOT, 100.0f, 2.0f, 2.0f);
        spot.radius = radius;
        ASSERT_EQ(stratum_scene_add_light(f.scene, &spot), STRATUM_OK);
        EXPECT_EQ(f.measure(0.5f, 2.0f).mean, 0.0);
    }
    // A hard edge (blend 0): full intensity just inside, none just outside.
    Floor inside, outside;
    StratumLightDesc spot = spot_at(STRATUM_LIGHT_SPOT, 100.0f, 2.0f * std::tan(29.0f * kPiF / 180.0f), 2.0f);
    spot.spot_blend = 0.0f;
    ASSERT_EQ(stratum_scene_add_light(inside.scene, &spot), STRATUM_OK);
    const double c = std::cos(29.0 * kPiF / 180.0);
    expect_radiance(inside.measure(0.5f, 2.0f), 100.0 / (4.0 * kPiF) * c * c * c / 4.0);
    spot.transform[3] = 2.0f * std::tan(31.0f * kPiF / 180.0f);
    ASSERT_EQ(stratum_scene_add_light(outside.scene, &spot), STRATUM_OK);
    EXPECT_EQ(outside.measure(0.5f, 2.0f).mean, 0.0);
}

TEST(DirectLighting, SpotLightValuesAreValidatedAndSaved) {
    Floor f;
    StratumLightDesc spot = spot_at(STRATUM_LIGHT_SPOT, 100.0f, 0.0f, 2.0f);
    spot.spot_size = 0.0f;
    EXPECT_EQ(stratum_scene_add_light(f.scene, &spot), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("spot_size"), std::string::npos) << stratum_last_error();
    spot.spot_size = 3.2f;
    EXPECT_EQ(stratum_scene_add_light(f.scene, &spot), STRATUM_ERROR_INVALID_ARGUMENT);
    spot.spot_size = kPiF;
    spot.spot_blend = 1.5f;
    EXPECT_EQ(stratum_scene_add_light(f.scene, &spot), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("spot_blend"), std::string::npos)
        << stratum_last_error();
    // Other lights ignore the spot fields.
    StratumLightDesc point = light_at(STRATUM_LIGHT_POINT, 1.0f, 2.0f);
    point.spot_size = -1.0f;
    EXPECT_EQ(stratum_scene_add_light(f.scene, &point), STRATUM_OK);

    // A saved scene keeps the cone: it renders the same image after loading.
    Floor g;
    const StratumLightDesc blended = spot_at(STRATUM_LIGHT_SPOT_V1, 100.0f, 0.9f, 2.0f);
    ASSERT_EQ(stratum_scene_add_light(g.scene, &blended), STRATUM_OK);
    StratumCameraDesc camera = camera_at(0, 0, 3);
    ASSERT_EQ(stratum_scene_set_camera(g.scene, &camera), STRATUM_OK);
    const std::string path = ::testing::TempDir() + "stratum_spot_scene.json";
    ASSERT_EQ(stratum_scene_save(g.scene, path.c_str()), STRATUM_OK) << stratum_last_error();
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(path.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    const auto a = render(g.scene, {{"width", 16}, {"height", 16}, {"samples", 4}, {"max_bounces", 0}});
    const auto b = render(loaded, {{"width", 16}, {"height", 16}, {"samples", 4}, {"max_bounces", 0}});
    EXPECT_EQ(a.rgba, b.rgba);
    stratum_scene_destroy(loaded);
    std::remove(path.c_str());
}
