// Cycles' area light spread (lights/area_light.h): flux-preserving, zero outside the half angle,
// sampled consistently with its pdf; spread π is the plain Lambertian light. Light visibility
// bits reach every LightSample.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "lights/area_light.h"
#include "lights/light_set.h"
#include "lights/point_light.h"
#include "render_helpers.h"

using namespace stratum;

namespace {

struct Spread {
    float tan_half, normalize;
};

// The constants AreaLight derives from a spread (Cycles 4.x scene/light.cpp).
Spread spread_constants(float spread) {
    const float h = 0.5f * spread;
    const float t = std::tan(h);
    return {t, h > 0.05f ? 1.0f / (t - h) : 3.0f / (h * h * h)};
}

// A size x size square light at height 2 facing down (local −Z = world −Z), power 10 W.
AreaLight square_light(float spread, float size = 1.0f) {
    Transform t;
    t.m[11] = 2.0f;
    return AreaLight(t, size, size, false, Rgb(10.0f), spread);
}

}  // namespace

// The flux over the hemisphere, 2π ∫₀ʰ f(a) cos a sin a da, is π for every spread (Simpson's
// rule, 20 000 intervals: its error is far below the float rounding of f, ~1e-6 relative), so
// the spread keeps the light's power. Both branches of N (exact and the h <= 0.05 Taylor form).
TEST(AreaLightSpread, SpreadPreservesTheFlux) {
    for (float degrees : {3.0f, 5.0f, 10.0f, 45.0f, 90.0f, 150.0f, 179.0f}) {
        const float spread = degrees * kPi / 180.0f, h = 0.5f * spread;
        const Spread s = spread_constants(spread);
        constexpr int kSteps = 20000;
        double sum = 0;
        for (int i = 0; i <= kSteps; ++i) {
            const double a = static_cast<double>(h) * i / kSteps;
            const double w = (i == 0 || i == kSteps) ? 1 : (i % 2 ? 4 : 2);
            sum += w *
                   area_light_spread_attenuation(static_cast<float>(std::cos(a)), s.tan_half, s.normalize) *
                   std::cos(a) * std::sin(a);
        }
        const double flux = 2.0 * kPi * sum * (h / kSteps) / 3.0;
        EXPECT_NEAR(flux, kPi, 2e-3 * kPi) << degrees << " degrees";
        // Nothing leaves beyond the half angle.
        EXPECT_EQ(area_light_spread_attenuation(std::cos(h * 1.01f), s.tan_half, s.normalize), 0.0f);
    }
}

// Spread π (and 0 at the ABI, which reads as π) is exactly the light without spread.
TEST(AreaLightSpread, SpreadPiIsTheLambertianLight) {
    Transform t;
    t.m[11] = 2.0f;
    const AreaLight plain(t, 1.0f, 0.5f, true, Rgb(3.0f));
    const AreaLight wide(t, 1.0f, 0.5f, true, Rgb(3.0f), kPi);
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (int i = 0; i < 200; ++i) {
        const Vec3 p(4 * u(rng) - 2, 4 * u(rng) - 2, 1.5f * u(rng));
        const Vec2 uv{u(rng), u(rng)};
        LightSample a, b;
        const bool ok = plain.sample(p, Vec3(), uv, TriangleSampling::SolidAngle, &a);
        ASSERT_EQ(ok, wide.sample(p, Vec3(), uv, TriangleSampling::SolidAngle, &b));
        if (!ok) continue;
        EXPECT_EQ(a.radiance.r, b.radiance.r);
        EXPECT_EQ(a.pdf, b.pdf);
    }
    // Through the ABI: spread 0 and spread π render the same image.
    using namespace stratum_test;
    const auto image = [](float spread) {
        StratumScene* scene = make_sphere_interior(diffuse_grey(0.7f), 8, 0, 0, 0.2f);
        StratumLightDesc light{};
        light.type = STRATUM_LIGHT_AREA_RECTANGLE;
        light.color[0] = light.color[1] = light.color[2] = 1;
        light.strength = 20;
        light.size_x = light.size_y = 0.5f;
        std::copy(kIdentity, kIdentity + 16, light.transform);
        light.transform[11] = 0.8f;
        light.spread = spread;
        EXPECT_EQ(stratum_scene_add_light(scene, &light), STRATUM_OK) << stratum_last_error();
        const auto out = render(scene, {{"width", 16}, {"height", 16}, {"samples", 4}});
        stratum_scene_destroy(scene);
        return out.rgba;
    };
    const auto zero = image(0.0f), pi = image(kPi), narrow = image(0.5f);
    EXPECT_EQ(zero, pi);
    EXPECT_NE(zero, narrow);
}

// Irradiance at points below a 1 m square light with spread 60°: the light's own estimator
// (uniform area samples, radiance × f, pdf r²/(A cos)) against a midpoint quadrature of
// ∫_A L f(a) cos θ_r cos θ_l / r² dA on a 400 x 400 grid (error ~1e-5 relative). The MC mean of
// N = 2^16 samples has standard error σ/√N with σ estimated from the samples; tolerance 4 of
// those (two-sided 4σ, fixed seed). Off axis the spread cuts part of the light away.
TEST(AreaLightSpread, SamplingMatchesTheIrradianceIntegral) {
    const float spread = 60.0f * kPi / 180.0f;
    const AreaLight light = square_light(spread);
    const Spread s = spread_constants(spread);
    const Rgb radiance_plain = Rgb(10.0f) * (kInvPi / 1.0f);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (const Vec3 p : {Vec3(0, 0, 0), Vec3(0.6f, 0.2f, 0.5f), Vec3(0.9f, 0, 1.0f)}) {
        double quad = 0;
        constexpr int kGrid = 400;
        for (int i = 0; i < kGrid; ++i) {
            for (int j = 0; j < kGrid; ++j) {
                const Vec3 q(-0.5f + (static_cast<float>(i) + 0.5f) / kGrid,
                             -0.5f + (static_cast<float>(j) + 0.5f) / kGrid, 2.0f);
                const Vec3 to = q - p;
                const float r2 = dot(to, to), r = std::sqrt(r2);
                const float cos_l = to.z / r, cos_r = to.z / r;  // light faces −Z, receiver +Z
                quad += radiance_plain.r * area_light_spread_attenuation(cos_l, s.tan_half, s.normalize) *
                        cos_r * cos_l / r2 / (kGrid * kGrid);
            }
        }
        constexpr int kN = 1 << 16;
        double sum = 0, sum2 = 0;
        for (int k = 0; k < kN; ++k) {
            LightSample ls;
            double x = 0;
            if (light.sample(p, Vec3(), {u(rng), u(rng)}, TriangleSampling::SolidAngle, &ls))
                x = ls.radiance.r * std::max(0.0f, ls.wi.z) / ls.pdf;
            sum += x;
            sum2 += x * x;
        }
        const double mean = sum / kN, sigma = std::sqrt(std::max(0.0, sum2 / kN - mean * mean));
        EXPECT_GT(quad, 0.0);
        EXPECT_NEAR(mean, quad, 4.0 * sigma / std::sqrt(double(kN)) + 1e-4 * quad)
            << "at (" << p.x << ", " << p.y << ", " << p.z << ")";
    }
}

// Light visibility: every sample of a light carries its bits; 0 at the ABI reads as all, and
// bits beyond STRATUM_VISIBLE_ALL or a spread outside (0, π] are refused by name.
TEST(AreaLightSpread, LightVisibilityReachesTheSamples) {
    LightSet set;
    set.add(PointLight(Vec3(0, 0, 2), Rgb(1.0f), 0.0f), 0, STRATUM_VISIBLE_DIFFUSE | STRATUM_VISIBLE_SHADOW);
    set.finalize(1.0f);
    LightSample ls;
    ASSERT_TRUE(set.sample({0, 0, 0}, {0, 0, 0}, 0.5f, {0.5f, 0.5f}, &ls));
    EXPECT_EQ(ls.visibility, static_cast<uint32_t>(STRATUM_VISIBLE_DIFFUSE | STRATUM_VISIBLE_SHADOW));

    using namespace stratum_test;
    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    StratumLightDesc light{};
    light.type = STRATUM_LIGHT_AREA_ELLIPSE;
    light.strength = 1;
    light.size_x = light.size_y = 1;
    std::copy(kIdentity, kIdentity + 16, light.transform);
    light.visibility = 64;
    EXPECT_EQ(stratum_scene_add_light(scene, &light), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("light visibility = 64"), std::string::npos)
        << stratum_last_error();
    light.visibility = 0;
    light.spread = 4.0f;
    EXPECT_EQ(stratum_scene_add_light(scene, &light), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("area light spread = 4"), std::string::npos)
        << stratum_last_error();
    light.spread = -0.5f;
    EXPECT_EQ(stratum_scene_add_light(scene, &light), STRATUM_ERROR_INVALID_ARGUMENT);
    light.spread = 1.0f;
    light.visibility = STRATUM_VISIBLE_CAMERA | STRATUM_VISIBLE_GLOSSY;
    EXPECT_EQ(stratum_scene_add_light(scene, &light), STRATUM_OK) << stratum_last_error();
    // The scene file keeps both.
    const std::string path = ::testing::TempDir() + "stratum_light_spread.json";
    ASSERT_EQ(stratum_scene_save(scene, path.c_str()), STRATUM_OK);
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(path.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    const std::string again = ::testing::TempDir() + "stratum_light_spread_again.json";
    ASSERT_EQ(stratum_scene_save(loaded, again.c_str()), STRATUM_OK);
    std::ifstream a(path), b(again);
    std::stringstream ta, tb;
    ta << a.rdbuf();
    tb << b.rdbuf();
    EXPECT_EQ(ta.str(), tb.str());
    EXPECT_NE(ta.str().find("\"spread\":1.0"), std::string::npos) << ta.str();
    EXPECT_NE(ta.str().find("\"visibility\":5"), std::string::npos) << ta.str();
    std::remove(path.c_str());
    std::remove(again.c_str());
    stratum_scene_destroy(loaded);
    stratum_scene_destroy(scene);
}

// A ray meets a lamp's emitting face: the nearest camera-visible area light in front of the
// ray gives its radiance (× spread factor); the back side, a miss, a lamp beyond t_max, a lamp
// without the ray's visibility bit and a point of the square outside the disk give black.
TEST(AreaLightSpread, RaysSeeTheEmittingFaceOfVisibleLamps) {
    Transform at2, at1;
    at2.m[11] = 2.0f;
    at1.m[11] = 1.0f;
    LightSet set;
    set.add(AreaLight(at2, 1.0f, 1.0f, false, Rgb(10.0f)), 0, STRATUM_VISIBLE_CAMERA);
    set.add(AreaLight(at1, 0.2f, 0.2f, true, Rgb(1.0f)), 1, STRATUM_VISIBLE_ALL & ~STRATUM_VISIBLE_CAMERA);
    set.finalize(1.0f);
    const Vec3 up(0, 0, 1);
    const float L = 10.0f * kInvPi;
    EXPECT_FLOAT_EQ(set.lamp_radiance({0.3f, 0.3f, 0}, up, kInfinity, STRATUM_VISIBLE_CAMERA).r, L);
    // The small disk at z = 1 is nearer but not camera-visible; glossy rays see it.
    EXPECT_FLOAT_EQ(set.lamp_radiance({0, 0, 0}, up, kInfinity, STRATUM_VISIBLE_CAMERA).r, L);
    EXPECT_FLOAT_EQ(set.lamp_radiance({0, 0, 0}, up, kInfinity, STRATUM_VISIBLE_GLOSSY).r,
                    1.0f * kInvPi / (kPi * 0.01f));
    // (0.09, 0.09) lies in the disk's bounding square but outside the disk (radius 0.1).
    EXPECT_FLOAT_EQ(set.lamp_radiance({0.09f, 0.09f, 0}, up, kInfinity, STRATUM_VISIBLE_GLOSSY).r, 0.0f);
    EXPECT_EQ(set.lamp_radiance({0.6f, 0, 0}, up, kInfinity, STRATUM_VISIBLE_CAMERA).r, 0.0f);
    EXPECT_EQ(set.lamp_radiance({0, 0, 0}, up, 1.5f, STRATUM_VISIBLE_CAMERA).r, 0.0f);
    EXPECT_EQ(set.lamp_radiance({0, 0, 3}, -up, kInfinity, STRATUM_VISIBLE_CAMERA).r, 0.0f);
    // Spread 60°: seen 20° off the normal, f = (tan 30° − tan 20°) N.
    const AreaLight narrow = square_light(60.0f * kPi / 180.0f, 4.0f);
    const Spread s = spread_constants(60.0f * kPi / 180.0f);
    const float a = 20.0f * kPi / 180.0f;
    float t = 0, pdf = 0;
    Rgb radiance;
    ASSERT_TRUE(narrow.intersect({0, 0, 0}, {std::sin(a), 0, std::cos(a)}, kInfinity, &t, &radiance, &pdf));
    EXPECT_NEAR(t, 2.0f / std::cos(a), 1e-5f);
    // sample()'s solid-angle density of that direction: t² / (A cos θ_light), A = 4 x 4.
    EXPECT_NEAR(pdf, t * t / (16.0f * std::cos(a)), 1e-6f);
    EXPECT_NEAR(radiance.r,
                10.0f * kInvPi / 16.0f * (std::tan(0.5f * 60.0f * kPi / 180.0f) - std::tan(a)) * s.normalize,
                1e-5f);
}
