// The path integrator over closure materials (integrators/path_integrator.h): transparent
// shadows, glass blocking shadow rays, transparent_max_bounces, holdouts and film alpha, and the
// exact energy conservation of smooth glass in a white world.
//
// The scenes are lit by a sun (a delta light: next-event estimation is deterministic) and render
// direct light only (max_bounces 0), so each expected value is a closed form and is met to float
// rounding: floor of albedo rho under a sun of irradiance E at normal incidence has radiance
// rho E / pi; a surface between them multiplies it by its transmittance. No statistical
// tolerance is needed; comparisons are relative 1e-5.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "integrators/path_integrator.h"
#include "render_scene/render_scene.h"
#include "stratum/stratum.h"

namespace stratum {
namespace {

constexpr float kSunIrradiance = 3.0f;
constexpr float kFloorAlbedo = 0.8f;

Material make(int32_t model, Rgb c, float roughness = 0.0f, float ior = 1.5f) {
    return {model, c, roughness, 0.0f, 0.5f, ior, Rgb(), MicrofacetDistribution::Ggx};
}

struct TestScene {
    Scene scene;
    // A horizontal square of half side `half` at height z (normal +z) with material `material`.
    void add_quad(float z, float half, uint32_t material) {
        Mesh mesh;
        mesh.positions = {{-half, -half, z}, {half, -half, z}, {half, half, z}, {-half, half, z}};
        mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
        mesh.material_ids = {material, material};
        scene.meshes.push_back(mesh);
        scene.instances.push_back({static_cast<uint32_t>(scene.meshes.size() - 1), Transform{}});
    }
    uint32_t add_material(std::initializer_list<WeightedClosure> closures) {
        scene.materials.push_back(SceneMaterial{closures});
        return static_cast<uint32_t>(scene.materials.size() - 1);
    }
    void add_sun() {
        LightParams sun;
        sun.type = STRATUM_LIGHT_SUN;
        sun.strength = kSunIrradiance;
        scene.lights.push_back(sun);  // identity transform: the sun is straight overhead
    }
    // A floor at z = 0 under the sun.
    static TestScene lit_floor() {
        TestScene t;
        t.add_quad(0.0f, 10.0f,
                   t.add_material({{Rgb(1.0f), make(STRATUM_MATERIAL_DIFFUSE, Rgb(kFloorAlbedo))}}));
        t.add_sun();
        return t;
    }
};

RadianceSample trace(const Scene& scene, Vec3 origin, Vec3 target, const IntegratorSettings& settings,
                     uint32_t index = 0) {
    const RenderScene render_scene(scene);
    const auto sampler = find_sampler("random")->create(SamplerSettings{});
    const PathIntegrator integrator(settings);
    uint64_t rays = 0;
    const CameraRay ray{origin, normalize(target - origin), 0.0f, kInfinity};
    return integrator.radiance(render_scene, *sampler, PixelSample{0, 0, index}, ray, rays);
}

IntegratorSettings direct_only() {
    IntegratorSettings s;
    s.max_bounces = 0;
    return s;
}

// A camera ray below the slabs (which are at z >= 1) reaching the floor at the origin.
RadianceSample floor_radiance(const Scene& scene, const IntegratorSettings& settings = direct_only()) {
    return trace(scene, {0.0f, -2.0f, 0.5f}, {0.0f, 0.0f, 0.0f}, settings);
}

void expect_rgb(Rgb actual, Rgb expected) {
    EXPECT_NEAR(actual.r, expected.r, 1e-5f * (1 + expected.r));
    EXPECT_NEAR(actual.g, expected.g, 1e-5f * (1 + expected.g));
    EXPECT_NEAR(actual.b, expected.b, 1e-5f * (1 + expected.b));
}

const float kUnoccluded = kFloorAlbedo * kSunIrradiance / kPi;

TEST(PathClosures, UnoccludedFloorIsTheClosedForm) {
    const TestScene t = TestScene::lit_floor();
    const RadianceSample r = floor_radiance(t.scene);
    expect_rgb(r.radiance, Rgb(kUnoccluded));
    EXPECT_EQ(r.alpha, 1.0f);
}

TEST(PathClosures, TransparentShadowIsColourTimesUnoccluded) {
    TestScene t = TestScene::lit_floor();
    const Rgb colour(0.7f, 0.4f, 0.1f);
    t.add_quad(1.0f, 3.0f, t.add_material({{Rgb(1.0f), make(STRATUM_MATERIAL_TRANSPARENT, colour)}}));
    expect_rgb(floor_radiance(t.scene).radiance, colour * kUnoccluded);
}

TEST(PathClosures, MixedTransparentShadowIsItsWeightedColour) {
    TestScene t = TestScene::lit_floor();
    const Rgb colour(0.7f, 0.4f, 0.1f);
    t.add_quad(1.0f, 3.0f,
               t.add_material({{Rgb(0.25f), make(STRATUM_MATERIAL_TRANSPARENT, colour)},
                               {Rgb(0.75f), make(STRATUM_MATERIAL_DIFFUSE, Rgb(0.5f))}}));
    expect_rgb(floor_radiance(t.scene).radiance, colour * (0.25f * kUnoccluded));
}

// Cycles traces no caustics through glass on shadow rays: a glass slab casts a full shadow.
TEST(PathClosures, GlassBlocksShadowRays) {
    TestScene t = TestScene::lit_floor();
    t.add_quad(1.0f, 3.0f, t.add_material({{Rgb(1.0f), make(STRATUM_MATERIAL_GLASS, Rgb(1.0f))}}));
    expect_rgb(floor_radiance(t.scene).radiance, Rgb(0.0f));
}

TEST(PathClosures, ShadowRaysCrossAtMostTransparentMaxBounces) {
    TestScene t = TestScene::lit_floor();
    const Rgb colour(0.5f, 0.6f, 0.9f);
    const uint32_t clear = t.add_material({{Rgb(1.0f), make(STRATUM_MATERIAL_TRANSPARENT, colour)}});
    t.add_quad(1.0f, 3.0f, clear);
    t.add_quad(1.5f, 3.0f, clear);
    IntegratorSettings s = direct_only();
    s.transparent_max_bounces = 2;
    expect_rgb(floor_radiance(t.scene, s).radiance, colour * colour * kUnoccluded);
    s.transparent_max_bounces = 1;
    expect_rgb(floor_radiance(t.scene, s).radiance, Rgb(0.0f));
}

// Light visibility: a light whose SHADOW bit is off is never occluded (Cycles cast_shadow off).
// The LightSample visibility comes from the light; here every light has the default (all bits),
// so an opaque slab shadows completely.
TEST(PathClosures, OpaqueSlabShadows) {
    TestScene t = TestScene::lit_floor();
    t.add_quad(1.0f, 3.0f, t.add_material({{Rgb(1.0f), make(STRATUM_MATERIAL_DIFFUSE, Rgb(0.5f))}}));
    expect_rgb(floor_radiance(t.scene).radiance, Rgb(0.0f));
}

// Next-event estimation through a transmissive closure: a rough glass square lit by the sun from
// above, seen from straight below (its back face: eta = 1/1.5). The light is below the viewer's
// side of the surface, so only the transmission lobe sees it. With wo = n and wi = -n, h = n and
// (glass.h) f cos_i = (1 - F0) D(n) G2 eta^2 / (1 - eta)^2 with D(n) = 1/(pi alpha^2), G2 = 1,
// F0 = ((1 - eta)/(1 + eta))^2; the sun's radiance is its irradiance (a delta light).
TEST(PathClosures, LightThroughRoughGlassIsTheClosedForm) {
    TestScene t;
    const float roughness = 0.5f, ior = 1.5f;
    t.add_quad(0.0f, 3.0f,
               t.add_material({{Rgb(1.0f), make(STRATUM_MATERIAL_GLASS, Rgb(1.0f), roughness, ior)}}));
    t.add_sun();
    const double eta = 1.0 / ior, alpha = roughness * roughness;
    const double f0 = ((1 - eta) / (1 + eta)) * ((1 - eta) / (1 + eta));
    const double expected =
        kSunIrradiance * (1 - f0) * eta * eta / ((1 - eta) * (1 - eta) * kPi * alpha * alpha);
    const RadianceSample r = trace(t.scene, {0.0f, 0.0f, -2.0f}, {0.0f, 0.0f, 0.0f}, direct_only());
    EXPECT_NEAR(r.radiance.r, expected, 1e-5 * expected);
    EXPECT_NEAR(r.radiance.b, expected, 1e-5 * expected);
}

// After the last bounce the path still crosses transparent surfaces to reach emission (Cycles'
// PATH_RAY_TERMINATE_AFTER_TRANSPARENT). A floor of albedo rho under a huge emitting ceiling of
// radiance E seen through a huge transparent sheet of colour c has radiance rho c E (irradiance
// pi c E). With max_bounces 0 half of that estimate (by MIS) comes from BSDF rays that cross the
// sheet after the floor's bounce; without crossing the mean would fall short. The ceiling and
// sheet (half side 1000 at heights 2 and 1) miss less than 1e-5 of the floor's cosine-weighted
// hemisphere. Tolerance: 4 standard errors of the mean of N independent samples.
TEST(PathClosures, EmissionBehindTransparentIsCollectedAfterTheLastBounce) {
    TestScene t;
    const float rho = 0.8f;
    const Rgb colour(0.6f, 0.3f, 0.9f), radiance(2.0f);
    t.add_quad(0.0f, 1000.0f, t.add_material({{Rgb(1.0f), make(STRATUM_MATERIAL_DIFFUSE, Rgb(rho))}}));
    t.add_quad(1.0f, 1000.0f, t.add_material({{Rgb(1.0f), make(STRATUM_MATERIAL_TRANSPARENT, colour)}}));
    Material glow = make(STRATUM_MATERIAL_EMISSION, Rgb(0.0f));
    glow.emission = radiance;
    t.add_quad(2.0f, 1000.0f, t.add_material({{Rgb(1.0f), glow}}));
    const RenderScene render_scene(t.scene);
    const auto sampler = find_sampler("random")->create(SamplerSettings{});
    const PathIntegrator integrator(direct_only());
    constexpr int kN = 200000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < kN; ++i) {
        uint64_t rays = 0;
        const CameraRay ray{{0.0f, 0.0f, 0.5f}, {0.0f, 0.0f, -1.0f}, 0.0f, kInfinity};
        const double v =
            integrator
                .radiance(render_scene, *sampler, PixelSample{0, 0, static_cast<uint32_t>(i)}, ray, rays)
                .radiance.b;
        sum += v;
        sum2 += v * v;
    }
    const double mean = sum / kN, std_error = std::sqrt(std::max(sum2 / kN - mean * mean, 0.0) / kN);
    const double expected = rho * colour.b * radiance.b;
    EXPECT_NEAR(mean, expected, 4.0 * std_error + 1e-5 * expected) << "std error " << std_error;
}

// Camera straight down at a holdout square over the floor.
RadianceSample look_down(const Scene& scene, bool film_transparent) {
    IntegratorSettings s = direct_only();
    s.film_transparent = film_transparent;
    return trace(scene, {0.0f, 0.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, s);
}

TEST(PathClosures, HoldoutGivesAlphaZeroWithOrWithoutATransparentFilm) {
    TestScene t = TestScene::lit_floor();
    t.add_quad(1.0f, 3.0f, t.add_material({{Rgb(1.0f), make(STRATUM_MATERIAL_HOLDOUT, Rgb(1.0f))}}));
    const RadianceSample transparent_film = look_down(t.scene, true);
    expect_rgb(transparent_film.radiance, Rgb(0.0f));
    EXPECT_EQ(transparent_film.alpha, 0.0f);
    // Cycles cuts alpha for holdouts whatever the film (measured in 3.4.1 and 5.0.1: a holdout
    // cube renders (0, 0, 0, 0) with Film > Transparent off).
    const RadianceSample opaque_film = look_down(t.scene, false);
    expect_rgb(opaque_film.radiance, Rgb(0.0f));
    EXPECT_EQ(opaque_film.alpha, 0.0f);
}

TEST(PathClosures, HalfHoldoutHalfEmissionGivesHalfAlpha) {
    TestScene t = TestScene::lit_floor();
    Material glow = make(STRATUM_MATERIAL_EMISSION, Rgb(0.0f));
    glow.emission = Rgb(2.0f, 1.0f, 0.5f);
    t.add_quad(1.0f, 3.0f,
               t.add_material({{Rgb(0.5f), make(STRATUM_MATERIAL_HOLDOUT, Rgb(1.0f))}, {Rgb(0.5f), glow}}));
    const RadianceSample r = look_down(t.scene, true);
    expect_rgb(r.radiance, glow.emission * 0.5f);
    EXPECT_FLOAT_EQ(r.alpha, 0.5f);
}

TEST(PathClosures, BackgroundSeenDirectlyIsTransparentOnlyWithATransparentFilm) {
    TestScene t;
    t.scene.background = Rgb(0.3f, 0.6f, 0.9f);
    const Rgb colour(0.5f, 0.25f, 1.0f);
    t.add_quad(1.0f, 3.0f, t.add_material({{Rgb(1.0f), make(STRATUM_MATERIAL_TRANSPARENT, colour)}}));
    // Looking up through the transparent square into the sky.
    IntegratorSettings s = direct_only();
    s.film_transparent = true;
    RadianceSample r = trace(t.scene, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 5.0f}, s);
    expect_rgb(r.radiance, Rgb(0.0f));
    EXPECT_FLOAT_EQ(r.alpha, 1.0f - colour.average());
    s.film_transparent = false;
    r = trace(t.scene, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 5.0f}, s);
    expect_rgb(r.radiance, colour * t.scene.background);
    EXPECT_EQ(r.alpha, 1.0f);
}

// A sphere of smooth white glass in a white world without lights: every path refracts or
// reflects with weight exactly 1 (Fresnel chooses, it does not scale) until it escapes to the
// background of radiance 1, so every sample is 1 (Russian roulette never fires at throughput 1).
TEST(PathClosures, SmoothGlassSphereInAWhiteWorldIsExactlyWhite) {
    TestScene t;
    t.scene.background = Rgb(1.0f);
    Mesh sphere;
    constexpr int kRings = 16, kSegments = 32;
    for (int i = 0; i <= kRings; ++i) {
        const float theta = kPi * static_cast<float>(i) / kRings;
        for (int j = 0; j < kSegments; ++j) {
            const float phi = 2.0f * kPi * static_cast<float>(j) / kSegments;
            sphere.positions.push_back(
                {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)});
        }
    }
    for (uint32_t i = 0; i < kRings; ++i) {
        for (uint32_t j = 0; j < kSegments; ++j) {
            const uint32_t a = i * kSegments + j, b = i * kSegments + (j + 1) % kSegments;
            sphere.triangles.push_back({a, a + kSegments, b});
            sphere.triangles.push_back({b, a + kSegments, b + kSegments});
        }
    }
    sphere.material_ids.assign(
        sphere.triangles.size(),
        t.add_material({{Rgb(1.0f), make(STRATUM_MATERIAL_GLASS, Rgb(1.0f), 0.0f, 1.45f)}}));
    t.scene.meshes.push_back(sphere);
    t.scene.instances.push_back({0, Transform{}});
    IntegratorSettings s;
    s.max_bounces = 256;
    for (uint32_t i = 0; i < 64; ++i) {
        const float x = -0.9f + 1.8f * static_cast<float>(i) / 63.0f;
        const RadianceSample r = trace(t.scene, {x, 0.1f, 4.0f}, {x, 0.1f, 0.0f}, s, i);
        expect_rgb(r.radiance, Rgb(1.0f));
    }
}

}  // namespace
}  // namespace stratum
