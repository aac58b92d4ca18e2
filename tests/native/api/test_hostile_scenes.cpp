// Issue 12: inputs that aborted the host process (Embree's ray.valid() assertion) or gave
// non-finite or black images. Each is now either refused at the C ABI with a message naming the
// value, or rendered to finite pixels, with a notice where something was left out.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <cfloat>
#include <cmath>
#include <string>
#include <vector>

#include "render_helpers.h"

using namespace stratum_test;

namespace {

constexpr StratumMaterialDesc kGrey{STRATUM_MATERIAL_DIFFUSE, {0.5f, 0.5f, 0.5f}, 1, 0, 0, 1.5f, {0, 0, 0},
                                    STRATUM_MICROFACET_GGX};

// A 2 x 2 quad in the plane z = 0 (a mesh to place), material 0.
struct Quad {
    float positions[12] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    uint32_t triangles[6] = {0, 1, 2, 0, 2, 3};
    uint32_t materials[2] = {0, 0};
    StratumMeshDesc desc() const { return {positions, 4, triangles, 2, nullptr, nullptr, materials}; }
};

// A scene with a grey material, one quad mesh (not placed) and a camera 3 above looking down.
StratumScene* quad_scene(uint32_t* mesh_id) {
    StratumScene* scene = nullptr;
    stratum_scene_create(&scene);
    stratum_scene_add_material(scene, &kGrey, nullptr);
    const Quad quad;
    const StratumMeshDesc mesh = quad.desc();
    stratum_scene_add_mesh(scene, &mesh, mesh_id);
    const StratumCameraDesc camera = camera_at(0, 0, 3);
    stratum_scene_set_camera(scene, &camera);
    const float sky[3] = {0.2f, 0.2f, 0.2f};
    stratum_scene_set_background(scene, sky);
    return scene;
}

std::string camera_error(const StratumCameraDesc& c) {
    StratumScene* scene = nullptr;
    stratum_scene_create(&scene);
    const bool ok = stratum_scene_set_camera(scene, &c) == STRATUM_OK;
    const std::string message = ok ? "" : stratum_last_error();
    stratum_scene_destroy(scene);
    return message;
}

bool all_finite(const std::vector<float>& rgba) {
    for (float v : rgba)
        if (!std::isfinite(v)) return false;
    return !rgba.empty();
}

const Settings kTiny{{"width", 8}, {"height", 8}, {"samples", 2}, {"max_bounces", 2}};

}  // namespace

// The camera values an ABI fuzzer and a hostile corpus found: each refused, naming the field.
TEST(HostileScenes, ExtremeCamerasAreRefusedByName) {
    StratumCameraDesc far = camera_at(1e19f, 0, 0);
    EXPECT_NE(camera_error(far).find("camera transform places its origin"), std::string::npos);
    far.type = STRATUM_CAMERA_EQUIRECTANGULAR;
    far.latitude_min = -1, far.latitude_max = 1, far.longitude_min = -3, far.longitude_max = 3;
    EXPECT_NE(camera_error(far).find("camera transform places its origin"), std::string::npos);

    StratumCameraDesc ortho = camera_at(0, 0, 3);
    ortho.type = STRATUM_CAMERA_ORTHOGRAPHIC;
    ortho.ortho_scale = 1e20f;
    EXPECT_NE(camera_error(ortho).find("camera ortho_scale = 1e+20"), std::string::npos);

    StratumCameraDesc lens = camera_at(0, 0, 3);
    lens.lens_mm = 1e-38f;
    EXPECT_NE(camera_error(lens).find("camera lens_mm = 1e-38"), std::string::npos);

    StratumCameraDesc aperture = camera_at(0, 0, 3);
    aperture.aperture_radius = 1e30f;
    aperture.focus_distance = 1.0f;
    EXPECT_NE(camera_error(aperture).find("camera aperture_radius = 1e+30"), std::string::npos);

    // A camera matrix scaled to nothing has no view directions (fuzzer: scale 1e-38).
    StratumCameraDesc tiny = camera_at(0, 0, 3);
    tiny.transform[0] = tiny.transform[5] = tiny.transform[10] = 1e-38f;
    EXPECT_NE(camera_error(tiny).find("camera transform has an axis of length"), std::string::npos);
    StratumCameraDesc flat = camera_at(0, 0, 3);
    flat.transform[10] = 0.0f;
    flat.transform[6] = 1.0f;  // z axis = y axis: no volume
    EXPECT_NE(camera_error(flat).find("camera transform is (nearly) singular"), std::string::npos);

    // The largest values accepted still render finite pixels (the limits of scene_limits.h).
    uint32_t mesh = 0;
    StratumScene* scene = quad_scene(&mesh);
    stratum_scene_add_instance(scene, mesh, kIdentity);
    StratumCameraDesc edge = camera_at(0, 0, 1e12f);
    edge.type = STRATUM_CAMERA_ORTHOGRAPHIC;
    edge.ortho_scale = 1e12f;
    edge.clip_end = 1e30f;
    ASSERT_EQ(stratum_scene_set_camera(scene, &edge), STRATUM_OK) << stratum_last_error();
    EXPECT_TRUE(all_finite(render(scene, kTiny).rgba));
    edge = camera_at(0, 0, 3);
    edge.lens_mm = 1e-3f;
    edge.aperture_radius = 1e12f;
    edge.focus_distance = 1e12f;
    ASSERT_EQ(stratum_scene_set_camera(scene, &edge), STRATUM_OK) << stratum_last_error();
    EXPECT_TRUE(all_finite(render(scene, kTiny).rgba));
    stratum_scene_destroy(scene);
}

// A vertex at 1e30 used to vanish silently (Embree drops triangles beyond 1.8e18).
TEST(HostileScenes, FarVertexIsRefusedNamingIt) {
    StratumScene* scene = nullptr;
    stratum_scene_create(&scene);
    stratum_scene_add_material(scene, &kGrey, nullptr);
    Quad quad;
    quad.positions[6] = 1e30f;  // vertex 2
    const StratumMeshDesc mesh = quad.desc();
    ASSERT_NE(stratum_scene_add_mesh(scene, &mesh, nullptr), STRATUM_OK);
    EXPECT_NE(std::string(stratum_last_error()).find("mesh vertex 2 position (1e+30, 1, 0)"),
              std::string::npos)
        << stratum_last_error();
    stratum_scene_destroy(scene);
}

// Placements that put a mesh beyond the coordinate bound: refused, naming what is too large.
TEST(HostileScenes, FarPlacementsAreRefused) {
    uint32_t mesh = 0;
    StratumScene* scene = quad_scene(&mesh);
    float m[16];
    std::copy(kIdentity, kIdentity + 16, m);
    m[3] = 1e19f;
    ASSERT_NE(stratum_scene_add_instance(scene, mesh, m), STRATUM_OK);
    EXPECT_NE(std::string(stratum_last_error()).find("instance transform places its origin"),
              std::string::npos);
    std::copy(kIdentity, kIdentity + 16, m);
    m[0] = 1e19f;  // a 1e19 scale
    ASSERT_NE(stratum_scene_add_instance(scene, mesh, m), STRATUM_OK);
    EXPECT_NE(std::string(stratum_last_error()).find("instance transform element 0 = 1e+19"),
              std::string::npos);
    std::copy(kIdentity, kIdentity + 16, m);
    m[0] = m[5] = 1e12f;
    m[3] = 5e11f;  // each bound kept, the quad's corner at 1.5e12 is not
    ASSERT_NE(stratum_scene_add_instance(scene, mesh, m), STRATUM_OK);
    EXPECT_NE(std::string(stratum_last_error()).find("instance transform places mesh 0 up to 1.5e+12"),
              std::string::npos)
        << stratum_last_error();
    // A motion-blurred instance sheared by 1e19, or moving to -3.4e38 (which hung the render).
    StratumInstanceDesc moving{};
    moving.mesh_id = mesh;
    std::copy(kIdentity, kIdentity + 16, moving.transform);
    std::copy(kIdentity, kIdentity + 16, moving.transform_end);
    moving.motion = 1;
    moving.transform_end[1] = 1e19f;
    ASSERT_NE(stratum_scene_add_instance_ex(scene, &moving), STRATUM_OK);
    EXPECT_NE(std::string(stratum_last_error()).find("instance transform_end element 1"), std::string::npos);
    moving.transform_end[1] = 0.0f;
    moving.transform_end[3] = -3.4e38f;
    ASSERT_NE(stratum_scene_add_instance_ex(scene, &moving), STRATUM_OK);
    EXPECT_NE(std::string(stratum_last_error()).find("instance transform_end places its origin"),
              std::string::npos);
    stratum_scene_destroy(scene);
}

// A linked duplicate flattened to zero (scale (1, 0, 1)) or to 1e-18, and a motion whose scale
// changes sign over the shutter, made Embree abort on the object-space ray. They are skipped,
// with a notice, and the image is the one without them.
TEST(HostileScenes, DegenerateInstancesAreSkippedWithANotice) {
    const auto render_with = [](const float* extra, bool moving, std::string* notices) {
        uint32_t mesh = 0;
        StratumScene* scene = quad_scene(&mesh);
        stratum_scene_add_instance(scene, mesh, kIdentity);  // the mesh is shared: instanced
        if (extra) {
            StratumInstanceDesc d{};
            d.mesh_id = mesh;
            std::copy(extra, extra + 16, d.transform);
            std::copy(kIdentity, kIdentity + 16, d.transform_end);
            d.transform_end[3] = 0.5f;
            d.motion = moving ? 1 : 0;
            d.visibility = STRATUM_VISIBLE_ALL;
            EXPECT_EQ(stratum_scene_add_instance_ex(scene, &d), STRATUM_OK) << stratum_last_error();
        }
        const RenderOutput out = render(scene, kTiny);
        if (notices) *notices = out.notices;
        stratum_scene_destroy(scene);
        return out.rgba;
    };
    const std::vector<float> alone = render_with(nullptr, false, nullptr);
    ASSERT_TRUE(all_finite(alone));
    float flat[16], tiny[16], mirrored[16];
    std::copy(kIdentity, kIdentity + 16, flat);
    std::copy(kIdentity, kIdentity + 16, tiny);
    std::copy(kIdentity, kIdentity + 16, mirrored);
    flat[5] = 0.0f;
    tiny[0] = tiny[5] = tiny[10] = 1e-18f;
    mirrored[10] = -1.0f;  // moves to the identity: its z scale passes through 0
    for (const auto& [m, moving] :
         {std::pair{flat, false}, std::pair{tiny, false}, std::pair{mirrored, true}}) {
        std::string notices;
        EXPECT_EQ(render_with(m, moving, &notices), alone);
        EXPECT_NE(notices.find("instance 1 (mesh 0) has a degenerate transform"), std::string::npos)
            << notices;
    }
    // A small but sound scale renders: the quad scaled by 1e-6 is no notice.
    float small[16];
    std::copy(kIdentity, kIdentity + 16, small);
    small[0] = small[5] = small[10] = 1e-6f;
    std::string notices;
    EXPECT_TRUE(all_finite(render_with(small, false, &notices)));
    EXPECT_EQ(notices.find("degenerate"), std::string::npos) << notices;
}

// stratum_scene_measure_ray_throughput traces the scene's rays with the same guards.
TEST(HostileScenes, RayThroughputOfADegenerateSceneIsMeasured) {
    uint32_t mesh = 0;
    StratumScene* scene = quad_scene(&mesh);
    float flat[16];
    std::copy(kIdentity, kIdentity + 16, flat);
    flat[0] = 0.0f;
    stratum_scene_add_instance(scene, mesh, kIdentity);
    stratum_scene_add_instance(scene, mesh, flat);
    double rays = 0, seconds = 0;
    EXPECT_EQ(stratum_scene_measure_ray_throughput(scene, 4, 4, 1, 2, 1, &rays, &seconds), STRATUM_OK);
    EXPECT_GT(rays, 0.0);
    stratum_scene_destroy(scene);
}

// Emission, lamps and the sky at about FLT_MAX: finite pixels (sums of such samples overflowed
// to Inf; a lamp's mean power (r + g + b) / 3 overflowed, making its choice probability NaN and
// the lamp black), and not black. The film's exact sums clamp a sample at 2^55 (film/film.h), so
// a pixel seen straight at such an emitter is 2^55, and the clamp is reported.
TEST(HostileScenes, RadianceNearTheLargestFloatStaysFinite) {
    const float huge = 3e38f;
    const auto centre_of = [](StratumScene* scene, const Settings& settings) {
        const RenderOutput out = render(scene, settings);
        EXPECT_TRUE(all_finite(out.rgba)) << out.error;
        if (!out.rgba.empty() && out.rgba[4 * (4 * 8 + 4)] >= 0x1p55f) {
            EXPECT_NE(out.notices.find("were clamped there"), std::string::npos) << out.notices;
        }
        return out.rgba.empty() ? 0.0f : out.rgba[4 * (4 * 8 + 4)];
    };
    // An emitter seen by the camera, 16 samples of it summed.
    {
        StratumScene* scene = nullptr;
        stratum_scene_create(&scene);
        StratumMaterialDesc light = kGrey;
        light.model = STRATUM_MATERIAL_EMISSION;
        light.emission[0] = light.emission[1] = light.emission[2] = FLT_MAX;
        uint32_t mat = 0, mesh = 0;
        stratum_scene_add_material(scene, &light, &mat);
        const Quad quad;
        const StratumMeshDesc desc = quad.desc();
        stratum_scene_add_mesh(scene, &desc, &mesh);
        stratum_scene_add_instance(scene, mesh, kIdentity);
        // Close enough that the quad fills the frame (90° view of ±0.5 at height 0.5): every
        // sample of the centre pixel, wherever the filter puts it, sees the emitter.
        const StratumCameraDesc camera = camera_at(0, 0, 0.5f);
        stratum_scene_set_camera(scene, &camera);
        EXPECT_EQ(centre_of(scene, {{"width", 8}, {"height", 8}, {"samples", 16}}), 0x1p55f);
        stratum_scene_destroy(scene);
    }
    // A background of 3e38 (fuzzer: an orthographic camera gave an infinite pixel).
    {
        uint32_t mesh = 0;
        StratumScene* scene = quad_scene(&mesh);
        const float sky[3] = {huge, huge, huge};
        stratum_scene_set_background(scene, sky);
        StratumCameraDesc ortho = camera_at(0, 0, 3);
        ortho.type = STRATUM_CAMERA_ORTHOGRAPHIC;
        ortho.ortho_scale = 4.0f;
        stratum_scene_set_camera(scene, &ortho);
        EXPECT_EQ(centre_of(scene, {{"width", 8}, {"height", 8}, {"samples", 16}}), 0x1p55f);
        stratum_scene_destroy(scene);
    }
    // Every lamp type, lighting the quad from 2 above.
    for (int32_t type : {STRATUM_LIGHT_POINT, STRATUM_LIGHT_SUN, STRATUM_LIGHT_AREA_RECTANGLE,
                         STRATUM_LIGHT_AREA_ELLIPSE, STRATUM_LIGHT_SPOT, STRATUM_LIGHT_SPOT_V1}) {
        for (float radius : {0.0f, 0.01f}) {
            uint32_t mesh = 0;
            StratumScene* scene = quad_scene(&mesh);
            const float black[3] = {0, 0, 0};
            stratum_scene_set_background(scene, black);
            stratum_scene_add_instance(scene, mesh, kIdentity);
            StratumLightDesc l{};
            l.type = type;
            l.color[0] = l.color[1] = l.color[2] = 1.0f;
            l.strength = huge;
            l.radius = radius;
            l.angle = radius;  // the sun: a point, or 0.01 rad wide
            l.size_x = l.size_y = radius > 0.0f ? radius : 0.5f;
            l.spot_size = 1.0f;
            std::copy(kIdentity, kIdentity + 16, l.transform);
            l.transform[11] = 2.0f;
            ASSERT_EQ(stratum_scene_add_light(scene, &l), STRATUM_OK) << stratum_last_error();
            const float lit = centre_of(scene, kTiny);
            EXPECT_GT(lit, 0.0f) << "light type " << type << " radius " << radius;
            stratum_scene_destroy(scene);
        }
    }
}

// A sample whose radiance is beyond float (two closures each emitting FLT_MAX sum to Inf) is
// dropped, counted and reported once the render ends; the film stays finite.
TEST(HostileScenes, DroppedSamplesAreReported) {
    StratumScene* scene = nullptr;
    stratum_scene_create(&scene);
    StratumMaterialDesc emitter = kGrey;
    emitter.model = STRATUM_MATERIAL_EMISSION;
    emitter.emission[0] = emitter.emission[1] = emitter.emission[2] = FLT_MAX;
    const StratumClosureDesc twice[2] = {{{1, 1, 1}, emitter}, {{1, 1, 1}, emitter}};
    uint32_t doubled = 0, mesh = 0;
    ASSERT_EQ(stratum_scene_add_closure_material(scene, twice, 2, &doubled), STRATUM_OK);
    Quad quad;
    quad.materials[0] = quad.materials[1] = doubled;
    const StratumMeshDesc desc = quad.desc();
    stratum_scene_add_mesh(scene, &desc, &mesh);
    stratum_scene_add_instance(scene, mesh, kIdentity);
    const StratumCameraDesc camera = camera_at(0, 0, 3);
    stratum_scene_set_camera(scene, &camera);
    const RenderOutput out = render(scene, kTiny);
    EXPECT_TRUE(all_finite(out.rgba));
    EXPECT_NE(out.notices.find("samples were not finite"), std::string::npos) << out.notices;
    stratum_scene_destroy(scene);
}

// The film is allocated for the rendered region: a 65536 x 65536 frame (Blender's largest) needs
// 208 GiB of film and is refused before allocating, naming the size, where Linux's overcommit
// would have granted part of it and the OOM killer ended the host; an 8 x 8 border of the same
// frame renders.
TEST(HostileScenes, FilmBeyondMemoryIsRefusedNamingTheSize) {
    uint32_t mesh = 0;
    StratumScene* scene = quad_scene(&mesh);
    stratum_scene_add_instance(scene, mesh, kIdentity);
    const RenderOutput out = render(scene, Settings{{"width", 65536}, {"height", 65536}, {"samples", 1}});
    EXPECT_TRUE(out.rgba.empty());
    EXPECT_NE(out.error.find("65536 x 65536 pixel render needs"), std::string::npos) << out.error;
    EXPECT_NE(out.error.find("for its film"), std::string::npos) << out.error;

    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    for (const auto& [name, value] : {std::pair{"width", 65536},
                                      {"height", 65536},
                                      {"samples", 1},
                                      {"crop_x", 32768},
                                      {"crop_y", 32768},
                                      {"crop_width", 8},
                                      {"crop_height", 8}})
        ASSERT_EQ(stratum_renderer_set_int(r, name, value), STRATUM_OK) << name;
    ASSERT_TRUE(render_to_end(r)) << stratum_last_error();
    std::vector<float> rgba(8 * 8 * 4);
    EXPECT_EQ(stratum_renderer_read_pixels(r, rgba.data(), rgba.size()), STRATUM_OK) << stratum_last_error();
    EXPECT_TRUE(all_finite(rgba));
    stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
}
