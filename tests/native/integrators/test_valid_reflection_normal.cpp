// The shading-normal bend of Cycles 3.x (integrators/valid_reflection_normal.h) and its use by
// the path integrator at smooth-shaded silhouettes.
//
// The bent normal is checked against its definition, not against its own formula: unit length,
// in the plane of the shading and geometric normals, on the geometric side, and reflecting the
// view direction to height t = min(0.9 dot(ng, wo), 0.01) above the surface. The integrator test
// is deterministic (a sun, direct light only), so it is met to float rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "integrators/path_integrator.h"
#include "integrators/valid_reflection_normal.h"
#include "render_scene/render_scene.h"
#include "stratum/stratum.h"

namespace stratum {
namespace {

float reflected_height(Vec3 ng, Vec3 wo, Vec3 n) { return dot(ng, n * (2.0f * dot(n, wo)) - wo); }

float threshold(Vec3 ng, Vec3 wo) { return std::min(0.9f * dot(ng, wo), 0.01f); }

Vec3 polar(float theta, float phi) {
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

TEST(ValidReflectionNormal, NormalWhoseReflectionIsAboveTheSurfaceIsKept) {
    const Vec3 ng(0, 0, 1), wo = polar(0.6f, 0.0f), ns = polar(0.3f, 2.0f);
    const Vec3 n = ensure_valid_reflection(ng, wo, ns);
    EXPECT_EQ(n.x, ns.x);
    EXPECT_EQ(n.y, ns.y);
    EXPECT_EQ(n.z, ns.z);
}

TEST(ValidReflectionNormal, NormalFacingAwayFromTheViewerIsBentJustEnough) {
    // A silhouette of a smooth mesh: the shading normal leans 60 degrees away from a viewer
    // 70 degrees off the geometric normal, so dot(ns, wo) < 0.
    const Vec3 ng(0, 0, 1), wo = polar(1.2217305f, 0.0f), ns = polar(1.0471976f, kPi);
    ASSERT_LT(dot(ns, wo), 0.0f);
    const Vec3 n = ensure_valid_reflection(ng, wo, ns);
    EXPECT_NEAR(length(n), 1.0f, 1e-5f);
    EXPECT_NEAR(n.y, 0.0f, 1e-6f);  // stays in the plane of ns and ng
    EXPECT_LT(n.x, 0.0f);           // still leaning the way ns leans
    EXPECT_GT(dot(n, wo), 0.0f);
    EXPECT_NEAR(reflected_height(ng, wo, n), threshold(ng, wo), 1e-4f);
}

// The bend is solved in float, as Cycles solves it: z^2 carries a rounding error of a few
// ulps (eps <= 8 FLT_EPSILON, from the sums and the quotient), and the tangent component
// sqrt(1 - z^2) then errs by up to sqrt(eps) when z^2 is near 1; the reflected height
// 2 (x wo.x + z wo.z) z - wo.z moves by 2 |wo.x| times that, at most 2 sqrt(8 FLT_EPSILON)
// = 2.0e-3.
const float kHeightTolerance = 2.0f * std::sqrt(8.0f * std::numeric_limits<float>::epsilon());

TEST(ValidReflectionNormal, RandomNormalsMeetTheDefinition) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    const Vec3 ng(0, 0, 1);
    int bent = 0, at_threshold = 0;
    for (int i = 0; i < 20000; ++i) {
        const Vec3 wo = polar(std::acos(u(rng)) * 0.999f, 2.0f * kPi * u(rng));
        // Shading normals from the whole sphere: at a sharp fold of a smooth mesh the
        // interpolated normal can point below the surface.
        const Vec3 ns = polar(std::acos(2.0f * u(rng) - 1.0f) * 0.999f, 2.0f * kPi * u(rng));
        const Vec3 n = ensure_valid_reflection(ng, wo, ns);
        ASSERT_NEAR(length(n), 1.0f, 1e-4f);
        // In the plane of ns and ng: no component along their common perpendicular.
        const Vec3 perpendicular = cross(ns, ng);
        if (length(perpendicular) > 1e-3f) {
            ASSERT_NEAR(dot(n, normalize(perpendicular)), 0.0f, 1e-4f);
        }
        const float t = threshold(ng, wo);
        if (n.x == ns.x && n.y == ns.y && n.z == ns.z) {
            // Kept as it is, even below the surface (as Cycles keeps it) when its reflection is
            // high enough.
            ASSERT_GE(reflected_height(ng, wo, n), t);
        } else if (!(n.x == ng.x && n.y == ng.y && n.z == ng.z)) {
            ++bent;
            ASSERT_GT(dot(n, ng), 0.0f);
            // Above the surface; at height t unless the root that would give t is one of the
            // squared equation's spurious ones (normal leaning the other way), when Cycles takes
            // the other root, whose reflection is still above the surface.
            const float height = reflected_height(ng, wo, n);
            ASSERT_GE(height, -kHeightTolerance) << "wo " << wo.x << " " << wo.y << " " << wo.z;
            if (std::abs(height - t) <= kHeightTolerance) ++at_threshold;
        }
    }
    EXPECT_GT(bent, 1000);  // the set does exercise the bend
    EXPECT_GT(at_threshold, bent * 9 / 10);
}

// A floor whose shading normals all lean 60 degrees away from the camera (as at the silhouette
// of a smooth mesh), under a sun overhead, seen at 70 degrees off its geometric normal. Without
// the bend the diffuse closure would see the camera below its hemisphere and return black;
// Cycles 3.x bends the normal and shades it with cos(bent normal, sun).
TEST(ValidReflectionNormal, SilhouetteOfSmoothMeshIsShadedWithTheBentNormal) {
    constexpr float kAlbedo = 0.8f, kIrradiance = 3.0f;
    Scene scene;
    Mesh mesh;
    const float half = 10.0f;
    mesh.positions = {{-half, -half, 0}, {half, -half, 0}, {half, half, 0}, {-half, half, 0}};
    mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
    mesh.material_ids = {0, 0};
    // The camera looks along +x down onto the floor; the normals lean toward +x (away from it).
    const Vec3 ns = polar(1.0471976f, 0.0f);
    mesh.corner_normals.assign(6, ns);
    scene.meshes.push_back(mesh);
    scene.instances.push_back({0, Transform{}});
    scene.materials.push_back(SceneMaterial{{{Rgb(1.0f),
                                              {STRATUM_MATERIAL_DIFFUSE, Rgb(kAlbedo), 0.0f, 0.0f, 0.5f, 1.5f,
                                               Rgb(), MicrofacetDistribution::Ggx}}}});
    LightParams sun;
    sun.type = STRATUM_LIGHT_SUN;
    sun.strength = kIrradiance;
    scene.lights.push_back(sun);

    const Vec3 wo = polar(1.2217305f, kPi);  // toward the camera, at -x
    const Vec3 origin = wo * 3.0f;
    IntegratorSettings settings;
    settings.max_bounces = 0;
    const RenderScene render_scene(scene);
    const auto sampler = find_sampler("random")->create(SamplerSettings{});
    const PathIntegrator integrator(settings);
    uint64_t rays = 0;
    const CameraRay ray{origin, -wo, 0.0f, kInfinity};
    const Rgb L = integrator.radiance(render_scene, *sampler, PixelSample{0, 0, 0}, ray, rays).radiance;

    // The bent normal from its definition: n = (sin a, 0, cos a) in the plane of ns and ng with
    // reflected height t, found by bisection on a in (0, 60 deg) (the height falls as the
    // normal leans further from the viewer).
    const Vec3 ng(0, 0, 1);
    float lo = 0.0f, hi = 1.0471976f;
    for (int i = 0; i < 60; ++i) {
        const float mid = 0.5f * (lo + hi);
        const Vec3 n(std::sin(mid), 0.0f, std::cos(mid));
        (reflected_height(ng, wo, n) > threshold(ng, wo) ? lo : hi) = mid;
    }
    const float expected = kAlbedo * kIrradiance * std::cos(0.5f * (lo + hi)) / kPi;
    EXPECT_NEAR(L.r, expected, 1e-4f * expected);
    EXPECT_GT(L.r, 0.1f);
}

}  // namespace
}  // namespace stratum
