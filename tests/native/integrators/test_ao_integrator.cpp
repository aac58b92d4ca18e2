// The `ao` integrator (seed 000, eq. 20) against closed forms, through the C ABI.
//
// Convention (integrators/ao_integrator.h): the image is the openness A = 1 − O, where
// O = (1/π) ∫ V cos θ dω is seed 000's occluded fraction (V = 1 when an obstacle lies within
// ao_distance d). 1 = fully open (white); camera rays that miss give 1. Each sample is
// 1 − V·w with w = cos θ / (π p) (exactly 1 for `cosine`).
//
// Closed forms used below (floor z = 0, shading point at the origin of its hemisphere):
//  (a) nothing above: V = 0 for every ray, so A = 1 exactly, every sample, every distribution.
//  (b) a parallel ceiling at height h, larger than the reach of d: a ray at angle θ meets it
//      at distance h / cos θ, so V = [cos θ > h/d]. Under the cosine density cos²θ is uniform
//      on [0,1] (Malley: the disk point's radius² is uniform), so O = P(cos²θ > (h/d)²) =
//      1 − (h/d)², i.e. A = (h/d)² for d > h, and A = 1 exactly for d < h (nothing in reach).
//  (c) an infinite vertical wall (plane x = 0) at distance x from the point: a ray with
//      horizontal part (dx, dy) = sin θ (cos φ, sin φ) reaches it at t = x / (−dx), so
//      V = [−dx > a], a = x/d. Cosine-weighted directions project to the uniform unit disk
//      (Malley), so O = area{(dx, dy) in the disk, dx < −a} / π = (acos a − a √(1 − a²)) / π;
//      at the foot of the wall (a → 0) O = 1/2, half the hemisphere. The wall is a finite quad
//      larger than d in height and length, which no ray within d can tell from the plane.
// The ray origin is offset by 1e-4 along the normal (ray_offset.h); h is corrected for it.
//
// Tolerance: pixels are independent estimates (the `random` sampler), each the mean of spp
// samples, of the same point (a 5000 mm lens sees a footprint < 0.004 wide, over which A
// changes by < 1e-3 and linearly, so the footprint averages out). The image mean over P pixels
// has standard error s/√P, s the spread of the pixel values; we accept |mean − A| ≤ 4 s/√P.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "render_helpers.h"
#include "scene_handle.h"
#include "setting_choices.h"

using namespace stratum_test;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kOffset = 1e-4f;  // ray_offset.h at |p| <= 1
const char* const kDistributions[] = {"uniform_angles", "uniform", "cosine"};

struct AoScene : SceneHandle {
    uint32_t material = 0;
    AoScene() {
        const StratumMaterialDesc grey = diffuse_grey(0.5f);
        EXPECT_EQ(stratum_scene_add_material(scene, &grey, &material), STRATUM_OK);
    }

    // Horizontal square of half side `half` at height z.
    void add_horizontal(float z, float half) {
        EXPECT_TRUE(add_square_instance(scene, z, half, material)) << stratum_last_error();
    }
    // Vertical wall in the plane x = 0: y in [-half, half], z in [0, height].
    void add_wall(float half, float height) {
        const float corners[12] = {0, -half, 0, 0, half, 0, 0, half, height, 0, -half, height};
        EXPECT_TRUE(add_quad_instance(scene, corners, material)) << stratum_last_error();
    }
    // Camera at (x, 0, z) looking straight down; `lens_mm` 5000 sees a tiny footprint.
    void look_down_at(float x, float z, float lens_mm = 5000.0f) {
        StratumCameraDesc camera = camera_at(x, 0, z);
        camera.lens_mm = lens_mm;
        EXPECT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK);
    }
};

// Grey values (red channel) of an `ao` render.
std::vector<float> render_ao(const AoScene& s, const char* hemisphere, double ao_distance, int64_t size,
                             int64_t spp, int64_t seed) {
    std::vector<float> grey;
    StratumRenderer* r = nullptr;
    if (stratum_renderer_create(s.scene, &r) != STRATUM_OK) return grey;
    const bool ok = stratum_renderer_set_int(r, "width", size) == STRATUM_OK &&
                    stratum_renderer_set_int(r, "height", size) == STRATUM_OK &&
                    stratum_renderer_set_int(r, "samples", spp) == STRATUM_OK &&
                    stratum_renderer_set_int(r, "seed", seed) == STRATUM_OK &&
                    stratum_renderer_set_string(r, "integrator", "ao") == STRATUM_OK &&
                    stratum_renderer_set_string(r, "sampler", "random") == STRATUM_OK &&
                    stratum_renderer_set_string(r, "hemisphere", hemisphere) == STRATUM_OK &&
                    stratum_renderer_set_float(r, "ao_distance", ao_distance) == STRATUM_OK;
    EXPECT_TRUE(ok) << stratum_last_error();
    if (ok && render_to_end(r)) {
        std::vector<float> rgba(static_cast<size_t>(size * size * 4));
        stratum_renderer_read_pixels(r, rgba.data(), rgba.size());
        for (size_t i = 0; i < rgba.size(); i += 4) grey.push_back(rgba[i]);
    }
    stratum_renderer_destroy(r);
    return grey;
}

struct Stats {
    double mean, standard_error;
};

Stats stats(const std::vector<float>& v) {
    const auto n = static_cast<double>(v.size());
    double sum = 0, sum2 = 0;
    for (const float x : v) {
        sum += x;
        sum2 += static_cast<double>(x) * x;
    }
    const double mean = sum / n, var = std::max(0.0, (sum2 - n * mean * mean) / (n - 1));
    return {mean, std::sqrt(var / n)};
}

// (c): occluded fraction next to an infinite wall, a = distance / ao_distance.
double wall_occlusion(double a) { return (std::acos(a) - a * std::sqrt(1.0 - a * a)) / kPi; }

}  // namespace

TEST(AoIntegrator, OpenPlaneIsExactlyOneForEveryDistribution) {
    AoScene s;
    s.add_horizontal(0.0f, 10.0f);
    s.look_down_at(0.0f, 1.0f, 18.0f);  // wide view: many different floor points
    for (const char* h : kDistributions) {
        for (const double d : {0.5, 1e3, static_cast<double>(INFINITY)}) {
            const std::vector<float> grey = render_ao(s, h, d, 16, 16, 1);
            ASSERT_EQ(grey.size(), 256u);
            for (const float g : grey) ASSERT_EQ(g, 1.0f) << h << " d=" << d;
        }
    }
}

TEST(AoIntegrator, CameraRaysThatMissAreOpen) {
    AoScene s;
    s.add_horizontal(0.0f, 1.0f);
    s.look_down_at(0.0f, -1.0f);  // below the floor, looking away from it
    for (const float g : render_ao(s, "uniform", 1.0, 8, 4, 0)) ASSERT_EQ(g, 1.0f);
}

TEST(AoIntegrator, CeilingOutOfReachIsOpenAndWithinReachGivesSquaredRatio) {
    // (b): h = 1 (minus the origin offset); ceiling half side 20 > √(d² − h²) for d ≤ 4.
    AoScene s;
    s.add_horizontal(0.0f, 20.0f);
    s.add_horizontal(1.0f, 20.0f);
    s.look_down_at(0.0f, 0.5f);
    const double h = 1.0 - kOffset;
    for (const char* hemisphere : kDistributions) {
        for (const float g : render_ao(s, hemisphere, 0.99, 8, 16, 2)) ASSERT_EQ(g, 1.0f) << hemisphere;
        for (const double d : {1.25, 2.0, 4.0}) {
            const std::vector<float> grey = render_ao(s, hemisphere, d, 32, 64, 3);
            const Stats st = stats(grey);
            const double expected = (h / d) * (h / d);
            EXPECT_NEAR(st.mean, expected, 4.0 * st.standard_error)
                << hemisphere << " d=" << d << " se " << st.standard_error;
            EXPECT_GT(st.standard_error, 0.0);
        }
    }
}

TEST(AoIntegrator, WallConvergesToDiskSegmentFraction) {
    // (c): (x, d) = (0.6, 2): a = 0.3, A = 1 − 0.31192 = 0.68808; (0.05, 20): a = 0.0025, the
    // foot of the wall, A ≈ 1/2 + 0.0016. Wall and floor extend beyond every d used.
    struct Case {
        float x;
        double d;
    };
    AoScene s;
    s.add_horizontal(0.0f, 60.0f);
    s.add_wall(60.0f, 60.0f);
    for (const Case c : {Case{0.6f, 2.0}, Case{0.05f, 20.0}}) {
        s.look_down_at(c.x, 0.5f);
        const double expected = 1.0 - wall_occlusion(c.x / c.d);
        for (const char* hemisphere : kDistributions) {
            const Stats st = stats(render_ao(s, hemisphere, c.d, 32, 64, 4));
            EXPECT_NEAR(st.mean, expected, 4.0 * st.standard_error)
                << hemisphere << " x=" << c.x << " d=" << c.d << " se " << st.standard_error;
            EXPECT_LT(st.standard_error, 0.005);
        }
    }
}

TEST(AoIntegrator, CosineHasTheLowestErrorAt16Rays) {
    // (d), seed 000 table 2. Each sample is 1 − V w, w = cos θ / (π p), so its variance is
    //     E_p[w² V] − O²,  E_p[w² V] = ∫ V cos²θ / (π² p) dω,
    // i.e. per distribution (V the wall indicator of (c)):
    //     cosine:          O − O² = O(1 − O)   (w = 1: a Bernoulli variable)
    //     uniform:         (2/π) ∫ V cos²θ dω
    //     uniform_angles:  ∫∫ V cos²θ sin²θ dθ dφ
    // Cosine sampling makes w ≡ 1, so the only noise left is V's own (Bernoulli). The others
    // have w = 2 cos θ (uniform) and π sin θ cos θ (uniform_angles): E_p[w² V] = E_cos[w V],
    // which exceeds O = E_cos[V] exactly when w averages above 1 over the occluded directions
    // (w > 1 at θ < 60° for uniform, 19.8° < θ < 70.2° for uniform_angles). Cosine is not optimal for every V
    // (an occluder only near the horizon, where w < 1, favours uniform), but the wall occludes a broad
    // half-disk of directions from θ = 0 outwards, as most real occluders do. At a = 0.3 the second moments
    // below come from a midpoint quadrature in (θ, φ). A pixel of 16 rays has MSE = σ²/16 (unbiased), which
    // the test also checks against the measured mean of squared errors over P = 64² pixels (standard error
    // from their spread).
    const double a = 0.3, d = 2.0;
    const float x = 0.6f;  // a = x / d
    const double occluded = wall_occlusion(a), expected = 1.0 - occluded;
    double m_uniform = 0, m_angles = 0;
    const int n = 1000;
    for (int i = 0; i < n; ++i) {
        const double theta = 0.5 * kPi * (i + 0.5) / n;
        for (int j = 0; j < 2 * n; ++j) {
            const double phi = 2.0 * kPi * (j + 0.5) / (2 * n);
            if (-std::sin(theta) * std::cos(phi) <= a) continue;
            const double dtheta_dphi = (0.5 * kPi / n) * (2.0 * kPi / (2 * n));
            const double c = std::cos(theta), sn = std::sin(theta);
            m_uniform += (2.0 / kPi) * c * c * sn * dtheta_dphi;
            m_angles += c * c * sn * sn * dtheta_dphi;
        }
    }
    const double predicted[] = {m_angles - occluded * occluded, m_uniform - occluded * occluded,
                                occluded * (1.0 - occluded)};

    AoScene s;
    s.add_horizontal(0.0f, 60.0f);
    s.add_wall(60.0f, 60.0f);
    s.look_down_at(x, 0.5f);
    double mse[3];
    for (int k = 0; k < 3; ++k) {
        const std::vector<float> grey = render_ao(s, kDistributions[k], d, 64, 16, 5);
        ASSERT_EQ(grey.size(), 4096u);
        std::vector<float> squared;
        for (const float g : grey) squared.push_back(static_cast<float>((g - expected) * (g - expected)));
        const Stats st = stats(squared);
        mse[k] = st.mean;
        std::printf("AO 16 rays, %-14s MSE %.5f (predicted sigma^2/16 = %.5f, se %.5f)\n", kDistributions[k],
                    st.mean, predicted[k] / 16.0, st.standard_error);
        EXPECT_NEAR(st.mean, predicted[k] / 16.0, 4.0 * st.standard_error) << kDistributions[k];
    }
    EXPECT_LT(mse[2], mse[0]);
    EXPECT_LT(mse[2], mse[1]);
}

TEST(AoSettings, ValidatedWithMessagesNamingTheValue) {
    AoScene s;
    s.add_horizontal(0.0f, 1.0f);
    s.look_down_at(0.0f, 1.0f);
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(s.scene, &r), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_string(r, "hemisphere", "cosine_weighted"),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("cosine_weighted"), std::string::npos);
    EXPECT_NE(std::string(stratum_last_error()).find("uniform_angles"), std::string::npos);  // lists known
    for (const double bad : {0.0, -1.0, static_cast<double>(NAN), 1e-60}) {
        EXPECT_EQ(stratum_renderer_set_float(r, "ao_distance", bad), STRATUM_ERROR_INVALID_ARGUMENT) << bad;
        EXPECT_NE(std::string(stratum_last_error()).find("ao_distance"), std::string::npos);
    }
    EXPECT_EQ(stratum_renderer_set_float(r, "ao_distance", 3.5), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_string(r, "integrator", "ao"), STRATUM_OK);
    for (const char* h : kDistributions)
        EXPECT_EQ(stratum_renderer_set_string(r, "hemisphere", h), STRATUM_OK);
    stratum_renderer_destroy(r);
}

TEST(AoSettings, HemisphereChoicesCrossTheAbi) {
    const std::vector<const char*> names = setting_choices("hemisphere");
    ASSERT_EQ(names.size(), 3u);
    for (size_t i = 0; i < names.size(); ++i) EXPECT_STREQ(names[i], kDistributions[i]);
}
