// Direct lighting of a diffuse floor by each light model, against closed forms. The floor
// (reflectance k, z = 0) is seen straight down through a very long lens; with max_bounces 0
// and non-reflecting emitters its radiance is exactly (k/π)·E, E the irradiance at the
// origin:
//   sun, strength E_s, overhead:             E = E_s
//   point light, power P, height h:          E = P / (4π h²)
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

#include "render_helpers.h"

using namespace stratum_test;

namespace {

constexpr float kPiF = 3.14159265358979f;
constexpr float kFloorReflectance = 0.5f;

struct Floor {
    StratumScene* scene = nullptr;
    Floor() {
        EXPECT_EQ(stratum_scene_create(&scene), STRATUM_OK);
        const StratumMaterialDesc floor{STRATUM_MATERIAL_DIFFUSE,
                                        {kFloorReflectance, kFloorReflectance, kFloorReflectance},
                                        1.0f,
                                        0.0f,
                                        0.0f,
                                        1.5f,
                                        {0, 0, 0},
                                        STRATUM_MICROFACET_GGX};
        add_quad(floor, 0.0f, 10.0f);
    }
    ~Floor() { stratum_scene_destroy(scene); }
    // A square of half side `half` at height z.
    void add_quad(const StratumMaterialDesc& material, float z, float half) {
        uint32_t mat = 0;
        EXPECT_EQ(stratum_scene_add_material(scene, &material, &mat), STRATUM_OK);
        const float positions[] = {-half, -half, z, half, -half, z, half, half, z, -half, half, z};
        const uint32_t triangles[] = {0, 1, 2, 0, 2, 3};
        const uint32_t mats[] = {mat, mat};
        const StratumMeshDesc mesh{positions, 4, triangles, 2, nullptr, nullptr, mats};
        uint32_t id = 0;
        EXPECT_EQ(stratum_scene_add_mesh(scene, &mesh, &id), STRATUM_OK);
        EXPECT_EQ(stratum_scene_add_instance(scene, id, kIdentity), STRATUM_OK);
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

TEST(DirectLighting, SphericalPointLightMatchesTheDeltaLightFromOutside) {
    // A uniformly emitting sphere of radius r irradiates an overhead surface like a point of
    // the same power, as long as it is fully above the horizon.
    Floor f;
    StratumLightDesc point = light_at(STRATUM_LIGHT_POINT, 100.0f, 2.0f);
    point.radius = 0.5f;
    ASSERT_EQ(stratum_scene_add_light(f.scene, &point), STRATUM_OK);
    expect_radiance(f.measure(1.0f, 2.0f), 100.0 / (4.0 * kPiF * 4.0));
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
