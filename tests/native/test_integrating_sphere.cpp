// Analytic check of the path tracer (textbook §3.3, research/textbook.md test B): inside a closed
// diffuse enclosure whose walls have reflectance k and emit L_e, the radiance everywhere is
// L_e / (1 − k), because every wall point sees the enclosure's uniform radiance L with
// irradiance πL, so L = L_e + k L. This holds for any closed shape, so a tessellated sphere is
// exact. With Cycles' bounce cap b (vertices 0..b scatter, the ray leaving vertex b still
// collects emission) the path carries at most b + 1 reflections: L = L_e Σ_{m=0}^{b+1} k^m.
//
// Tolerance: the image mean over P pixels of independent estimates; its standard error is
// s / √P with s the standard deviation of the pixel values (each pixel a mean of spp samples).
// We accept |mean − expected| ≤ 4 s / √P (fails by chance with probability 6e-5).
#include <gtest/gtest.h>

#include <numeric>

#include "render_helpers.h"

using namespace stratum_test;

namespace {

struct Stats {
    double mean, standard_error;
};

Stats red_channel_stats(const std::vector<float>& rgba) {
    const size_t n = rgba.size() / 4;
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < n; ++i) {
        sum += rgba[4 * i];
        sum2 += static_cast<double>(rgba[4 * i]) * rgba[4 * i];
    }
    const double mean = sum / static_cast<double>(n);
    const double var = (sum2 - static_cast<double>(n) * mean * mean) / static_cast<double>(n - 1);
    return {mean, std::sqrt(std::max(var, 0.0) / static_cast<double>(n))};
}

double expected_radiance(double emission, double k, int max_bounces) {
    double sum = 0, term = 1;
    for (int m = 0; m <= max_bounces + 1; ++m, term *= k) sum += term;
    return emission * sum;
}

RenderOutput render_sphere(int32_t model, float k, float emission, int max_bounces, uint32_t seed,
                           const char* sampler = "random") {
    const StratumMaterialDesc wall{
        model, {k, k, k}, 1.0f, 0.0f, 0.0f, 1.5f, {emission, emission, emission}, STRATUM_MICROFACET_GGX};
    StratumScene* scene = make_sphere_interior(wall, 12, 0.1f, -0.2f, 0.3f);
    EXPECT_NE(scene, nullptr) << stratum_last_error();
    RenderOutput out = render(
        scene, {{"width", 16}, {"height", 16}, {"samples", 64}, {"max_bounces", max_bounces}, {"seed", seed}},
        sampler);
    stratum_scene_destroy(scene);
    return out;
}

}  // namespace

TEST(IntegratingSphere, RadianceIsEmissionOverOneMinusReflectance) {
    for (const int bounces : {0, 1, 3, 24}) {
        const RenderOutput out = render_sphere(STRATUM_MATERIAL_DIFFUSE, 0.5f, 1.0f, bounces, 7);
        ASSERT_EQ(out.rgba.size(), 16u * 16u * 4u);
        const Stats s = red_channel_stats(out.rgba);
        const double expected = expected_radiance(1.0, 0.5, bounces);
        EXPECT_NEAR(s.mean, expected, 4.0 * s.standard_error)
            << "max_bounces " << bounces << ": mean " << s.mean << " expected " << expected << " (se "
            << s.standard_error << ")";
        // The estimate must be noisy enough to be a real test but not degenerate.
        EXPECT_GT(s.standard_error, 0.0);
        EXPECT_LT(s.standard_error, 0.01 * expected);
    }
}

TEST(IntegratingSphere, HighReflectanceConvergesToGeometricSeries) {
    // k = 0.8: L_e / (1 − k) = 5 with 60 bounces (0.8^61 < 1e-5 of the total).
    const RenderOutput out = render_sphere(STRATUM_MATERIAL_DIFFUSE, 0.8f, 1.0f, 60, 11);
    const Stats s = red_channel_stats(out.rgba);
    EXPECT_NEAR(s.mean, 5.0, 4.0 * s.standard_error) << "se " << s.standard_error;
}

// Every registered sampler renders the closed sphere without bias. Pixel errors are independent
// only for samplers randomised per pixel: a static lattice or an unscrambled sequence correlates
// them, and blue-noise samplers anti-correlate them. So the standard error combines the spread
// of pixels within one image (s_p/√P) with the spread of image means over R = 8 seeds
// (s_r/√R), which captures correlation across pixels; the test accepts 4 combined σ.
TEST(IntegratingSphere, EverySamplerIsUnbiased) {
    const int32_t n = stratum_registry_count(STRATUM_REGISTRY_SAMPLER);
    ASSERT_GE(n, 1);
    const double expected = expected_radiance(1.0, 0.5, 6);
    for (int32_t i = 0; i < n; ++i) {
        const char* name = nullptr;
        ASSERT_EQ(stratum_registry_entry(STRATUM_REGISTRY_SAMPLER, i, &name, nullptr, nullptr), STRATUM_OK);
        constexpr int kSeeds = 8;
        double sum = 0, sum2 = 0, pixel_se = 0;
        for (int seed = 0; seed < kSeeds; ++seed) {
            const Stats st = red_channel_stats(
                render_sphere(STRATUM_MATERIAL_DIFFUSE, 0.5f, 1.0f, 6, static_cast<uint32_t>(seed), name)
                    .rgba);
            sum += st.mean;
            sum2 += st.mean * st.mean;
            pixel_se = std::max(pixel_se, st.standard_error);
        }
        const double mean = sum / kSeeds;
        const double seed_var = std::max(0.0, (sum2 - kSeeds * mean * mean) / (kSeeds - 1));
        // The mean of R images has pixel noise s_p/√(P R) and correlated noise s_r/√R.
        const double se = std::sqrt(pixel_se * pixel_se / kSeeds + seed_var / kSeeds);
        EXPECT_NEAR(mean, expected, 4.0 * se)
            << name << ": mean " << mean << " expected " << expected << " se " << se;
        EXPECT_GT(se, 0.0) << name;
    }
}

TEST(Determinism, SameSeedGivesBitIdenticalImagesForAnyThreadCount) {
    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    const StratumMaterialDesc wall{STRATUM_MATERIAL_DIFFUSE, {0.6f, 0.5f, 0.4f},    1, 0, 0, 1.5f,
                                   {0.5f, 0.5f, 0.5f},       STRATUM_MICROFACET_GGX};
    uint32_t mat = 0;
    ASSERT_EQ(stratum_scene_add_material(scene, &wall, &mat), STRATUM_OK);
    const SphereMesh sphere = make_sphere(1.0f, 6, 12);
    const std::vector<uint32_t> mats(sphere.triangles.size() / 3, mat);
    const StratumMeshDesc mesh{sphere.positions.data(),
                               static_cast<uint32_t>(sphere.positions.size() / 3),
                               sphere.triangles.data(),
                               static_cast<uint32_t>(sphere.triangles.size() / 3),
                               nullptr,
                               nullptr,
                               mats.data()};
    uint32_t mesh_id = 0;
    ASSERT_EQ(stratum_scene_add_mesh(scene, &mesh, &mesh_id), STRATUM_OK);
    ASSERT_EQ(stratum_scene_add_instance(scene, mesh_id, kIdentity), STRATUM_OK);
    const StratumCameraDesc camera = camera_at(0, 0, 0.5f);
    ASSERT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK);
    const auto one =
        render(scene, {{"width", 40}, {"height", 24}, {"samples", 9}, {"threads", 1}, {"seed", 3}});
    const auto two =
        render(scene, {{"width", 40}, {"height", 24}, {"samples", 9}, {"threads", 2}, {"seed", 3}});
    const auto other =
        render(scene, {{"width", 40}, {"height", 24}, {"samples", 9}, {"threads", 2}, {"seed", 4}});
    stratum_scene_destroy(scene);
    ASSERT_EQ(one.rgba.size(), 40u * 24u * 4u);
    EXPECT_EQ(one.rgba, two.rgba);
    EXPECT_NE(one.rgba, other.rgba);
    EXPECT_EQ(one.progress.samples_done, 9);
}
