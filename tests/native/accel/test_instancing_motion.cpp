// Instance motion blur, ray visibility masks, holdout and the shading data of instanced hits.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "accel/embree_scene.h"
#include "render_helpers.h"
#include "render_scene/render_scene.h"

using namespace stratum;

namespace {

// The square [x0, x1] x [y0, y1] at height z facing +Z, uv (0,0) at (x0,y0) and (1,1) at (x1,y1).
Mesh rectangle(float x0, float x1, float y0, float y1, float z, uint32_t material = 0) {
    Mesh m;
    m.positions = {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    m.corner_uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
    m.material_ids = {material, material};
    return m;
}

Transform rotation_z(float angle, Vec3 scale = {1, 1, 1}, Vec3 translation = {0, 0, 0}) {
    const float c = std::cos(angle), s = std::sin(angle);
    Transform t;
    t.m = {c * scale.x, -s * scale.y, 0, translation.x, s * scale.x, c * scale.y, 0, translation.y, 0, 0,
           scale.z,     translation.z};
    return t;
}

Scene one_material_scene() {
    Scene scene;
    scene.materials.push_back(SceneMaterial{{WeightedClosure{Rgb(1.0f), Material{}}}});
    return scene;
}

Instance instance_of(uint32_t mesh, const Transform& t, uint32_t visibility = 31) {
    Instance inst{};
    inst.mesh_id = mesh;
    inst.object_to_world = t;
    inst.object_to_world_end = t;
    inst.visibility = visibility;
    return inst;
}

constexpr RayQuery kCamera{0.5f, STRATUM_VISIBLE_CAMERA}, kShadow{0.5f, STRATUM_VISIBLE_SHADOW};

}  // namespace

// Embree's interpolated transform at the two time steps is the transform given, for rotation,
// non-uniform scale, skew and a mirror: the decomposition and the quaternion convention agree
// with Embree's recomposition.
TEST(InstanceMotion, DecompositionRecomposesAtBothEnds) {
    Transform a = rotation_z(0.8f, {0.5f, 2.0f, -1.5f}, {1, 2, 3});  // mirrored (negative z scale)
    a.m[2] = 0.3f;                                                   // skew
    Transform b = rotation_z(2.5f, {1.0f, 1.0f, 1.0f}, {-1, 0, 4});
    const Mesh m = rectangle(0, 1, 0, 1, 0);
    const TriangleGeometry proto{m.positions, m.triangles};
    const InstancePlacement p{0, a, b, true, 31};
    EmbreeScene embree;
    ASSERT_EQ(embree.build(std::span(&proto, 1), std::span(&p, 1), 1e6f), "");
    for (const auto& [time, expected] : {std::pair{0.0f, a}, std::pair{1.0f, b}}) {
        const Transform got = embree.motion_transform(0, time);
        for (int i = 0; i < 12; ++i)
            EXPECT_NEAR(got.m[i], expected.m[i], 1e-5f) << "time " << time << " element " << i;
    }
}

// Rotation interpolates as a quaternion (Cycles' transform_motion_decompose + slerp): a bar of
// length 2 along +x turning 90° about z points along 45° at time 0.5 with its full length. A
// linear blend of the matrices would shrink it to 2 cos 45° = 1.41, missing the probe at 1.5.
TEST(InstanceMotion, RotationInterpolatesAsAQuaternion) {
    Scene scene = one_material_scene();
    scene.meshes.push_back(rectangle(0, 2, -0.05f, 0.05f, 0));
    Instance inst = instance_of(0, rotation_z(0.0f));
    inst.motion = true;
    inst.object_to_world_end = rotation_z(0.5f * kPi);
    scene.instances.push_back(inst);
    const RenderScene rs(scene);
    EXPECT_TRUE(rs.has_motion());
    const auto probe = [&](float angle, float time, SurfaceHit* hit) {
        const Vec3 p(1.5f * std::cos(angle), 1.5f * std::sin(angle), 5.0f);
        return rs.intersect(p, Vec3(0, 0, -1), 0.0f, kInfinity, hit, RayQuery{time, 31});
    };
    SurfaceHit hit;
    EXPECT_TRUE(probe(0.25f * kPi, 0.5f, &hit));
    EXPECT_NEAR(hit.position.x, 1.5f * std::cos(0.25f * kPi), 1e-4f);
    EXPECT_NEAR(hit.position.y, 1.5f * std::sin(0.25f * kPi), 1e-4f);
    EXPECT_NEAR(hit.position.z, 0.0f, 1e-5f);
    // The shading frame is the transform at the ray's time: uv along the bar and dpdu at 45°.
    EXPECT_NEAR(hit.uv.x, 0.75f, 1e-4f);
    EXPECT_NEAR(hit.tangent_frame.dpdu.x, 2.0f * std::cos(0.25f * kPi), 1e-4f);
    EXPECT_NEAR(hit.tangent_frame.dpdu.y, 2.0f * std::sin(0.25f * kPi), 1e-4f);
    EXPECT_FALSE(probe(0.0f, 0.5f, &hit));
    EXPECT_TRUE(probe(0.0f, 0.0f, &hit));
    EXPECT_TRUE(probe(0.5f * kPi, 1.0f, &hit));
    EXPECT_FALSE(probe(0.5f * kPi, 0.0f, &hit));
}

// A square 1 wide moves from x = -1 to x = +1 over the shutter, seen straight down by an
// orthographic camera 4 units wide (64 px). A film point x0 is covered for a fraction of the
// shutter
//     p(x0) = (x0 + 1.5)/2 on [-1.5, -0.5], 0.5 on [-0.5, 0.5], (1.5 - x0)/2 on [0.5, 1.5], 0 outside.
// Each sample draws a film point uniformly in the pixel and a time uniformly in [0, 1) (as the
// renderer draws kDimTime when the scene moves), traces the camera ray at that time and
// scores 1 on a hit: a Bernoulli variable. p is linear within each piece, so the pixel's mean
// is p(centre) unless the pixel (±0.5 px = ±0.031 units) crosses a kink; those are skipped.
// N = 4096 samples per pixel of variance p(1 - p): the mean must be within 4 sqrt(p(1 - p)/N)
// of p (two-sided 4σ: false-alarm odds 6e-5 per pixel; the seed is fixed).
TEST(InstanceMotion, MovingObjectCoversThePixelsForTheAnalyticFractionOfTheShutter) {
    Scene scene = one_material_scene();
    scene.meshes.push_back(rectangle(-0.5f, 0.5f, -2, 2, 0));
    Instance inst = instance_of(0, rotation_z(0, {1, 1, 1}, {-1, 0, 0}));
    inst.motion = true;
    inst.object_to_world_end = rotation_z(0, {1, 1, 1}, {1, 0, 0});
    scene.instances.push_back(inst);
    const RenderScene rs(scene);
    CameraParams params;
    params.type = CameraType::Orthographic;
    params.ortho_scale = 4.0f;
    params.camera_to_world.m[11] = 5.0f;
    constexpr uint32_t kWidth = 64, kHeight = 8, kSamples = 4096;
    const Camera camera(params, kWidth, kHeight);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    const auto coverage = [](float x) {
        if (x <= -1.5f || x >= 1.5f) return 0.0f;
        if (x < -0.5f) return (x + 1.5f) / 2;
        if (x > 0.5f) return (1.5f - x) / 2;
        return 0.5f;
    };
    int checked = 0;
    for (uint32_t i = 0; i < kWidth; ++i) {
        const float x0 = -2.0f + (static_cast<float>(i) + 0.5f) / 16.0f;
        bool near_kink = false;
        for (float kink : {-1.5f, -0.5f, 0.5f, 1.5f}) near_kink |= std::abs(x0 - kink) < 0.04f;
        if (near_kink) continue;
        int covered = 0;
        for (uint32_t k = 0; k < kSamples; ++k) {
            const CameraRay ray = camera.generate_ray(static_cast<float>(i) + uniform(rng), 4.0f);
            SurfaceHit hit;
            covered += rs.intersect(ray.origin, ray.direction, ray.t_min, ray.t_max, &hit,
                                    RayQuery{uniform(rng), STRATUM_VISIBLE_CAMERA});
        }
        const double mean = covered / static_cast<double>(kSamples), p = coverage(x0);
        EXPECT_NEAR(mean, p, 4.0 * std::sqrt(p * (1.0 - p) / kSamples) + 1e-9)
            << "column " << i << " x0 " << x0;
        ++checked;
    }
    EXPECT_GT(checked, 48);
}

// A camera-invisible blocker is passed by camera rays but blocks shadow rays; a
// shadow-invisible one is seen by the camera but blocks no shadow ray. Hits carry the
// instance's visibility bits and holdout flag.
TEST(InstanceVisibility, RayMasksSelectInstances) {
    Scene scene = one_material_scene();
    scene.meshes.push_back(rectangle(-2, 2, -2, 2, 0));
    scene.meshes.push_back(rectangle(-0.5f, 0.5f, -0.5f, 0.5f, 1));
    scene.instances.push_back(instance_of(0, Transform{}));
    const uint32_t not_camera = STRATUM_VISIBLE_ALL & ~STRATUM_VISIBLE_CAMERA;
    const uint32_t not_shadow = STRATUM_VISIBLE_ALL & ~STRATUM_VISIBLE_SHADOW;
    Instance hidden = instance_of(1, Transform{}, not_camera);
    scene.instances.push_back(hidden);
    Instance holdout = instance_of(1, rotation_z(0, {1, 1, 1}, {3, 0, 0}), not_shadow);
    holdout.holdout = true;
    scene.instances.push_back(holdout);
    scene.instances.push_back(instance_of(0, rotation_z(0, {1, 1, 1}, {4, 0, 0})));
    const RenderScene rs(scene);
    const Vec3 down(0, 0, -1), up(0, 0, 1);
    SurfaceHit hit;
    // Camera ray over the camera-invisible blocker: reaches the floor.
    ASSERT_TRUE(rs.intersect({0, 0, 5}, down, 0, kInfinity, &hit, kCamera));
    EXPECT_NEAR(hit.position.z, 0.0f, 1e-6f);
    EXPECT_NEAR(hit.t, 5.0f, 1e-6f);
    EXPECT_EQ(hit.visibility, static_cast<uint32_t>(STRATUM_VISIBLE_ALL));
    EXPECT_FALSE(hit.holdout);
    // ...but it shadows the floor, and diffuse rays see it.
    EXPECT_TRUE(rs.occluded({0, 0, 1e-3f}, up, 0, kInfinity, kShadow));
    ASSERT_TRUE(rs.intersect({0, 0, 5}, down, 0, kInfinity, &hit, RayQuery{0.5f, STRATUM_VISIBLE_DIFFUSE}));
    EXPECT_NEAR(hit.position.z, 1.0f, 1e-6f);
    EXPECT_EQ(hit.visibility, not_camera);
    // The shadow-invisible holdout: the camera sees it, shadow rays pass it.
    ASSERT_TRUE(rs.intersect({3, 0, 5}, down, 0, kInfinity, &hit, kCamera));
    EXPECT_NEAR(hit.position.z, 1.0f, 1e-6f);
    EXPECT_TRUE(hit.holdout);
    EXPECT_EQ(hit.visibility, not_shadow);
    EXPECT_FALSE(rs.occluded({3, 0, 1e-3f}, up, 0, kInfinity, kShadow));
    EXPECT_TRUE(rs.occluded({3, 0, 1e-3f}, up, 0, kInfinity, kCamera));
}

// uv and dpdu of an instanced hit come from the prototype's corner_uvs and the transform: the
// unit-uv square of side 2 scaled by 2 and turned 90° about z has dpdu = 4 along world +y.
TEST(InstanceShading, UvAndTangentFollowTheTransform) {
    Scene scene = one_material_scene();
    scene.meshes.push_back(rectangle(-1, 1, -1, 1, 0));
    scene.instances.push_back(instance_of(0, rotation_z(0.5f * kPi, {2, 2, 2}, {0, 0, 1})));
    const RenderScene rs(scene);
    SurfaceHit hit;
    // World (0.5, 0.5) is object (0.25, -0.25) -> uv (0.625, 0.375).
    ASSERT_TRUE(rs.intersect({0.5f, 0.5f, 5}, {0, 0, -1}, 0, kInfinity, &hit));
    EXPECT_NEAR(hit.uv.x, 0.625f, 1e-5f);
    EXPECT_NEAR(hit.uv.y, 0.375f, 1e-5f);
    EXPECT_NEAR(hit.tangent_frame.dpdu.x, 0.0f, 1e-5f);
    EXPECT_NEAR(hit.tangent_frame.dpdu.y, 4.0f, 1e-5f);
    EXPECT_NEAR(hit.tangent_frame.dpdu.z, 0.0f, 1e-5f);
    EXPECT_NEAR(hit.geometric_normal.z, 1.0f, 1e-6f);
    // A mesh without uvs: uv 0 and dpdu 0.
    scene.meshes[0].corner_uvs.clear();
    const RenderScene plain(scene);
    ASSERT_TRUE(plain.intersect({0.5f, 0.5f, 5}, {0, 0, -1}, 0, kInfinity, &hit));
    EXPECT_EQ(hit.tangent_frame.dpdu.y, 0.0f);
    EXPECT_EQ(hit.uv.x, 0.0f);
}

// Emissive triangles of static instances are lights with the material's summed closure
// emission (sum_i weight_i * emission_i); a moving emitter gets no light entries.
TEST(InstanceShading, EmissiveLightsSumTheClosuresAndSkipMovingEmitters) {
    Scene scene;
    Material a{}, b{};
    a.emission = Rgb(1.0f, 2.0f, 3.0f);
    b.emission = Rgb(4.0f, 0.0f, 1.0f);
    scene.materials.push_back(
        SceneMaterial{{WeightedClosure{Rgb(0.5f), a}, WeightedClosure{Rgb(0.25f, 1.0f, 0.0f), b}}});
    EXPECT_EQ(material_emission(scene.materials[0]).r, 0.5f + 1.0f);
    EXPECT_EQ(material_emission(scene.materials[0]).g, 1.0f);
    EXPECT_EQ(material_emission(scene.materials[0]).b, 1.5f);
    scene.meshes.push_back(rectangle(-1, 1, -1, 1, 0));
    scene.instances.push_back(instance_of(0, Transform{}));
    Instance moving = instance_of(0, rotation_z(0, {1, 1, 1}, {5, 0, 0}));
    moving.motion = true;
    moving.object_to_world_end = rotation_z(0, {1, 1, 1}, {6, 0, 0});
    scene.instances.push_back(moving);
    Instance still = instance_of(0, rotation_z(0, {1, 1, 1}, {-5, 0, 0}));
    still.motion = true;  // flagged as moving, but both ends equal: a static light
    scene.instances.push_back(still);
    const RenderScene rs(scene);
    EXPECT_TRUE(rs.has_motion());
    EXPECT_EQ(rs.lights().size(), 4u);  // the two static squares' triangles
    LightSample ls;
    ASSERT_TRUE(rs.lights().sample({0, 0, 1}, {0, 0, 0}, 0.1f, {0.3f, 0.3f}, &ls));
    EXPECT_EQ(ls.radiance.r, 1.5f);
    EXPECT_EQ(ls.radiance.b, 1.5f);
    SurfaceHit hit;
    ASSERT_TRUE(rs.intersect({5.2f, 0, 1}, {0, 0, -1}, 0, kInfinity, &hit, RayQuery{0.0f, 31}));
    EXPECT_EQ(hit.emissive_light, kNoLight);
}

// Instance descriptions are validated by name.
TEST(InstanceVisibility, AbiValidatesInstancesByName) {
    using namespace stratum_test;
    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    const auto error = [&](const StratumInstanceDesc& d) {
        return stratum_scene_add_instance_ex(scene, &d) == STRATUM_OK ? std::string()
                                                                      : std::string(stratum_last_error());
    };
    StratumInstanceDesc d{};
    std::copy(kIdentity, kIdentity + 16, d.transform);
    EXPECT_NE(error(d).find("instance mesh_id 0 out of range [0, 0)"), std::string::npos) << error(d);
    const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t tri[3] = {0, 1, 2}, mats[1] = {0};
    const StratumMaterialDesc grey = diffuse_grey(0.5f);
    stratum_scene_add_material(scene, &grey, nullptr);
    const StratumMeshDesc mesh{pos, 3, tri, 1, nullptr, nullptr, mats};
    ASSERT_EQ(stratum_scene_add_mesh(scene, &mesh, nullptr), STRATUM_OK);
    d.visibility = 64;
    EXPECT_NE(error(d).find("instance visibility = 64"), std::string::npos) << error(d);
    d.visibility = 31;
    d.holdout = 2;
    EXPECT_NE(error(d).find("instance holdout = 2"), std::string::npos) << error(d);
    d.holdout = 1;
    d.motion = 1;  // transform_end all zero: not affine
    EXPECT_NE(error(d).find("instance transform_end is not affine"), std::string::npos) << error(d);
    d.transform_end[15] = 1;
    // A singular end (all zero) is no ABI error: the render scene skips the placement with a
    // notice (test_degenerate_instances.cpp).
    EXPECT_EQ(error(d), "");
    std::copy(kIdentity, kIdentity + 16, d.transform_end);
    d.transform_end[0] = std::nanf("");
    EXPECT_NE(error(d).find("instance transform_end element 0 = nan is not finite"), std::string::npos)
        << error(d);
    d.transform_end[0] = 1;
    d.motion = 3;
    EXPECT_NE(error(d).find("instance motion = 3"), std::string::npos) << error(d);
    d.motion = 1;
    EXPECT_EQ(error(d), "");
    stratum_scene_destroy(scene);
}
