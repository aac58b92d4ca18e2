// Integrating sphere A (textbook §3.3, eq. 3.17; research/textbook.md §2.1 test A): a point lamp
// of flux Φ at the centre of a diffuse sphere of radius 1, reflectance k, black port fraction h.
// Wall radiance L = kΦ/(πA_s(1 − k(1 − h)))·(1 − (k(1 − h))ⁿ) with n = max_bounces + 1
// (sphere_a_radiance in render_helpers.h). Default estimator and every sampler here; the
// estimator ladder in test_integrating_sphere_estimators.cpp.
//
// Flux convention: a Blender point lamp of Power P has intensity P/(4π) W/sr in every direction
// (lights/point_light.h, docs/cycles_models.md §4, measured in Cycles), so its flux is Φ = P.
// We set P = 4π: intensity 1, irradiance 1 at the wall of the unit sphere.
//
// Tessellation bound (closed sphere). The lamp gives a wall point x the irradiance
// E(x) = I d_p/|x|³, d_p the distance of x's facet plane from the centre. Every mesh point has
// d_min ≤ d_p ≤ |x| ≤ 1 (d_min = PortedSphereMesh::min_plane_distance), so
// E ∈ [I d_min, I/d_min²]; the mean Φ/A_s lies in [I, I/d_min²] since
// 4π d_min² ≤ A_s ≤ 4π (the mesh lies between the spheres of radius d_min and 1, both convex).
// So |E/Ē − 1| ≤ ε = 1/d_min³ − 1. The closed enclosure's transport K has row sums k (the form
// factors of a closed surface sum to 1), so the uniform L_A solves L = kE/π + KL with E = Ē and
// δ = L − L_A obeys δ = k(E − Ē)/π + Kδ: ‖δ‖ ≤ (k/π)εĒ/(1 − k) = ε L_A (uncapped; each capped
// partial sum likewise). 96 rings: d_min = 0.99973, ε = 8.0e-4; we add ε·L_A to the tolerance.
// With the port, the port form factor's deviation adds kPortedSphereBias (derived in
// render_helpers.h for the same mesh).
//
// Tolerance: 4 standard errors of the image mean from independent pixels (the `random`
// sampler), or from the spread over 8 seeds for samplers that correlate pixels; see
// test_integrating_sphere.cpp.
#include <gtest/gtest.h>

#include "render_helpers.h"
#include "setting_choices.h"

using namespace stratum_test;

namespace {

constexpr double kFlux = 4.0 * 3.14159265358979323846;  // P = 4π W: intensity 1 W/sr

IntegratingSphere point_lit_sphere(float k, uint32_t port_rings, uint32_t rings = 96) {
    IntegratingSphereDesc d;
    d.reflectance = k;
    d.point_power = static_cast<float>(kFlux);
    d.rings = rings;
    d.port_rings = port_rings;
    return make_integrating_sphere(d);
}

double tessellation_bound(const PortedSphereMesh& m) {
    const double d = m.min_plane_distance;
    return 1.0 / (d * d * d) - 1.0 + (m.port_area > 0 ? kPortedSphereBias : 0.0);
}

}  // namespace

// The book's example: k = 0.8, h = 0, Φ = 4π on the unit sphere gives 4/π uncapped; the caps
// 0 (one reflection: kΦ/(πA_s) = 0.8/π) and 2 cut the series after 1 and 3 terms.
TEST(IntegratingSpherePointLight, RadianceIsTextbook317WithTheBounceCap) {
    IntegratingSphere s = point_lit_sphere(0.8f, 0);
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    const double A = s.sphere.total_area();
    EXPECT_NEAR(A, 4.0 * 3.14159265358979323846, 2e-3 * A);
    EXPECT_NEAR(sphere_a_radiance(kFlux, 4.0 * 3.14159265358979323846, 0.8, 0.0, 100000),
                4.0 / 3.14159265358979, 1e-9);
    const double bound = tessellation_bound(s.sphere);
    EXPECT_LT(bound, 1e-3);
    for (const uint32_t bounces : {0u, 2u, 40u}) {
        const Measurement m =
            measure(s.scene,
                    {{"width", 32}, {"height", 32}, {"samples", 64}, {"max_bounces", bounces}, {"seed", 3u}});
        ASSERT_TRUE(m.error.empty()) << m.error;
        const double expected = sphere_a_radiance(kFlux, A, 0.8, 0.0, bounces);
        EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error + bound * expected)
            << "max_bounces " << bounces << ": mean " << m.mean << " expected " << expected << " (se "
            << m.standard_error << ")";
        EXPECT_GT(m.standard_error, 0.0);
        EXPECT_LT(m.standard_error, 0.01 * expected);
    }
    stratum_scene_destroy(s.scene);
}

TEST(IntegratingSpherePointLight, BlackPortLowersTheMultiplier) {
    IntegratingSphere s = point_lit_sphere(0.5f, 20);
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    const double h = s.sphere.port_fraction(), A = s.sphere.total_area();
    const double bound = tessellation_bound(s.sphere);
    for (const uint32_t bounces : {1u, 30u}) {
        const Measurement m =
            measure(s.scene,
                    {{"width", 32}, {"height", 32}, {"samples", 64}, {"max_bounces", bounces}, {"seed", 4u}});
        ASSERT_TRUE(m.error.empty()) << m.error;
        const double expected = sphere_a_radiance(kFlux, A, 0.5, h, bounces);
        EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error + bound * expected)
            << "max_bounces " << bounces << ": mean " << m.mean << " expected " << expected << " (se "
            << m.standard_error << ")";
        EXPECT_GT(std::abs(sphere_a_radiance(kFlux, A, 0.5, 0.0, bounces) - m.mean), 8.0 * m.standard_error);
    }
    stratum_scene_destroy(s.scene);
}

TEST(IntegratingSpherePointLight, EverySamplerIsUnbiased) {
    const std::vector<const char*> samplers = setting_choices("sampler");
    ASSERT_GE(samplers.size(), 1u);
    // 64 rings (ε = 1.8e-3) and a cap of 2 bounces keep the 8 renders per sampler cheap.
    IntegratingSphere s = point_lit_sphere(0.5f, 0, 64);
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    const double expected = sphere_a_radiance(kFlux, s.sphere.total_area(), 0.5, 0.0, 2);
    const double bound = tessellation_bound(s.sphere);
    EXPECT_LT(bound, 2e-3);
    for (const char* name : samplers) {
        const Measurement m = measure(
            s.scene, {{"width", 16}, {"height", 16}, {"samples", 32}, {"max_bounces", 2}, {"sampler", name}},
            8);
        ASSERT_TRUE(m.error.empty()) << name << ": " << m.error;
        EXPECT_NEAR(m.mean, expected, 4.0 * m.standard_error + bound * expected)
            << name << ": mean " << m.mean << " expected " << expected << " se " << m.standard_error;
        EXPECT_GT(m.standard_error, 0.0) << name;
    }
    stratum_scene_destroy(s.scene);
}

// BSDF sampling alone finds emission only by hitting it, and a point lamp of radius 0 has no
// surface: every path of this scene (the walls do not emit) contributes exactly nothing, and
// the renderer says why. With NEE or MIS the same scene is lit and there is no notice.
TEST(IntegratingSpherePointLight, BsdfSamplingAloneRendersBlackAndSaysWhy) {
    IntegratingSphere s = point_lit_sphere(0.5f, 0);
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    const RenderOutput dark = render(
        s.scene,
        {{"width", 16}, {"height", 16}, {"samples", 16}, {"max_bounces", 4}, {"light_sampling", "bsdf"}});
    ASSERT_TRUE(dark.error.empty()) << dark.error;
    ASSERT_EQ(dark.rgba.size(), 16u * 16u * 4u);
    for (size_t i = 0; i < dark.rgba.size(); i += 4) {
        ASSERT_EQ(dark.rgba[i], 0.0f) << "pixel " << i / 4;
        ASSERT_EQ(dark.rgba[i + 1], 0.0f) << "pixel " << i / 4;
        ASSERT_EQ(dark.rgba[i + 2], 0.0f) << "pixel " << i / 4;
    }
    EXPECT_NE(dark.notices.find("bsdf"), std::string::npos) << dark.notices;
    EXPECT_NE(dark.notices.find("point"), std::string::npos) << dark.notices;
    for (const char* lit : {"nee", "mis"}) {
        const RenderOutput out = render(
            s.scene,
            {{"width", 16}, {"height", 16}, {"samples", 4}, {"max_bounces", 4}, {"light_sampling", lit}});
        ASSERT_TRUE(out.error.empty()) << out.error;
        EXPECT_EQ(out.notices, "") << lit;
        EXPECT_GT(pixel_stats(out.rgba).mean, 0.0) << lit;
    }
    stratum_scene_destroy(s.scene);
}
