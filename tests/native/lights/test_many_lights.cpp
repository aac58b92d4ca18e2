// Many point lights over a diffuse floor, against a closed sum (issue 16, acceptance 1: every
// light-selection mode unbiased for N = 1, 16 and 1024 lights).
//
// | quantity | value                                                                        |
// |----------|------------------------------------------------------------------------------|
// | floor    | z = 0, Lambertian reflectance k = 0.5, half side 50 (beyond the frame)        |
// | lamps    | N point lamps (radius 0), a √N × √N grid of pitch 0.25 over the origin at     |
// |          | height h = 0.6; powers P_i = P₀(1 + 9 f_i), f_i = (37 i mod N)/N, so power    |
// |          | and uniform selection differ                                                 |
// | camera   | orthographic, straight down from z = 5, ortho_scale 2: the frame is the floor |
// |          | square [−1, 1]²                                                              |
// | render   | 32 × 32, 64 spp, box filter of width 1 (each pixel averages exactly its       |
// |          | footprint), max_bounces 0                                                    |
//
// Closed form. A lamp of power P has intensity I = P/(4π) (lights/point_light.h), so it gives a
// floor point at offset (x, y) from its foot the irradiance I h/(x² + y² + h²)^{3/2}, and the
// floor's radiance is k/π times the sum over lamps. The image mean is the mean radiance over the
// frame F = [−a, a]², a = 1; the integral of h/(x² + y² + h²)^{3/2} over a rectangle is the solid
// angle it subtends from the lamp, Ω = Σ_corners ± atan(XY / (h √(X² + Y² + h²))) (X, Y the
// corner's offsets from the foot; signs + for (x₂, y₂), (x₁, y₁), − for the mixed corners). So
//     mean = (k/π) Σ_i I_i Ω_i / (4a²),
// with no approximation: nothing blocks a shadow ray, a point lamp is never hit, and with box
// filtering of width 1 the pixels tile the frame.
//
// Tolerance: 4 standard errors of the mean over R = 16 seeds, s_R/√R from the spread of the 16
// image means (the image itself is not uniform, so the pixel spread is not noise); with 15
// degrees of freedom P(|t| > 4) ≈ 1e-3, and the seeds are fixed. Every light-selection choice
// the library lists is tested, so a new one (the light tree) is covered without editing this.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "render_helpers.h"
#include "scene_handle.h"
#include "setting_choices.h"

using namespace stratum_test;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kReflectance = 0.5f;
constexpr float kHeight = 0.6f;
constexpr float kPitch = 0.25f;
constexpr float kHalfFrame = 1.0f;
constexpr double kBasePower = 2.0;
constexpr uint32_t kSeeds = 16;

struct Lamp {
    float x, y;
    double power;
};

std::vector<Lamp> lamp_grid(uint32_t n) {
    const auto side = static_cast<uint32_t>(std::lround(std::sqrt(static_cast<double>(n))));
    std::vector<Lamp> lamps;
    for (uint32_t i = 0; i < n; ++i) {
        const float x = (static_cast<float>(i % side) - 0.5f * static_cast<float>(side - 1)) * kPitch;
        const float y = (static_cast<float>(i / side) - 0.5f * static_cast<float>(side - 1)) * kPitch;
        const double f = static_cast<double>((37u * i) % n) / static_cast<double>(n);
        lamps.push_back({x, y, kBasePower * (1.0 + 9.0 * f)});
    }
    return lamps;
}

// Solid angle of the floor rectangle [x1, x2] × [y1, y2] (offsets from the lamp's foot) seen from
// height h: the integral of h / (x² + y² + h²)^{3/2} over it.
double rectangle_solid_angle(double x1, double x2, double y1, double y2, double h) {
    const auto corner = [h](double x, double y) {
        return std::atan(x * y / (h * std::sqrt(x * x + y * y + h * h)));
    };
    return corner(x2, y2) - corner(x1, y2) - corner(x2, y1) + corner(x1, y1);
}

double expected_mean_radiance(const std::vector<Lamp>& lamps) {
    double sum = 0.0;
    for (const Lamp& l : lamps) {
        const double omega = rectangle_solid_angle(-kHalfFrame - l.x, kHalfFrame - l.x, -kHalfFrame - l.y,
                                                   kHalfFrame - l.y, kHeight);
        sum += l.power / (4.0 * kPi) * omega;
    }
    return kReflectance / kPi * sum / (4.0 * kHalfFrame * kHalfFrame);
}

struct LampFloor : SceneHandle {
    explicit LampFloor(const std::vector<Lamp>& lamps) {
        const StratumMaterialDesc floor = diffuse_grey(kReflectance);
        uint32_t mat = 0;
        EXPECT_EQ(stratum_scene_add_material(scene, &floor, &mat), STRATUM_OK);
        EXPECT_TRUE(add_square_instance(scene, 0.0f, 50.0f, mat)) << stratum_last_error();
        for (const Lamp& l : lamps) {
            StratumLightDesc lamp{};
            lamp.type = STRATUM_LIGHT_POINT;
            lamp.color[0] = lamp.color[1] = lamp.color[2] = 1.0f;
            lamp.strength = static_cast<float>(l.power);
            std::copy(kIdentity, kIdentity + 16, lamp.transform);
            lamp.transform[3] = l.x;
            lamp.transform[7] = l.y;
            lamp.transform[11] = kHeight;
            EXPECT_EQ(stratum_scene_add_light(scene, &lamp), STRATUM_OK) << stratum_last_error();
        }
        StratumCameraDesc camera = camera_at(0.0f, 0.0f, 5.0f);
        camera.type = STRATUM_CAMERA_ORTHOGRAPHIC;
        camera.ortho_scale = 2.0f * kHalfFrame;
        EXPECT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK) << stratum_last_error();
    }
};

}  // namespace

namespace {

// The mean over kSeeds renders with `settings`, and its standard error (header).
struct SeedMean {
    double mean = 0.0, standard_error = 0.0;
};

SeedMean seed_mean(const LampFloor& floor, const Settings& settings) {
    std::vector<double> means;
    for (uint32_t seed = 0; seed < kSeeds; ++seed) {
        Settings with_seed = settings;
        with_seed.push_back({"seed", seed});
        const RenderOutput out = render(floor.scene, with_seed);
        EXPECT_TRUE(out.error.empty()) << out.error;
        if (!out.error.empty()) return {};
        means.push_back(pixel_stats(out.rgba, 1).mean);
    }
    SeedMean result;
    for (const double m : means) result.mean += m;
    result.mean /= kSeeds;
    double ss = 0.0;
    for (const double m : means) ss += (m - result.mean) * (m - result.mean);
    result.standard_error = std::sqrt(ss / (kSeeds - 1) / kSeeds);
    return result;
}

Settings floor_settings(const char* mode) {
    return {{"width", 32},          {"height", 32},        {"samples", 64},          {"max_bounces", 0},
            {"filter_type", "box"}, {"filter_width", 1.0}, {"light_selection", mode}};
}

}  // namespace

TEST(ManyLights, EverySelectionModeMatchesTheClosedSum) {
    const std::vector<const char*> modes = setting_choices("light_selection");
    ASSERT_GE(modes.size(), 3u);
    for (const uint32_t n : {1u, 16u, 1024u}) {
        const std::vector<Lamp> lamps = lamp_grid(n);
        ASSERT_EQ(lamps.size(), n);
        const LampFloor floor(lamps);
        const double expected = expected_mean_radiance(lamps);
        for (const char* mode : modes) {
            const SeedMean m = seed_mean(floor, floor_settings(mode));
            EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error)
                << n << " lamps, light_selection " << mode << ": mean " << m.mean << ", closed sum "
                << expected << ", standard error " << m.standard_error;
        }
    }
}

// The light tree with adaptive splitting (lights/light_tree.h): one light sample per cut node,
// summed; 1 is the unsplit tree (the default, 8, runs in the test above). The floor points lie
// under the lamp grid (their distance to the root's bounding sphere is below its radius), so the
// cut fills up to its cap; the same tolerance as above.
TEST(ManyLights, TreeWithSplittingMatchesTheClosedSum) {
    for (const uint32_t n : {1u, 16u, 1024u}) {
        const std::vector<Lamp> lamps = lamp_grid(n);
        const LampFloor floor(lamps);
        const double expected = expected_mean_radiance(lamps);
        for (const uint32_t splits : {1u, 2u, 16u}) {
            Settings settings = floor_settings("tree");
            settings.push_back({"light_tree_splits", splits});
            const SeedMean m = seed_mean(floor, settings);
            EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error)
                << n << " lamps, " << splits << " splits: mean " << m.mean << ", closed sum " << expected
                << ", standard error " << m.standard_error;
        }
    }
}

// Splitting keeps the image a function of the scene, the settings and the seed alone: the cut
// depends on the shading point only, each sub-estimator reads the vertex's sample numbers
// (lights/light_set.h), and nothing is shared between threads, so 1, 2 and 3 threads give the
// same bits.
TEST(ManyLights, TreeWithSplittingIsBitIdenticalForAnyThreadCount) {
    const LampFloor floor(lamp_grid(1024));
    std::vector<float> first;
    for (const int64_t threads : {1, 2, 3}) {
        Settings settings = floor_settings("tree");
        settings.push_back({"light_tree_splits", 8});
        settings.push_back({"samples", 4});
        settings.push_back({"threads", threads});
        const RenderOutput out = render(floor.scene, settings);
        ASSERT_TRUE(out.error.empty()) << out.error;
        if (first.empty()) {
            first = out.rgba;
            continue;
        }
        ASSERT_EQ(out.rgba.size(), first.size());
        EXPECT_TRUE(out.rgba == first) << threads << " threads differ from 1";
    }
}
