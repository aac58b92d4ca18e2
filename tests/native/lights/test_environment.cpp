// The environment light (lights/environment_light.h): lookups against the constant background,
// the floor's irradiance against a quadrature of the image, the sampling density against its
// own histogram, and validation at the C ABI.
//
// Floor tests: a diffuse floor (reflectance k, z = 0, 20 x 20) seen straight down through a
// 5000 mm lens, max_bounces 0; its radiance is (k/π)·E with E = ∫ L cos θ dω over the upper
// hemisphere, which is the same at every floor point (the environment is at infinity and the
// floor occludes nothing above it). Tolerance 4·s/√P (s the spread of the P pixel values).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "chi_square.h"
#include "lights/environment_light.h"
#include "render_helpers.h"
#include "scene_handle.h"

using namespace stratum_test;

namespace {

constexpr double kPiD = 3.14159265358979323846;
constexpr float kReflectance = 0.5f;

struct EnvFloor : SceneHandle {
    EnvFloor() {
        const StratumMaterialDesc floor = diffuse_grey(kReflectance);
        uint32_t mat = 0;
        EXPECT_EQ(stratum_scene_add_material(scene, &floor, &mat), STRATUM_OK);
        EXPECT_TRUE(add_square_instance(scene, 0.0f, 10.0f, mat)) << stratum_last_error();
    }

    // Pixels of a 16x16 render from (0, 0, 1), looking down (or up at the sky).
    std::vector<float> render_view(bool look_up, int64_t samples = 64) {
        StratumCameraDesc camera = camera_at(0, 0, 1);
        if (look_up) {  // rotate 180° about X: looks down world +Z
            camera.transform[5] = -1.0f;
            camera.transform[10] = -1.0f;
        } else {
            camera.lens_mm = 5000.0f;
        }
        EXPECT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK);
        return render(scene, {{"width", 16}, {"height", 16}, {"samples", samples}, {"max_bounces", 0}}).rgba;
    }
};

struct Stats {
    double mean, standard_error;
};

Stats channel_stats(const std::vector<float>& rgba, int channel) {
    const size_t n = rgba.size() / 4;
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < n; ++i) {
        const double v = rgba[4 * i + static_cast<size_t>(channel)];
        sum += v;
        sum2 += v * v;
    }
    const double mean = sum / static_cast<double>(n);
    const double var =
        std::max(0.0, (sum2 - static_cast<double>(n) * mean * mean) / static_cast<double>(n - 1));
    return {mean, std::sqrt(var / static_cast<double>(n))};
}

void expect_floor_radiance(const std::vector<float>& rgba, int channel, double irradiance) {
    ASSERT_EQ(rgba.size(), 16u * 16u * 4u);
    const Stats s = channel_stats(rgba, channel);
    const double expected = kReflectance / kPiD * irradiance;
    EXPECT_NEAR(s.mean, expected, 4.0 * s.standard_error + 1e-6 * expected)
        << "channel " << channel << " measured " << s.mean << " expected " << expected << " (se "
        << s.standard_error << ")";
}

}  // namespace

TEST(Environment, ConstantImageMatchesTheConstantBackground) {
    const float background[3] = {1.0f, 0.5f, 0.25f};
    // 0.5 × strength 2 = the background, exactly representable.
    std::vector<float> image(8 * 4 * 3);
    for (size_t k = 0; k < image.size(); k += 3) {
        image[k] = 0.5f;
        image[k + 1] = 0.25f;
        image[k + 2] = 0.125f;
    }
    EnvFloor constant, environment;
    ASSERT_EQ(stratum_scene_set_background(constant.scene, background), STRATUM_OK);
    ASSERT_EQ(stratum_scene_set_environment(environment.scene, image.data(), 8, 4, 2.0f, nullptr),
              STRATUM_OK);
    // Sky: camera rays that miss take the lookup with weight 1, bit for bit.
    const std::vector<float> sky_a = constant.render_view(true), sky_b = environment.render_view(true);
    ASSERT_EQ(sky_a.size(), 16u * 16u * 4u);
    EXPECT_EQ(sky_a, sky_b);
    EXPECT_EQ(sky_b[0], 1.0f);
    EXPECT_EQ(sky_b[2], 0.25f);
    // Floor: E = π L for a uniform sky. The constant background is found by BSDF rays only; the
    // environment by NEE and BSDF rays under MIS: both must give k·L.
    for (int c = 0; c < 3; ++c) {
        expect_floor_radiance(constant.render_view(false), c, kPiD * background[c]);
        expect_floor_radiance(environment.render_view(false), c, kPiD * background[c]);
    }
}

TEST(Environment, FloorIrradianceIsTheIntegralOfTheImage) {
    // 32 x 16: a bright band around the zenith varying with φ, a dimmer band down to the
    // horizon, and a very bright ground (below the horizon) that the floor must not see.
    constexpr uint32_t W = 32, H = 16;
    std::vector<float> image(W * H * 3, 0.0f);
    for (uint32_t j = 0; j < H; ++j) {
        for (uint32_t i = 0; i < W; ++i) {
            float value = 0.0f;
            if (j < 3)
                value = 4.0f * (1.0f + 0.8f * std::cos(2.0f * 3.14159265f * static_cast<float>(i) / W));
            else if (j < 8)
                value = 0.2f;
            else
                value = 50.0f;
            float* p = &image[3 * (j * W + i)];
            p[0] = value;
            p[1] = 0.5f * value;
            p[2] = j < 3 ? 0.0f : value;
        }
    }
    // Independent quadrature: texel (i, j) spans θ ∈ [jπ/H, (j+1)π/H] and 2π/W in φ, so its
    // ∫ cos θ dω over the upper hemisphere is (2π/W)·(sin²θ₁ − sin²θ₀)/2 (θ₁ ≤ π/2).
    std::array<double, 3> irradiance{0, 0, 0};
    for (uint32_t j = 0; j < H / 2; ++j) {
        const double t0 = kPiD * j / H, t1 = kPiD * (j + 1) / H;
        const double weight =
            2.0 * kPiD / W * 0.5 * (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0));
        for (uint32_t i = 0; i < W; ++i)
            for (int c = 0; c < 3; ++c)
                irradiance[static_cast<size_t>(c)] += weight * image[3 * (j * W + i) + c];
    }
    EnvFloor f;
    const float strength = 1.5f;
    // A rotation about Z (90°) moves the image around the vertical: E is unchanged.
    const float rotation[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
    ASSERT_EQ(stratum_scene_set_environment(f.scene, image.data(), W, H, strength, rotation), STRATUM_OK);
    const std::vector<float> rgba = f.render_view(false, 128);
    for (int c = 0; c < 3; ++c) expect_floor_radiance(rgba, c, strength * irradiance[static_cast<size_t>(c)]);
}

TEST(Environment, LookupFollowsCyclesEquirectangularMapping) {
    // One lit texel per direction of interest on an 8 x 4 image; the others stay black.
    auto lit = [](uint32_t i, uint32_t j) {
        std::vector<float> image(8 * 4 * 3, 0.0f);
        image[3 * (j * 8 + i)] = 1.0f;
        return stratum::EnvironmentLight(image, 8, 4, {1, 0, 0, 0, 1, 0, 0, 0, 1});
    };
    // u = 0.5 − atan2(y, x)/2π: +X at the centre column (u 0.5 → i = 4), −Y at u = 0.75 (i = 6),
    // +Y at u = 0.25 (i = 2); v = 1 − θ/π: rows from the top.
    EXPECT_EQ(lit(4, 1).radiance(stratum::normalize({1, 0, 0.1f})).r, 1.0f);
    EXPECT_EQ(lit(6, 1).radiance(stratum::normalize({0, -1, 0.1f})).r, 1.0f);
    EXPECT_EQ(lit(2, 2).radiance(stratum::normalize({0, 1, -0.1f})).r, 1.0f);
    EXPECT_EQ(lit(0, 0).radiance(stratum::normalize({-1, 0.01f, 3})).r, 1.0f);
    EXPECT_EQ(lit(0, 0).radiance(stratum::normalize({1, 0, 3})).r, 0.0f);
}

TEST(Environment, SamplingDensityIntegratesToOneAndMatchesTheHistogram) {
    constexpr uint32_t W = 16, H = 8;
    std::vector<float> image(W * H * 3);
    for (uint32_t j = 0; j < H; ++j)
        for (uint32_t i = 0; i < W; ++i)
            for (int c = 0; c < 3; ++c)
                image[3 * (j * W + i) + c] =
                    (i == 3 && j == 2) ? 40.0f : 0.1f + static_cast<float>((i * 7 + j * 3) % 5);
    // Row 5 black: zero density there, and no samples.
    for (uint32_t i = 0; i < W; ++i)
        for (int c = 0; c < 3; ++c) image[3 * (5 * W + i) + c] = 0.0f;
    // No rotation here: texel edges then fall on the edges of the test's fine quadrature grid
    // (π/8 = 128 θ cells, 2π/16 = 50 φ cells), so the expected counts are exact.
    const stratum::EnvironmentLight env(image, W, H, {1, 0, 0, 0, 1, 0, 0, 0, 1});
    int mismatches = 0;
    const auto r = stratum::chi_square::chi_square_directions(
        [&](stratum::Vec2 u, float, stratum::Vec3* w) {
            stratum::LightSample ls;
            if (!env.sample(stratum::Vec3(), stratum::Vec3(), u, stratum::TriangleSampling::SolidAngle, &ls))
                return false;
            // The returned pdf is the one pdf() reports for that direction (but on texel edges,
            // where the lookup may round to the neighbour).
            if (std::abs(ls.pdf - env.pdf(ls.wi)) > 1e-4f * ls.pdf) ++mismatches;
            EXPECT_TRUE(ls.found_by_bsdf_rays);
            *w = ls.wi;
            return true;
        },
        [&](stratum::Vec3 w) { return env.pdf(w); }, 7, 200000, 1024, 800);
    EXPECT_LT(mismatches, 20);
    EXPECT_NEAR(r.density_mass, 1.0, 3e-3);
    EXPECT_GT(r.p_value, 1e-3) << "chi2 " << r.statistic << " dof " << r.dof;
}

TEST(Environment, RotationTurnsSamplesAndLookups) {
    // With world-to-environment rotation R, every sample and density is the unrotated one
    // seen through Rᵀ: sample(u) = Rᵀ·sample₀(u), pdf(w) = pdf₀(R·w), radiance likewise.
    constexpr uint32_t W = 16, H = 8;
    std::vector<float> image(W * H * 3);
    for (size_t k = 0; k < image.size(); ++k) image[k] = 0.1f + static_cast<float>((k * 7) % 11);
    const float c = 0.8660254f, s = 0.5f;  // 30° about X
    const std::array<float, 9> R{1, 0, 0, 0, c, -s, 0, s, c};
    const stratum::EnvironmentLight plain(image, W, H, {1, 0, 0, 0, 1, 0, 0, 0, 1}), turned(image, W, H, R);
    for (int k = 0; k < 200; ++k) {
        const stratum::Vec2 u{(static_cast<float>(k) + 0.5f) / 200.0f,
                              std::fmod(0.618034f * static_cast<float>(k), 1.0f)};
        stratum::LightSample a, b;
        ASSERT_TRUE(
            plain.sample(stratum::Vec3(), stratum::Vec3(), u, stratum::TriangleSampling::SolidAngle, &a));
        ASSERT_TRUE(
            turned.sample(stratum::Vec3(), stratum::Vec3(), u, stratum::TriangleSampling::SolidAngle, &b));
        const stratum::Vec3 rw(R[0] * b.wi.x + R[1] * b.wi.y + R[2] * b.wi.z,
                               R[3] * b.wi.x + R[4] * b.wi.y + R[5] * b.wi.z,
                               R[6] * b.wi.x + R[7] * b.wi.y + R[8] * b.wi.z);
        EXPECT_NEAR(rw.x, a.wi.x, 1e-5f);
        EXPECT_NEAR(rw.y, a.wi.y, 1e-5f);
        EXPECT_NEAR(rw.z, a.wi.z, 1e-5f);
        EXPECT_NEAR(b.pdf, a.pdf, 1e-3f * a.pdf);
        EXPECT_EQ(b.radiance.r, a.radiance.r);
    }
}

TEST(Environment, ValidationNamesTheBadValue) {
    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    std::vector<float> image(4 * 2 * 3, 1.0f);
    auto expect_error = [&](const float* rgb, uint32_t w, uint32_t h, float strength, const float* rotation,
                            const std::string& fragment) {
        EXPECT_EQ(stratum_scene_set_environment(scene, rgb, w, h, strength, rotation),
                  STRATUM_ERROR_INVALID_ARGUMENT);
        EXPECT_NE(std::string(stratum_last_error()).find(fragment), std::string::npos)
            << stratum_last_error();
    };
    expect_error(nullptr, 4, 2, 1.0f, nullptr, "environment rgb is NULL");
    expect_error(image.data(), 0, 2, 1.0f, nullptr, "environment size 0 x 2");
    expect_error(image.data(), 4, 2, -1.0f, nullptr, "environment strength = -1");
    expect_error(image.data(), 4, 2, NAN, nullptr, "environment strength = nan");
    image[3 * (1 * 4 + 2) + 1] = -0.5f;
    expect_error(image.data(), 4, 2, 1.0f, nullptr, "environment pixel (2, 1) channel 1 = -0.5");
    image[3 * (1 * 4 + 2) + 1] = INFINITY;
    expect_error(image.data(), 4, 2, 1.0f, nullptr, "environment pixel (2, 1) channel 1 = inf");
    image[3 * (1 * 4 + 2) + 1] = 1.0f;
    const float scaled[9] = {2, 0, 0, 0, 1, 0, 0, 0, 1};
    expect_error(image.data(), 4, 2, 1.0f, scaled,
                 "environment rotation is not a rotation: row 0 · row 0 = 4");
    const float nan_rotation[9] = {1, 0, 0, 0, NAN, 0, 0, 0, 1};
    expect_error(image.data(), 4, 2, 1.0f, nan_rotation, "environment rotation element 4 = nan");
    EXPECT_EQ(stratum_scene_set_environment(scene, image.data(), 4, 2, 1.0f, nullptr), STRATUM_OK);
    stratum_scene_destroy(scene);
}

TEST(Environment, SurvivesSaveAndLoad) {
    EnvFloor f;
    std::vector<float> image(4 * 2 * 3);
    for (size_t k = 0; k < image.size(); ++k) image[k] = 0.25f * static_cast<float>(k % 7);
    const float rotation[9] = {0, -1, 0, 1, 0, 0, 0, 0, 1};
    ASSERT_EQ(stratum_scene_set_environment(f.scene, image.data(), 4, 2, 3.0f, rotation), STRATUM_OK);
    const std::string path = testing::TempDir() + "stratum_environment_scene.json";
    ASSERT_EQ(stratum_scene_save(f.scene, path.c_str()), STRATUM_OK) << stratum_last_error();
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(path.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    const std::vector<float> a = f.render_view(true, 4);
    StratumCameraDesc camera = camera_at(0, 0, 1);
    camera.transform[5] = -1.0f;
    camera.transform[10] = -1.0f;
    ASSERT_EQ(stratum_scene_set_camera(loaded, &camera), STRATUM_OK);
    const std::vector<float> b =
        render(loaded, {{"width", 16}, {"height", 16}, {"samples", 4}, {"max_bounces", 0}}).rgba;
    EXPECT_EQ(a, b);
    stratum_scene_destroy(loaded);
    std::remove(path.c_str());
}
