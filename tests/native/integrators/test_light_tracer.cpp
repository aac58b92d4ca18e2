// The light tracer (integrator `light`, textbook ch. 6) against the path tracer and closed
// forms, its determinism, border renders and notices.
//
// Statistics. A light-tracer particle splats into every pixel within the filter radius, so
// neighbouring pixels are correlated and the spread of pixel values does not give the standard
// error of an image mean. Each comparison therefore renders S independent images per estimator
// (seeds 1..S) and takes the image mean m_s of each: the m_s are independent and identically
// distributed, their mean M estimates the expectation with standard error σ = sd(m_s)/√S.
// Two estimators agree when |M_a − M_b| ≤ 4·√(σ_a² + σ_b²). With σ estimated from S = 8 seeds
// the ratio is t-distributed with about 14 degrees of freedom; |t| > 4 has probability 1.3e-3
// (seeds are fixed, so a passing test stays passing). Against a closed form the bound is
// 4σ_a. Scenes are 16×16 pixels at 32 samples: a few tenths of a second each in Release.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "render_helpers.h"

using namespace stratum_test;

namespace {

constexpr float kPiF = 3.14159265358979f;
constexpr int kSeeds = 8;
constexpr int64_t kSize = 16;

struct Image {
    std::vector<float> rgba;
    std::string notices;
};

struct Options {
    const char* integrator = "light";
    int64_t samples = 32;
    int64_t max_bounces = 12;
    int64_t diffuse_bounces = 1024, glossy_bounces = 1024;
    int64_t seed = 1;
    int64_t threads = 0;
    int64_t crop_x = 0, crop_y = 0, crop_width = 0, crop_height = 0;
};

Image render_image(StratumScene* scene, const Options& o) {
    Image out;
    StratumRenderer* r = nullptr;
    EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK) << stratum_last_error();
    for (const auto& [name, value] : {std::pair<const char*, int64_t>{"width", kSize},
                                      {"height", kSize},
                                      {"samples", o.samples},
                                      {"max_bounces", o.max_bounces},
                                      {"diffuse_bounces", o.diffuse_bounces},
                                      {"glossy_bounces", o.glossy_bounces},
                                      {"seed", o.seed},
                                      {"threads", o.threads},
                                      {"crop_x", o.crop_x},
                                      {"crop_y", o.crop_y},
                                      {"crop_width", o.crop_width},
                                      {"crop_height", o.crop_height}}) {
        EXPECT_EQ(stratum_renderer_set_int(r, name, value), STRATUM_OK)
            << name << ": " << stratum_last_error();
    }
    EXPECT_EQ(stratum_renderer_set_string(r, "integrator", o.integrator), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_string(r, "sampler", "random"), STRATUM_OK);
    EXPECT_TRUE(render_to_end(r)) << stratum_last_error();
    const char* notices = nullptr;
    EXPECT_EQ(stratum_renderer_notices(r, &notices), STRATUM_OK);
    out.notices = notices ? notices : "";
    StratumProgress progress{};
    EXPECT_EQ(stratum_renderer_progress(r, &progress), STRATUM_OK);
    // Camera samples and particles both count toward the progress bar, which ends full.
    EXPECT_DOUBLE_EQ(progress.fraction_done, 1.0);
    EXPECT_EQ(progress.samples_done, o.samples);
    const int64_t w = o.crop_width ? o.crop_width : kSize, h = o.crop_height ? o.crop_height : kSize;
    out.rgba.resize(static_cast<size_t>(w * h * 4));
    EXPECT_EQ(stratum_renderer_read_pixels(r, out.rgba.data(), out.rgba.size()), STRATUM_OK);
    stratum_renderer_destroy(r);
    return out;
}

struct Estimate {
    double mean[3], error[3];  // per channel: mean over seeds of the image mean, its standard error
};

Estimate estimate(StratumScene* scene, Options o) {
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int s = 1; s <= kSeeds; ++s) {
        o.seed = s;
        const Image img = render_image(scene, o);
        const size_t n = img.rgba.size() / 4;
        for (int c = 0; c < 3; ++c) {
            double m = 0;
            for (size_t i = 0; i < n; ++i) m += img.rgba[4 * i + c];
            m /= static_cast<double>(n);
            sum[c] += m;
            sum2[c] += m * m;
        }
    }
    Estimate e{};
    for (int c = 0; c < 3; ++c) {
        e.mean[c] = sum[c] / kSeeds;
        const double var = std::max(0.0, (sum2[c] - kSeeds * e.mean[c] * e.mean[c]) / (kSeeds - 1));
        e.error[c] = std::sqrt(var / kSeeds);
    }
    return e;
}

void expect_agree(const Estimate& a, const Estimate& b, const char* what) {
    for (int c = 0; c < 3; ++c) {
        const double tolerance = 4.0 * std::hypot(a.error[c], b.error[c]);
        EXPECT_NEAR(a.mean[c], b.mean[c], tolerance) << what << ", channel " << c;
        EXPECT_GT(a.mean[c], 0.0) << what;
    }
}

StratumMaterialDesc diffuse(float r, float g, float b) {
    return {STRATUM_MATERIAL_DIFFUSE, {r, g, b}, 1.0f, 0.0f, 0.0f, 1.5f, {0, 0, 0}, STRATUM_MICROFACET_GGX};
}

StratumMaterialDesc emission(float radiance) {
    return {STRATUM_MATERIAL_EMISSION, {0, 0, 0}, 1.0f, 0.0f, 0.0f, 1.5f, {radiance, radiance, radiance},
            STRATUM_MICROFACET_GGX};
}

// An axis-aligned rectangle [x0,x1]×[y0,y1] at height z, wound so its normal is +Z (up) or −Z.
void add_rectangle(StratumScene* scene, const StratumMaterialDesc& material, float x0, float x1, float y0,
                   float y1, float z, bool up) {
    uint32_t mat = 0, id = 0;
    ASSERT_EQ(stratum_scene_add_material(scene, &material, &mat), STRATUM_OK);
    const float positions[] = {x0, y0, z, x1, y0, z, x1, y1, z, x0, y1, z};
    const uint32_t up_tris[] = {0, 1, 2, 0, 2, 3}, down_tris[] = {0, 2, 1, 0, 3, 2};
    const uint32_t mats[] = {mat, mat};
    const StratumMeshDesc mesh{positions, 4, up ? up_tris : down_tris, 2, nullptr, nullptr, mats};
    ASSERT_EQ(stratum_scene_add_mesh(scene, &mesh, &id), STRATUM_OK);
    ASSERT_EQ(stratum_scene_add_instance(scene, id, kIdentity), STRATUM_OK);
}

// Issue 6 point 3: a Lambertian a×b panel of radiance L₀ (flux πL₀ab per face) at height 1
// lighting a diffuse floor, seen from a pinhole between them looking down.
StratumScene* panel_over_floor() {
    StratumScene* scene = nullptr;
    EXPECT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    add_rectangle(scene, diffuse(0.8f, 0.5f, 0.2f), -3, 3, -3, 3, 0.0f, true);
    add_rectangle(scene, emission(4.0f), -0.3f, 0.3f, -0.2f, 0.2f, 1.0f, false);
    const StratumCameraDesc camera = camera_at(0.1f, 0.0f, 0.6f);
    EXPECT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK);
    return scene;
}

// A closed diffuse sphere of radius 1 (reflectance k per channel) with a light inside and the
// camera inside: multiple bounces everywhere.
StratumScene* sphere_with_light(const StratumLightDesc& light, float k) {
    StratumScene* scene = make_sphere_interior(diffuse(k, 0.5f * k, 0.9f), 12, 0.1f, -0.2f, 0.3f);
    EXPECT_NE(scene, nullptr) << stratum_last_error();
    EXPECT_EQ(stratum_scene_add_light(scene, &light), STRATUM_OK) << stratum_last_error();
    return scene;
}

StratumLightDesc point_light(float power) {
    StratumLightDesc l{};
    l.type = STRATUM_LIGHT_POINT;
    l.color[0] = l.color[1] = l.color[2] = 1.0f;
    l.strength = power;
    std::copy(kIdentity, kIdentity + 16, l.transform);
    l.transform[3] = -0.2f;
    l.transform[7] = 0.3f;
    l.transform[11] = -0.1f;
    l.spot_size = kPiF;
    return l;
}

StratumLightDesc area_light(float power) {
    StratumLightDesc l = point_light(power);
    l.type = STRATUM_LIGHT_AREA_RECTANGLE;
    l.size_x = 0.4f;
    l.size_y = 0.3f;
    l.transform[11] = 0.5f;  // facing down (local −Z), near the top of the sphere
    return l;
}

}  // namespace

TEST(LightTracer, PanelOverFloorMatchesThePathTracer) {
    StratumScene* scene = panel_over_floor();
    const Estimate light = estimate(scene, {"light"});
    const Estimate path = estimate(scene, {"path"});
    expect_agree(light, path, "panel over floor");
    stratum_scene_destroy(scene);
}

// Integrating sphere B (textbook §3.3, research digest test B) by light tracing: every wall
// emits L_e, reflectance k; with the bounce cap b the radiance is L_e Σ_{m=0}^{b+1} k^m. The
// camera-ray part gives L_e (m = 0), particles connecting at their m-th vertex give the rest.
TEST(LightTracer, EmissiveSphereGivesTheClosedForm) {
    const float k = 0.5f, le = 1.0f;
    StratumMaterialDesc wall = diffuse(k, k, k);
    wall.emission[0] = wall.emission[1] = wall.emission[2] = le;
    StratumScene* scene = make_sphere_interior(wall, 12, 0.1f, -0.2f, 0.3f);
    ASSERT_NE(scene, nullptr);
    for (const int64_t bounces : {0, 2, 24}) {
        Options o;
        o.max_bounces = bounces;
        const Estimate e = estimate(scene, o);
        double expected = 0, term = le;
        for (int m = 0; m <= bounces + 1; ++m, term *= k) expected += term;
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(e.mean[c], expected, 4.0 * e.error[c])
                << "max_bounces " << bounces << ", channel " << c;
    }
    stratum_scene_destroy(scene);
}

TEST(LightTracer, PointLightInADiffuseSphereMatchesThePathTracer) {
    StratumScene* scene = sphere_with_light(point_light(20.0f), 0.7f);
    for (const int64_t bounces : {1, 12}) {
        Options light, path;
        path.integrator = "path";
        light.max_bounces = path.max_bounces = bounces;
        expect_agree(estimate(scene, light), estimate(scene, path), "point light");
    }
    stratum_scene_destroy(scene);
}

TEST(LightTracer, AreaLampInADiffuseSphereMatchesThePathTracer) {
    StratumScene* scene = sphere_with_light(area_light(20.0f), 0.7f);
    Options path;
    path.integrator = "path";
    expect_agree(estimate(scene, {}), estimate(scene, path), "area lamp");
    stratum_scene_destroy(scene);
}

TEST(LightTracer, ThinLensCameraMatchesThePathTracer) {
    StratumScene* scene = panel_over_floor();
    StratumCameraDesc camera = camera_at(0.1f, 0.0f, 0.6f);
    camera.aperture_radius = 0.05f;
    camera.focus_distance = 0.3f;  // the floor (0.6 below) is out of focus
    ASSERT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK) << stratum_last_error();
    Options path;
    path.integrator = "path";
    expect_agree(estimate(scene, {}), estimate(scene, path), "thin lens");
    stratum_scene_destroy(scene);
}

TEST(LightTracer, SameSeedIsBitIdenticalForAnyThreadCount) {
    StratumScene* scene = sphere_with_light(area_light(20.0f), 0.7f);
    Options one, two;
    one.threads = 1;
    two.threads = 2;
    one.samples = two.samples = 8;
    const Image a = render_image(scene, one), b = render_image(scene, two), c = render_image(scene, two);
    ASSERT_EQ(a.rgba.size(), b.rgba.size());
    EXPECT_EQ(std::memcmp(a.rgba.data(), b.rgba.data(), a.rgba.size() * sizeof(float)), 0);
    EXPECT_EQ(std::memcmp(b.rgba.data(), c.rgba.data(), b.rgba.size() * sizeof(float)), 0);
    stratum_scene_destroy(scene);
}

TEST(LightTracer, BorderRenderEqualsTheCropOfTheFullRender) {
    StratumScene* scene = sphere_with_light(area_light(20.0f), 0.7f);
    Options full, border;
    full.samples = border.samples = 8;
    border.crop_x = 3;
    border.crop_y = 5;
    border.crop_width = 7;
    border.crop_height = 6;
    const Image f = render_image(scene, full), b = render_image(scene, border);
    for (int64_t y = 0; y < border.crop_height; ++y) {
        for (int64_t x = 0; x < border.crop_width; ++x) {
            for (int c = 0; c < 4; ++c) {
                const float in_full = f.rgba[4 * ((y + border.crop_y) * kSize + x + border.crop_x) + c];
                EXPECT_EQ(b.rgba[4 * (y * border.crop_width + x) + c], in_full) << x << "," << y << "," << c;
            }
        }
    }
    stratum_scene_destroy(scene);
}

TEST(LightTracer, OrthographicCameraRendersWhatItSeesDirectlyAndSaysWhy) {
    StratumScene* scene = panel_over_floor();
    StratumCameraDesc camera = camera_at(0.0f, 0.0f, 0.6f);
    camera.type = STRATUM_CAMERA_ORTHOGRAPHIC;
    camera.ortho_scale = 2.0f;
    ASSERT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK) << stratum_last_error();
    const Image img = render_image(scene, {});
    EXPECT_NE(img.notices.find("orthographic"), std::string::npos) << img.notices;
    // Only the camera-ray part: the floor (not emissive) is black.
    for (size_t i = 0; i < img.rgba.size(); i += 4) EXPECT_EQ(img.rgba[i], 0.0f);
    Options path;
    path.integrator = "path";
    EXPECT_EQ(render_image(scene, path).notices, "");
    stratum_scene_destroy(scene);
}

TEST(LightTracer, PerspectiveDiffuseSceneHasNoNotice) {
    StratumScene* scene = panel_over_floor();
    EXPECT_EQ(render_image(scene, {}).notices, "");
    stratum_scene_destroy(scene);
}

namespace {

// A Cornell box (issue 6 point 4's scene): 2×2×2, open on the camera's side (+Y), Principled
// walls (Cycles 4.x model, roughness 0.5: a diffuse base under a glossy coat), coloured side
// walls, a rectangular area lamp under the ceiling.
StratumScene* principled_cornell_box() {
    StratumScene* scene = nullptr;
    EXPECT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    const auto principled = [](float r, float g, float b) {
        StratumMaterialDesc m = diffuse(r, g, b);
        m.model = STRATUM_MATERIAL_PRINCIPLED_V2;
        m.roughness = 0.5f;
        m.specular = 0.5f;
        return m;
    };
    const auto add_quad = [&](const StratumMaterialDesc& material, const float(&p)[12]) {
        uint32_t mat = 0, id = 0;
        ASSERT_EQ(stratum_scene_add_material(scene, &material, &mat), STRATUM_OK);
        const uint32_t triangles[] = {0, 1, 2, 0, 2, 3}, mats[] = {mat, mat};
        const StratumMeshDesc mesh{p, 4, triangles, 2, nullptr, nullptr, mats};
        ASSERT_EQ(stratum_scene_add_mesh(scene, &mesh, &id), STRATUM_OK);
        ASSERT_EQ(stratum_scene_add_instance(scene, id, kIdentity), STRATUM_OK);
    };
    // Box [−1,1]×[−1,1]×[0,2], seen along −Y from y = 3.5 through the open side y = 1.
    add_quad(principled(0.7f, 0.7f, 0.7f), {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0});    // floor
    add_quad(principled(0.7f, 0.7f, 0.7f), {-1, -1, 2, -1, 1, 2, 1, 1, 2, 1, -1, 2});    // ceiling
    add_quad(principled(0.7f, 0.7f, 0.7f), {-1, -1, 0, -1, -1, 2, 1, -1, 2, 1, -1, 0});  // back
    add_quad(principled(0.7f, 0.1f, 0.1f), {-1, -1, 0, -1, 1, 0, -1, 1, 2, -1, -1, 2});  // left
    add_quad(principled(0.1f, 0.7f, 0.1f), {1, -1, 0, 1, -1, 2, 1, 1, 2, 1, 1, 0});      // right
    StratumLightDesc lamp = area_light(30.0f);
    lamp.transform[3] = 0.0f;
    lamp.transform[7] = 0.0f;
    lamp.transform[11] = 1.95f;
    // Hidden from the camera: its directly seen radiance (80) on a few edge pixels would swamp
    // the variance of the image mean, and both estimators see it by the same camera rays anyway.
    lamp.visibility = STRATUM_VISIBLE_ALL & ~STRATUM_VISIBLE_CAMERA;
    EXPECT_EQ(stratum_scene_add_light(scene, &lamp), STRATUM_OK) << stratum_last_error();
    // Camera at (0, 3.5, 1) looking along −Y: camera −Z maps to world −Y, camera +Y to world +Z
    // (and camera +X to world −X, a rotation).
    StratumCameraDesc camera = camera_at(0, 0, 0);
    const float to_world[16] = {-1, 0, 0, 0, 0, 0, 1, 3.5f, 0, 1, 0, 1, 0, 0, 0, 1};
    std::copy(to_world, to_world + 16, camera.transform);
    EXPECT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK);
    return scene;
}

}  // namespace

TEST(LightTracer, PrincipledCornellBoxMatchesThePathTracer) {
    StratumScene* scene = principled_cornell_box();
    Options path;
    path.integrator = "path";
    expect_agree(estimate(scene, {}), estimate(scene, path), "Cornell box");
    stratum_scene_destroy(scene);
}

// Cycles' per-kind limits read along the camera path: a particle's connection counts its own
// scattering and the particle's after the first hit. A diffuse sphere around a rough glossy
// panel under an area lamp: paths mix diffuse and glossy scatterings in every order, and each
// pair of limits removes different ones (the path tracer applies them as Cycles does).
TEST(LightTracer, PerKindBounceLimitsMatchThePathTracer) {
    StratumScene* scene = sphere_with_light(area_light(20.0f), 0.7f);
    StratumMaterialDesc glossy = diffuse(0.9f, 0.8f, 0.7f);
    glossy.model = STRATUM_MATERIAL_GLOSSY;
    glossy.roughness = 0.4f;
    add_rectangle(scene, glossy, -0.4f, 0.4f, -0.4f, 0.4f, -0.5f, true);
    for (const auto& [diffuse_limit, glossy_limit] :
         {std::pair<int64_t, int64_t>{1, 1024}, {1024, 0}, {0, 1}}) {
        Options light, path;
        path.integrator = "path";
        light.diffuse_bounces = path.diffuse_bounces = diffuse_limit;
        light.glossy_bounces = path.glossy_bounces = glossy_limit;
        const std::string what =
            "diffuse " + std::to_string(diffuse_limit) + ", glossy " + std::to_string(glossy_limit);
        expect_agree(estimate(scene, light), estimate(scene, path), what.c_str());
    }
    stratum_scene_destroy(scene);
}

namespace {

// A diffuse floor just larger than the view of a camera 0.6 above it: the sun's and the
// environment's beams cover the scene's bounding sphere (radius 1 here), so most particles land
// in view.
StratumScene* small_floor() {
    StratumScene* scene = nullptr;
    EXPECT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    add_rectangle(scene, diffuse(0.8f, 0.5f, 0.2f), -0.7f, 0.7f, -0.7f, 0.7f, 0.0f, true);
    const StratumCameraDesc camera = camera_at(0.0f, 0.0f, 0.6f);
    EXPECT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK);
    return scene;
}

}  // namespace

// Every other light model's emission (the point light and the emissive triangles are above):
// a spot with a soft edge in the sphere, a sun (delta and with an angle) and an environment over
// an open floor, each against the path tracer.
TEST(LightTracer, SpotSunAndEnvironmentMatchThePathTracer) {
    Options path;
    path.integrator = "path";
    {
        StratumLightDesc spot = point_light(20.0f);
        spot.type = STRATUM_LIGHT_SPOT;
        spot.spot_size = 1.2f;
        spot.spot_blend = 0.4f;
        StratumScene* scene = sphere_with_light(spot, 0.6f);
        expect_agree(estimate(scene, {}), estimate(scene, path), "spot");
        stratum_scene_destroy(scene);
    }
    for (const float angle : {0.0f, 0.3f}) {
        StratumScene* scene = small_floor();
        StratumLightDesc sun = point_light(2.0f);
        sun.type = STRATUM_LIGHT_SUN;
        sun.angle = angle;
        // Toward the sun = light +Z rotated 40° about X.
        const float c = std::cos(0.7f), s = std::sin(0.7f);
        const float rotation[16] = {1, 0, 0, 0, 0, c, -s, 0, 0, s, c, 0, 0, 0, 0, 1};
        std::copy(rotation, rotation + 16, sun.transform);
        ASSERT_EQ(stratum_scene_add_light(scene, &sun), STRATUM_OK) << stratum_last_error();
        expect_agree(estimate(scene, {}), estimate(scene, path), angle > 0 ? "sun with angle" : "delta sun");
        stratum_scene_destroy(scene);
    }
    {
        StratumScene* scene = small_floor();
        // 4×2 sky, brighter toward +X and overhead.
        const float sky[] = {0.2f, 0.3f, 0.5f, 0.4f, 0.4f, 0.6f, 1.5f, 1.2f, 1.0f, 0.3f, 0.3f, 0.5f,
                             0.0f, 0.0f, 0.0f, 0.1f, 0.1f, 0.1f, 0.3f, 0.2f, 0.1f, 0.0f, 0.0f, 0.0f};
        ASSERT_EQ(stratum_scene_set_environment(scene, sky, 4, 2, 1.0f, nullptr), STRATUM_OK)
            << stratum_last_error();
        expect_agree(estimate(scene, {}), estimate(scene, path), "environment");
        stratum_scene_destroy(scene);
    }
}

TEST(LightTracer, TransmissiveClosuresAreNoticed) {
    StratumScene* scene = panel_over_floor();
    StratumMaterialDesc glass = diffuse(1, 1, 1);
    glass.model = STRATUM_MATERIAL_GLASS;
    add_rectangle(scene, glass, -0.2f, 0.2f, -0.2f, 0.2f, 0.3f, true);
    Options o;
    o.samples = 1;
    EXPECT_NE(render_image(scene, o).notices.find("refract"), std::string::npos);
    stratum_scene_destroy(scene);
}

// A constant background (Blender's world colour) lights the scene through escaping paths of the
// path tracer; the light tracer emits it as a uniform sky, alone and shared with a lamp.
TEST(LightTracer, ConstantBackgroundLightsLikeTheSky) {
    Options path;
    path.integrator = "path";
    for (const bool with_lamp : {false, true}) {
        StratumScene* scene = small_floor();
        const float sky[3] = {0.3f, 0.5f, 0.8f};
        ASSERT_EQ(stratum_scene_set_background(scene, sky), STRATUM_OK);
        if (with_lamp) {
            StratumLightDesc lamp = point_light(3.0f);
            lamp.transform[11] = 0.4f;
            ASSERT_EQ(stratum_scene_add_light(scene, &lamp), STRATUM_OK);
        }
        expect_agree(estimate(scene, {}), estimate(scene, path), with_lamp ? "sky and lamp" : "sky");
        stratum_scene_destroy(scene);
    }
}

TEST(LightTracer, MovingEmissiveObjectsAreNoticed) {
    StratumScene* scene = small_floor();
    uint32_t mat = 0, id = 0;
    const StratumMaterialDesc glow = emission(2.0f);
    ASSERT_EQ(stratum_scene_add_material(scene, &glow, &mat), STRATUM_OK);
    const float positions[] = {-0.1f, -0.1f, 0.3f, 0.1f, -0.1f, 0.3f, 0.1f, 0.1f, 0.3f};
    const uint32_t triangles[] = {0, 2, 1}, mats[] = {mat};
    const StratumMeshDesc mesh{positions, 3, triangles, 1, nullptr, nullptr, mats};
    ASSERT_EQ(stratum_scene_add_mesh(scene, &mesh, &id), STRATUM_OK);
    StratumInstanceDesc moving{};
    moving.mesh_id = id;
    std::copy(kIdentity, kIdentity + 16, moving.transform);
    std::copy(kIdentity, kIdentity + 16, moving.transform_end);
    moving.transform_end[3] = 0.2f;
    moving.motion = 1;
    moving.visibility = STRATUM_VISIBLE_ALL;
    ASSERT_EQ(stratum_scene_add_instance_ex(scene, &moving), STRATUM_OK) << stratum_last_error();
    Options o;
    o.samples = 1;
    EXPECT_NE(render_image(scene, o).notices.find("moving emissive"), std::string::npos);
    stratum_scene_destroy(scene);
}
