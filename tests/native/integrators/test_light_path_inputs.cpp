// What the path integrator gives the Light Path node's inputs (STRATUM_INPUT_IS_CAMERA_RAY ..
// PORTAL_DEPTH) in each context, as Cycles' kernel fills its path flag and counters: a surface
// on the camera path (behind transparent sheets, after a mirror), the transparent surfaces of a
// shadow ray, a lamp for a light sample and for a camera ray, and the world for camera, BSDF and
// light-sample rays. Every scene is deterministic (one sample per pixel centre, delta lights or
// delta scattering), so each value is exact; the world's light sample is a mean with its error.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "node_types.h"
#include "render_helpers.h"
#include "scene_handle.h"

namespace {

constexpr uint32_t kInputs = STRATUM_SHADER_INPUT_REGISTERS;
constexpr int kSize = 4;

// A channel of a program's RGB: a renderer input, or one minus it.
struct Channel {
    uint32_t input;
    bool one_minus = false;
};

// A program whose registers kInputs .. kInputs + 2 hold the three channels (kInputs + 3 holds 1).
StratumShaderProgramDesc channels_program(const std::array<Channel, 3>& channels,
                                          std::vector<StratumShaderNode>& nodes,
                                          std::vector<float>& registers) {
    registers.assign(kInputs + 4, 0.0f);
    registers[kInputs + 3] = 1.0f;
    nodes.clear();
    for (uint32_t k = 0; k < 3; ++k) {
        StratumShaderNode n{};
        if (channels[k].one_minus) {
            n.type = stratum_test::node_type("math");
            n.modes[0] = 1;  // SUBTRACT
            n.inputs[0] = kInputs + 3;
            n.inputs[1] = n.inputs[2] = channels[k].input;
        } else {
            n.type = stratum_test::node_type("copy");
            n.inputs[0] = channels[k].input;
        }
        n.outputs[0] = kInputs + k;
        nodes.push_back(n);
    }
    return {nodes.data(), 3, registers.data(), static_cast<uint32_t>(registers.size()), nullptr, 0};
}

uint32_t add_program(StratumScene* scene, const std::array<Channel, 3>& channels) {
    std::vector<StratumShaderNode> nodes;
    std::vector<float> registers;
    const StratumShaderProgramDesc desc = channels_program(channels, nodes, registers);
    uint32_t id = 0;
    EXPECT_EQ(stratum_scene_add_shader_program(scene, &desc, &id), STRATUM_OK) << stratum_last_error();
    return id;
}

// A horizontal square at height z of material `material`, seen by the rays of `visibility`.
void add_sheet(StratumScene* scene, float z, uint32_t material, uint32_t visibility) {
    const float corners[12] = {-10, -10, z, 10, -10, z, 10, 10, z, -10, 10, z};
    StratumInstanceDesc inst{};
    inst.visibility = visibility;
    ASSERT_TRUE(stratum_test::add_quad_instance(scene, corners, material, inst)) << stratum_last_error();
}

uint32_t add_material(StratumScene* scene, StratumMaterialDesc m) {
    uint32_t id = 0;
    EXPECT_EQ(stratum_scene_add_material(scene, &m, &id), STRATUM_OK);
    return id;
}

StratumMaterialDesc model(int32_t type, float k) {
    StratumMaterialDesc m = stratum_test::diffuse_grey(k);
    m.model = type;
    return m;
}

// Renders kSize² pixel centres from above (orthographic, from z = 3) and expects `want` in every
// pixel.
void expect_every_pixel(StratumScene* scene, std::array<float, 3> want, stratum_test::Settings extra = {}) {
    StratumCameraDesc camera = stratum_test::camera_at(0.0f, 0.0f, 3.0f);
    camera.type = STRATUM_CAMERA_ORTHOGRAPHIC;
    camera.ortho_scale = 2.0f;
    ASSERT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK);
    stratum_test::Settings settings{
        {"width", kSize}, {"height", kSize}, {"samples", 1}, {"filter_type", "box"}, {"filter_width", 0.01}};
    settings.insert(settings.end(), extra.begin(), extra.end());
    const stratum_test::RenderOutput out = stratum_test::render(scene, settings);
    ASSERT_TRUE(out.error.empty()) << out.error;
    for (int p = 0; p < kSize * kSize; ++p)
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(out.rgba[p * 4 + c], want[c], 1e-5f) << "pixel " << p << " channel " << c;
}

// An emitter whose emission is `channels`, under two clear Transparent sheets: the camera ray
// keeps its kind through them (Is Camera Ray 1), arrives at depth 0 with transparent depth 2.
void camera_behind_sheets(const std::array<Channel, 3>& channels, std::array<float, 3> want) {
    stratum_test::SceneHandle h;
    const uint32_t emitter = add_material(h.scene, model(STRATUM_MATERIAL_EMISSION, 0.0f));
    const uint32_t sheet = add_material(h.scene, model(STRATUM_MATERIAL_TRANSPARENT, 1.0f));
    add_sheet(h.scene, 0.0f, emitter, STRATUM_VISIBLE_ALL);
    add_sheet(h.scene, 1.0f, sheet, STRATUM_VISIBLE_ALL);
    add_sheet(h.scene, 2.0f, sheet, STRATUM_VISIBLE_ALL);
    const StratumProgramBinding b{emitter, 0, STRATUM_PROGRAM_EMISSION, add_program(h.scene, channels),
                                  kInputs};
    ASSERT_EQ(stratum_scene_bind_program(h.scene, &b), STRATUM_OK) << stratum_last_error();
    expect_every_pixel(h.scene, want);
}

TEST(LightPathInputs, ACameraRayKeepsItsKindThroughTransparentSurfaces) {
    camera_behind_sheets(
        {{{STRATUM_INPUT_IS_CAMERA_RAY}, {STRATUM_INPUT_TRANSPARENT_DEPTH}, {STRATUM_INPUT_RAY_DEPTH}}},
        {1.0f, 2.0f, 0.0f});
    camera_behind_sheets(
        {{{STRATUM_INPUT_IS_SHADOW_RAY}, {STRATUM_INPUT_IS_REFLECTION_RAY}, {STRATUM_INPUT_IS_GLOSSY_RAY}}},
        {0.0f, 0.0f, 0.0f});
    camera_behind_sheets({{{STRATUM_INPUT_DIFFUSE_DEPTH},
                           {STRATUM_INPUT_IS_VOLUME_SCATTER_RAY},
                           {STRATUM_INPUT_PORTAL_DEPTH}}},
                         {0.0f, 0.0f, 0.0f});
}

// A camera ray reflected by a perfect mirror up to an emitter the camera does not see: the ray
// is a singular glossy reflection at depth 1 (Cycles: REFLECT | GLOSSY | SINGULAR, bounce 1,
// glossy_bounce 1).
void after_a_mirror(const std::array<Channel, 3>& channels, std::array<float, 3> want) {
    stratum_test::SceneHandle h;
    const uint32_t emitter = add_material(h.scene, model(STRATUM_MATERIAL_EMISSION, 0.0f));
    StratumMaterialDesc mirror = model(STRATUM_MATERIAL_GLOSSY, 1.0f);
    mirror.roughness = 0.0f;
    const uint32_t mirror_id = add_material(h.scene, mirror);
    add_sheet(h.scene, 0.0f, mirror_id, STRATUM_VISIBLE_ALL);
    add_sheet(h.scene, 1.0f, emitter, STRATUM_VISIBLE_ALL & ~STRATUM_VISIBLE_CAMERA);
    const StratumProgramBinding b{emitter, 0, STRATUM_PROGRAM_EMISSION, add_program(h.scene, channels),
                                  kInputs};
    ASSERT_EQ(stratum_scene_bind_program(h.scene, &b), STRATUM_OK) << stratum_last_error();
    expect_every_pixel(h.scene, want);
}

TEST(LightPathInputs, AMirroredRayIsASingularGlossyReflectionOneDeep) {
    after_a_mirror(
        {{{STRATUM_INPUT_IS_GLOSSY_RAY}, {STRATUM_INPUT_IS_SINGULAR_RAY}, {STRATUM_INPUT_IS_REFLECTION_RAY}}},
        {1.0f, 1.0f, 1.0f});
    after_a_mirror({{{STRATUM_INPUT_RAY_DEPTH}, {STRATUM_INPUT_GLOSSY_DEPTH}, {STRATUM_INPUT_IS_CAMERA_RAY}}},
                   {1.0f, 1.0f, 0.0f});
    after_a_mirror({{{STRATUM_INPUT_IS_DIFFUSE_RAY},
                     {STRATUM_INPUT_IS_TRANSMISSION_RAY},
                     {STRATUM_INPUT_DIFFUSE_DEPTH}}},
                   {0.0f, 0.0f, 0.0f});
}

// A diffuse floor (reflectance 0.5) under a sun shining straight down through two sheets the
// camera does not see, whose Transparent colour is `channels`: the floor shows the sun's light
// times the product of the sheets' colours for its shadow ray. With irradiance pi the floor is
// 0.5 where the shadow ray passes freely. Max bounces 0: only the floor's light sample counts.
void shadow_through_sheets(const std::array<Channel, 3>& channels, std::array<float, 3> want) {
    stratum_test::SceneHandle h;
    const uint32_t sheet = add_material(h.scene, model(STRATUM_MATERIAL_TRANSPARENT, 1.0f));
    const uint32_t floor = add_material(h.scene, stratum_test::diffuse_grey(0.5f));
    add_sheet(h.scene, 0.0f, floor, STRATUM_VISIBLE_ALL);
    add_sheet(h.scene, 1.0f, sheet, STRATUM_VISIBLE_ALL & ~STRATUM_VISIBLE_CAMERA);
    add_sheet(h.scene, 2.0f, sheet, STRATUM_VISIBLE_ALL & ~STRATUM_VISIBLE_CAMERA);
    const StratumProgramBinding b{sheet, 0, STRATUM_PROGRAM_BASE_COLOR, add_program(h.scene, channels),
                                  kInputs};
    ASSERT_EQ(stratum_scene_bind_program(h.scene, &b), STRATUM_OK) << stratum_last_error();
    StratumLightDesc sun{};
    sun.type = STRATUM_LIGHT_SUN;
    sun.color[0] = sun.color[1] = sun.color[2] = 1.0f;
    sun.strength = 3.14159265f;
    std::copy(stratum_test::kIdentity, stratum_test::kIdentity + 16, sun.transform);
    ASSERT_EQ(stratum_scene_add_light(h.scene, &sun), STRATUM_OK);
    for (float& w : want) w *= 0.5f;
    expect_every_pixel(h.scene, want, {{"max_bounces", 0}});
}

TEST(LightPathInputs, AShadowRaysSurfacesSeeOnlyIsShadowAndCountTheSurfacesCrossed) {
    // Ray Depth: the floor's bounce 0, plus one on a shadow ray; Transparent Depth 0 at the
    // first sheet, 1 at the second (1 - it: 1 x 0).
    shadow_through_sheets(
        {{{STRATUM_INPUT_IS_SHADOW_RAY}, {STRATUM_INPUT_RAY_DEPTH}, {STRATUM_INPUT_TRANSPARENT_DEPTH, true}}},
        {1.0f, 1.0f, 0.0f});
    // The arriving ray's kinds are not the shadow ray's: Cycles passes PATH_RAY_SHADOW alone.
    shadow_through_sheets({{{STRATUM_INPUT_IS_CAMERA_RAY, true},
                            {STRATUM_INPUT_IS_DIFFUSE_RAY, true},
                            {STRATUM_INPUT_IS_REFLECTION_RAY, true}}},
                          {1.0f, 1.0f, 1.0f});
}

// The floor of shadow_through_sheets without sheets, lit by a sun whose program scales it by
// `channels`: a light sample evaluates the lamp with Cycles' PATH_RAY_EMISSION alone (no ray
// kind) one bounce further than the floor (Ray Depth 1).
void sun_program(const std::array<Channel, 3>& channels, std::array<float, 3> want) {
    stratum_test::SceneHandle h;
    const uint32_t floor = add_material(h.scene, stratum_test::diffuse_grey(0.5f));
    add_sheet(h.scene, 0.0f, floor, STRATUM_VISIBLE_ALL);
    StratumLightDesc sun{};
    sun.type = STRATUM_LIGHT_SUN;
    sun.color[0] = sun.color[1] = sun.color[2] = 1.0f;
    sun.strength = 3.14159265f;
    std::copy(stratum_test::kIdentity, stratum_test::kIdentity + 16, sun.transform);
    ASSERT_EQ(stratum_scene_add_light(h.scene, &sun), STRATUM_OK);
    ASSERT_EQ(stratum_scene_set_light_program(h.scene, 0, add_program(h.scene, channels), kInputs),
              STRATUM_OK)
        << stratum_last_error();
    for (float& w : want) w *= 0.5f;
    expect_every_pixel(h.scene, want, {{"max_bounces", 0}});
}

TEST(LightPathInputs, ALampsLightSampleHasNoRayKindAndIsOneBounceFurther) {
    sun_program({{{STRATUM_INPUT_RAY_DEPTH},
                  {STRATUM_INPUT_IS_CAMERA_RAY, true},
                  {STRATUM_INPUT_IS_SHADOW_RAY, true}}},
                {1.0f, 1.0f, 1.0f});
    sun_program({{{STRATUM_INPUT_IS_DIFFUSE_RAY, true},
                  {STRATUM_INPUT_DIFFUSE_DEPTH, true},
                  {STRATUM_INPUT_TRANSPARENT_DEPTH, true}}},
                {1.0f, 1.0f, 1.0f});
}

// An area lamp facing the camera across the whole view, scaled by `channels`: a camera ray that
// meets a lamp evaluates it with PATH_RAY_EMISSION alone too (the lamp that lights but is not
// seen: Is Camera Ray 0), at Ray Depth 0 + 1. The lamp's radiance is power / (pi area) = 1.
void lamp_seen_by_camera(const std::array<Channel, 3>& channels, std::array<float, 3> want) {
    stratum_test::SceneHandle h;
    StratumLightDesc lamp{};
    lamp.type = STRATUM_LIGHT_AREA_RECTANGLE;
    lamp.color[0] = lamp.color[1] = lamp.color[2] = 1.0f;
    lamp.size_x = lamp.size_y = 8.0f;
    lamp.strength = 3.14159265f * 64.0f;
    std::copy(stratum_test::kIdentity, stratum_test::kIdentity + 16, lamp.transform);
    // Below the camera, emitting up (+Z): local -Z turned over.
    lamp.transform[5] = -1.0f;
    lamp.transform[10] = -1.0f;
    ASSERT_EQ(stratum_scene_add_light(h.scene, &lamp), STRATUM_OK);
    ASSERT_EQ(stratum_scene_set_light_program(h.scene, 0, add_program(h.scene, channels), kInputs),
              STRATUM_OK)
        << stratum_last_error();
    expect_every_pixel(h.scene, want);
}

TEST(LightPathInputs, ALampMetByACameraRayIsNotACameraRaysHit) {
    lamp_seen_by_camera(
        {{{STRATUM_INPUT_IS_CAMERA_RAY}, {STRATUM_INPUT_RAY_DEPTH}, {STRATUM_INPUT_IS_CAMERA_RAY, true}}},
        {0.0f, 1.0f, 1.0f});
}

// A world whose program is `channels`, over a diffuse floor (reflectance 0.5) that fills the
// view when `floor`: the camera sees it with its own ray's kind, Ray Depth 0 + 1; a BSDF ray of
// the floor with its kind (diffuse reflection) and Ray Depth 1 + 1; a light sample with no kind
// and Ray Depth 0 + 1.
void world_program(const std::array<Channel, 3>& channels, bool floor, std::array<float, 3> want,
                   const char* light_sampling = "bsdf") {
    stratum_test::SceneHandle h;
    if (floor)
        add_sheet(h.scene, 0.0f, add_material(h.scene, stratum_test::diffuse_grey(0.5f)),
                  STRATUM_VISIBLE_ALL);
    const uint32_t program = add_program(h.scene, channels);
    ASSERT_EQ(stratum_scene_set_background_program(h.scene, program, kInputs, 16, 8), STRATUM_OK)
        << stratum_last_error();
    for (float& w : want) w *= floor ? 0.5f : 1.0f;
    expect_every_pixel(h.scene, want, {{"max_bounces", 0}, {"light_sampling", light_sampling}});
}

TEST(LightPathInputs, TheWorldSeesTheRaysThatLeaveTheScene) {
    world_program(
        {{{STRATUM_INPUT_IS_CAMERA_RAY}, {STRATUM_INPUT_RAY_DEPTH}, {STRATUM_INPUT_IS_DIFFUSE_RAY}}}, false,
        {1.0f, 1.0f, 0.0f});
    // A diffuse bounce: a cosine-sampled direction of a constant world carries exactly its value.
    world_program({{{STRATUM_INPUT_IS_CAMERA_RAY, true},
                    {STRATUM_INPUT_IS_DIFFUSE_RAY},
                    {STRATUM_INPUT_DIFFUSE_DEPTH}}},
                  true, {1.0f, 1.0f, 1.0f});
    world_program(
        {{{STRATUM_INPUT_RAY_DEPTH}, {STRATUM_INPUT_IS_REFLECTION_RAY}, {STRATUM_INPUT_IS_GLOSSY_RAY}}}, true,
        {2.0f, 1.0f, 0.0f});
}

// The same world lights the floor by light samples only: each is the world program's value with
// no ray kind and Ray Depth 1, taken in a direction the baked map (Cycles' importance-map state:
// here 1 everywhere) chose. The floor's mean over the pixels is 0.5 x the value.
TEST(LightPathInputs, TheWorldsLightSampleHasNoRayKind) {
    stratum_test::SceneHandle h;
    add_sheet(h.scene, 0.0f, add_material(h.scene, stratum_test::diffuse_grey(0.5f)), STRATUM_VISIBLE_ALL);
    const uint32_t program = add_program(
        h.scene,
        {{{STRATUM_INPUT_IS_CAMERA_RAY, true}, {STRATUM_INPUT_RAY_DEPTH}, {STRATUM_INPUT_IS_DIFFUSE_RAY}}});
    ASSERT_EQ(stratum_scene_set_background_program(h.scene, program, kInputs, 16, 8), STRATUM_OK);
    StratumCameraDesc camera = stratum_test::camera_at(0.0f, 0.0f, 3.0f);
    camera.type = STRATUM_CAMERA_ORTHOGRAPHIC;
    camera.ortho_scale = 2.0f;
    ASSERT_EQ(stratum_scene_set_camera(h.scene, &camera), STRATUM_OK);
    const stratum_test::RenderOutput out =
        stratum_test::render(h.scene, stratum_test::Settings{{"width", 16},
                                                             {"height", 16},
                                                             {"samples", 16},
                                                             {"max_bounces", 0},
                                                             {"light_sampling", "nee"},
                                                             {"seed", 7}});
    ASSERT_TRUE(out.error.empty()) << out.error;
    for (int c = 0; c < 3; ++c) {
        const stratum_test::PixelStats s = stratum_test::pixel_stats(out.rgba, c);
        // Independent pixels (a random sampler per pixel): the mean is within 5 standard errors
        // of 0.5 x the value (a false failure 1 time in ~2 million); 0 exactly when it is 0.
        const double want = c == 2 ? 0.0 : 0.5;
        EXPECT_NEAR(s.mean, want, 5.0 * s.standard_error + 1e-6) << "channel " << c;
    }
}

// A scene file keeps a world program that reads the node (by its id; the map is baked again on
// loading): the loaded scene's camera still sees Is Camera Ray 1, which the map (baked without
// it) does not hold.
TEST(LightPathInputs, ASceneFileKeepsTheWorldsProgram) {
    stratum_test::SceneHandle h;
    const uint32_t program = add_program(
        h.scene, {{{STRATUM_INPUT_IS_CAMERA_RAY}, {STRATUM_INPUT_RAY_DEPTH}, {STRATUM_INPUT_IS_SHADOW_RAY}}});
    ASSERT_EQ(stratum_scene_set_background_program(h.scene, program, kInputs, 16, 8), STRATUM_OK);
    const std::string path = ::testing::TempDir() + "light_path_world.json";
    ASSERT_EQ(stratum_scene_save(h.scene, path.c_str()), STRATUM_OK) << stratum_last_error();
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(path.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    expect_every_pixel(loaded, {1.0f, 1.0f, 0.0f});
    stratum_scene_destroy(loaded);
    std::remove(path.c_str());
}

// Light tracing and radiosity do not follow Cycles' camera paths: one notice names the programs
// that read the node.
TEST(LightPathInputs, LightTracingNamesWhatReadsTheNode) {
    stratum_test::SceneHandle h;
    const uint32_t emitter = add_material(h.scene, model(STRATUM_MATERIAL_EMISSION, 0.0f));
    add_sheet(h.scene, 0.0f, emitter, STRATUM_VISIBLE_ALL);
    const StratumProgramBinding b{
        emitter, 0, STRATUM_PROGRAM_EMISSION,
        add_program(h.scene,
                    {{{STRATUM_INPUT_IS_CAMERA_RAY}, {STRATUM_INPUT_RAY_DEPTH}, {STRATUM_INPUT_RAY_DEPTH}}}),
        kInputs};
    ASSERT_EQ(stratum_scene_bind_program(h.scene, &b), STRATUM_OK);
    const StratumCameraDesc camera = stratum_test::camera_at(0.0f, 0.0f, 3.0f);
    ASSERT_EQ(stratum_scene_set_camera(h.scene, &camera), STRATUM_OK);
    for (const char* integrator : {"light", "radiosity"}) {
        const stratum_test::RenderOutput out = stratum_test::render(
            h.scene,
            stratum_test::Settings{{"width", 4}, {"height", 4}, {"samples", 1}, {"integrator", integrator}});
        ASSERT_TRUE(out.error.empty()) << out.error;
        EXPECT_NE(out.notices.find("the Light Path node of material 0 gives fixed values"), std::string::npos)
            << integrator << ": " << out.notices;
    }
    const stratum_test::RenderOutput path = stratum_test::render(
        h.scene, stratum_test::Settings{{"width", 4}, {"height", 4}, {"samples", 1}, {"integrator", "path"}});
    EXPECT_EQ(path.notices.find("Light Path"), std::string::npos) << path.notices;
}

}  // namespace
