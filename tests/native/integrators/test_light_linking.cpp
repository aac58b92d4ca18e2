// Light linking and shadow linking (scene/light_links.h, integrators/shadow_linking.h): the C
// ABI's checks, and the path tracer on a floor under one emitter, where what linking must give is
// known exactly (0, or the image without the occluder) for next-event estimation, for
// scattered rays alone (light_sampling bsdf: the forward side and its dedicated pass) and both.
//
// Tolerance of the comparisons of two renders: each image mean over P = 256 pixels has the
// standard error s/√P (s the pixel values' spread, which includes the floor's shading gradient,
// so it over-states the noise); two independent renders differ by at most 4 √(se₁² + se₂²) but
// with probability 6e-5 when they estimate the same value.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "render_helpers.h"

using namespace stratum_test;

namespace {

constexpr uint32_t kNoCamera = STRATUM_VISIBLE_ALL & ~STRATUM_VISIBLE_CAMERA;
constexpr uint64_t kAll = ~uint64_t{0};

// A square of half side `half` at height z facing +Z (down: facing −Z), seen by `visibility`.
bool add_square(StratumScene* scene, float z, float half, bool down, uint32_t material, uint32_t visibility) {
    const float corners_up[12] = {-half, -half, z, half, -half, z, half, half, z, -half, half, z};
    const float corners_down[12] = {-half, -half, z, -half, half, z, half, half, z, half, -half, z};
    StratumInstanceDesc d{};
    d.visibility = visibility;
    return add_quad_instance(scene, down ? corners_down : corners_up, material, d);
}

enum class Emitter { Mesh, PointLamp };

struct FloorScene {
    StratumScene* scene = nullptr;
};

// Instance 0: a grey floor (z = 0, half side 1); instance 1: the emitter, an emissive square
// facing down at z = 1 (or a point lamp there: light 0), unseen by the camera; instance 2 (if
// `occluder`): a black square at z = 0.5 between them, unseen by the camera. An orthographic
// camera looks down on the floor across [−1, 1]².
StratumScene* make_floor_scene(Emitter emitter, bool occluder) {
    StratumScene* scene = nullptr;
    if (stratum_scene_create(&scene) != STRATUM_OK) return nullptr;
    StratumMaterialDesc floor = diffuse_grey(0.8f), black = diffuse_grey(0.0f), light = diffuse_grey(0.0f);
    light.model = STRATUM_MATERIAL_EMISSION;
    light.emission[0] = light.emission[1] = light.emission[2] = 2.0f;
    uint32_t m_floor = 0, m_black = 0, m_light = 0;
    StratumCameraDesc camera = camera_at(0.0f, 0.0f, 3.0f);
    camera.type = STRATUM_CAMERA_ORTHOGRAPHIC;
    camera.ortho_scale = 2.0f;
    bool ok = stratum_scene_add_material(scene, &floor, &m_floor) == STRATUM_OK &&
              stratum_scene_add_material(scene, &black, &m_black) == STRATUM_OK &&
              stratum_scene_add_material(scene, &light, &m_light) == STRATUM_OK &&
              add_square(scene, 0.0f, 1.0f, false, m_floor, STRATUM_VISIBLE_ALL) &&
              stratum_scene_set_camera(scene, &camera) == STRATUM_OK;
    if (emitter == Emitter::Mesh) {
        ok = ok && add_square(scene, 1.0f, 0.5f, true, m_light, kNoCamera);
    } else {
        // The floor stays instance 0 and the occluder instance 2 as in the mesh scene.
        ok = ok && add_square(scene, -5.0f, 0.01f, false, m_black, kNoCamera);
        StratumLightDesc lamp{};
        lamp.type = STRATUM_LIGHT_POINT;
        lamp.color[0] = lamp.color[1] = lamp.color[2] = 1.0f;
        lamp.strength = 20.0f;
        std::copy(kIdentity, kIdentity + 16, lamp.transform);
        lamp.transform[11] = 1.0f;
        ok = ok && stratum_scene_add_light(scene, &lamp) == STRATUM_OK;
    }
    if (occluder) ok = ok && add_square(scene, 0.5f, 0.45f, false, m_black, kNoCamera);
    if (!ok) {
        stratum_scene_destroy(scene);
        return nullptr;
    }
    return scene;
}

// Sets the emitter's memberships (instance 1 or light 0) and the sets of instances 0 and 2.
bool link(StratumScene* scene, Emitter emitter, uint64_t light_membership, uint64_t shadow_membership,
          uint8_t floor_set, uint8_t occluder_set, bool occluder) {
    const uint8_t floor_receiver = floor_set;
    const bool emitter_ok =
        emitter == Emitter::Mesh
            ? stratum_scene_set_light_linking(scene, STRATUM_LINK_INSTANCES, 1, 1, nullptr, nullptr,
                                              &light_membership, &shadow_membership) == STRATUM_OK
            : stratum_scene_set_light_linking(scene, STRATUM_LINK_LIGHTS, 0, 1, nullptr, nullptr,
                                              &light_membership, &shadow_membership) == STRATUM_OK;
    return emitter_ok &&
           stratum_scene_set_light_linking(scene, STRATUM_LINK_INSTANCES, 0, 1, &floor_receiver, nullptr,
                                           nullptr, nullptr) == STRATUM_OK &&
           (!occluder || stratum_scene_set_light_linking(scene, STRATUM_LINK_INSTANCES, 2, 1, nullptr,
                                                         &occluder_set, nullptr, nullptr) == STRATUM_OK);
}

Settings direct(const char* light_sampling, uint32_t samples = 16) {
    return Settings{{"width", 16},
                    {"height", 16},
                    {"samples", samples},
                    {"max_bounces", 0},
                    {"sampler", "random"},
                    {"seed", 3u},
                    {"light_sampling", light_sampling}};
}

double max_value(const std::vector<float>& rgba) {
    double m = 0.0;
    for (size_t i = 0; i < rgba.size(); i += 4) m = std::max({m, double(rgba[i]), double(rgba[i + 1])});
    return m;
}

}  // namespace

TEST(LightLinkingAbi, ChecksSetIdsTargetsAndRanges) {
    StratumScene* scene = make_floor_scene(Emitter::PointLamp, true);
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    const uint8_t too_big = 64, fine = 63;
    const uint64_t membership = 1;
    EXPECT_EQ(stratum_scene_set_light_linking(scene, STRATUM_LINK_INSTANCES, 0, 1, &too_big, nullptr, nullptr,
                                              nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("receiver_light_set[0] = 64"), std::string::npos)
        << stratum_last_error();
    EXPECT_EQ(stratum_scene_set_light_linking(scene, STRATUM_LINK_INSTANCES, 0, 1, nullptr, &too_big, nullptr,
                                              nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(
        stratum_scene_set_light_linking(scene, STRATUM_LINK_INSTANCES, 0, 1, &fine, &fine, nullptr, nullptr),
        STRATUM_OK);
    // Lamps are emitters only.
    EXPECT_EQ(stratum_scene_set_light_linking(scene, STRATUM_LINK_LIGHTS, 0, 1, &fine, nullptr, &membership,
                                              nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_scene_set_light_linking(scene, STRATUM_LINK_LIGHTS, 1, 1, nullptr, nullptr, &membership,
                                              nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("outside the scene's 1"), std::string::npos)
        << stratum_last_error();
    EXPECT_EQ(stratum_scene_set_light_linking(scene, 2, 0, 1, nullptr, nullptr, &membership, nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_scene_set_light_linking(scene, STRATUM_LINK_INSTANCES, 2, 2, nullptr, nullptr,
                                              &membership, nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    stratum_scene_destroy(scene);
}

// A lamp (next-event estimation only) and an emissive square (both strategies) that light only
// the default set leave the floor, in set 1, exactly black by every strategy; lighting set 1 as
// well gives the image without linking, bit for bit.
TEST(LightLinking, AnEmitterLightsOnlyItsReceiverSets) {
    for (const Emitter emitter : {Emitter::PointLamp, Emitter::Mesh}) {
        for (const char* strategy : {"nee", "bsdf", "mis"}) {
            if (emitter == Emitter::PointLamp && std::string(strategy) == "bsdf") continue;
            StratumScene* scene = make_floor_scene(emitter, false);
            ASSERT_NE(scene, nullptr) << stratum_last_error();
            const RenderOutput plain = render(scene, direct(strategy, 4));
            ASSERT_TRUE(plain.error.empty()) << plain.error;
            ASSERT_GT(max_value(plain.rgba), 0.01) << strategy;
            ASSERT_TRUE(link(scene, emitter, 1u, kAll, 1, 0, false)) << stratum_last_error();
            const RenderOutput unlit = render(scene, direct(strategy, 4));
            EXPECT_EQ(max_value(unlit.rgba), 0.0) << strategy;
            ASSERT_TRUE(link(scene, emitter, 0b11u, kAll, 1, 0, false)) << stratum_last_error();
            const RenderOutput lit = render(scene, direct(strategy, 4));
            EXPECT_EQ(lit.rgba, plain.rgba) << strategy;
            stratum_scene_destroy(scene);
        }
    }
}

// Camera rays see every emitter, linked or not: an emissive square lighting no set is seen.
TEST(LightLinking, CameraRaysSeeEveryEmitter) {
    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    StratumMaterialDesc light = diffuse_grey(0.0f);
    light.model = STRATUM_MATERIAL_EMISSION;
    light.emission[0] = light.emission[1] = light.emission[2] = 2.0f;
    uint32_t m = 0;
    const StratumCameraDesc camera = camera_at(0.0f, 0.0f, 3.0f);
    ASSERT_EQ(stratum_scene_add_material(scene, &light, &m), STRATUM_OK);
    ASSERT_TRUE(add_square(scene, 0.0f, 10.0f, false, m, STRATUM_VISIBLE_ALL));
    ASSERT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK);
    const uint64_t none = 0;
    ASSERT_EQ(
        stratum_scene_set_light_linking(scene, STRATUM_LINK_INSTANCES, 0, 1, nullptr, nullptr, &none, &none),
        STRATUM_OK);
    const RenderOutput out = render(scene, direct("mis", 1));
    ASSERT_TRUE(out.error.empty()) << out.error;
    for (size_t i = 0; i < out.rgba.size(); i += 4) ASSERT_FLOAT_EQ(out.rgba[i], 2.0f) << i / 4;
    stratum_scene_destroy(scene);
}

// A lamp whose blocker set leaves out the occluder's: next-event estimation ignores the
// occluder, and the floor is the floor without it, bit for bit (the occluder is black and
// unseen by the camera, max_bounces 0). Not linked, the occluder's shadow darkens it.
TEST(ShadowLinking, ShadowRaysPassOccludersOutsideTheBlockerSets) {
    StratumScene* open = make_floor_scene(Emitter::PointLamp, false);
    StratumScene* blocked = make_floor_scene(Emitter::PointLamp, true);
    ASSERT_TRUE(open && blocked) << stratum_last_error();
    const RenderOutput reference = render(open, direct("mis", 4));
    const RenderOutput shadowed = render(blocked, direct("mis", 4));
    ASSERT_TRUE(reference.error.empty() && shadowed.error.empty());
    EXPECT_NE(shadowed.rgba, reference.rgba);
    ASSERT_TRUE(link(blocked, Emitter::PointLamp, kAll, kAll & ~uint64_t{0b10}, 0, 1, true))
        << stratum_last_error();
    const RenderOutput linked = render(blocked, direct("mis", 4));
    EXPECT_EQ(linked.rgba, reference.rgba);
    // The occluder in a set the lamp's blocker set holds blocks it again.
    ASSERT_TRUE(link(blocked, Emitter::PointLamp, kAll, 0b10, 0, 1, true)) << stratum_last_error();
    EXPECT_EQ(render(blocked, direct("mis", 4)).rgba, shadowed.rgba);
    stratum_scene_destroy(open);
    stratum_scene_destroy(blocked);
}

// An emissive square shadow-linked past the occluder: by light samples, by scattered rays alone
// (the dedicated pass: the main path's rays stop at the occluder) and by both, the floor's mean
// is the mean without the occluder (tolerance: header); not linked, it is far darker.
TEST(ShadowLinking, ScatteredRaysFindShadowLinkedEmittersPastExcludedOccluders) {
    StratumScene* open = make_floor_scene(Emitter::Mesh, false);
    StratumScene* blocked = make_floor_scene(Emitter::Mesh, true);
    ASSERT_TRUE(open && blocked) << stratum_last_error();
    for (const char* strategy : {"nee", "bsdf", "mis"}) {
        const Measurement reference = measure(open, direct(strategy, 64));
        const Measurement shadowed = measure(blocked, direct(strategy, 64));
        ASSERT_TRUE(reference.error.empty() && shadowed.error.empty()) << reference.error << shadowed.error;
        ASSERT_TRUE(link(blocked, Emitter::Mesh, kAll, kAll & ~uint64_t{0b10}, 0, 1, true))
            << stratum_last_error();
        const Measurement linked = measure(blocked, direct(strategy, 64));
        ASSERT_TRUE(link(blocked, Emitter::Mesh, kAll, kAll, 0, 0, true)) << stratum_last_error();
        const double tolerance = 4.0 * std::hypot(reference.standard_error, linked.standard_error);
        EXPECT_NEAR(linked.mean, reference.mean, tolerance) << strategy;
        EXPECT_GT(reference.mean - shadowed.mean, tolerance) << strategy;
    }
    stratum_scene_destroy(open);
    stratum_scene_destroy(blocked);
}

// The light tracer and radiosity do not link: one notice names the linked emitters.
TEST(LightLinking, MethodsWithoutLinkingSayWhichEmittersTheyDoNotLink) {
    StratumScene* scene = make_floor_scene(Emitter::PointLamp, false);
    ASSERT_NE(scene, nullptr);
    ASSERT_TRUE(link(scene, Emitter::PointLamp, 1u, kAll, 1, 0, false)) << stratum_last_error();
    for (const char* integrator : {"light", "radiosity"}) {
        Settings settings = direct("mis", 1);
        settings.emplace_back("integrator", integrator);
        const RenderOutput out = render(scene, settings);
        ASSERT_TRUE(out.error.empty()) << out.error;
        EXPECT_NE(out.notices.find("ignores light and shadow linking: light 0 light"), std::string::npos)
            << out.notices;
    }
    stratum_scene_destroy(scene);
}

// The sets survive what replaces an instance or a lamp (stratum_scene_set_instance,
// _set_light) and a scene file's round trip: the floor in set 1 stays unlit by the lamp that
// lights set 0 only, and the shadow-linked lamp still passes the occluder.
TEST(LightLinking, SetsSurviveEditsAndSceneFiles) {
    StratumScene* scene = make_floor_scene(Emitter::PointLamp, true);
    ASSERT_NE(scene, nullptr);
    ASSERT_TRUE(link(scene, Emitter::PointLamp, 0b11u, kAll & ~uint64_t{0b100}, 1, 2, true))
        << stratum_last_error();
    const RenderOutput linked = render(scene, direct("mis", 2));
    ASSERT_TRUE(link(scene, Emitter::PointLamp, 1u, kAll, 1, 2, true)) << stratum_last_error();
    StratumLightDesc lamp{};
    lamp.type = STRATUM_LIGHT_POINT;
    lamp.color[0] = lamp.color[1] = lamp.color[2] = 1.0f;
    lamp.strength = 30.0f;
    std::copy(kIdentity, kIdentity + 16, lamp.transform);
    lamp.transform[11] = 1.0f;
    ASSERT_EQ(stratum_scene_set_light(scene, 0, &lamp), STRATUM_OK);
    StratumInstanceDesc floor{};
    std::copy(kIdentity, kIdentity + 16, floor.transform);
    floor.visibility = STRATUM_VISIBLE_ALL;
    ASSERT_EQ(stratum_scene_set_instance(scene, 0, &floor), STRATUM_OK) << stratum_last_error();
    EXPECT_EQ(max_value(render(scene, direct("mis", 2)).rgba), 0.0);

    ASSERT_TRUE(link(scene, Emitter::PointLamp, 0b11u, kAll & ~uint64_t{0b100}, 1, 2, true))
        << stratum_last_error();
    ASSERT_EQ(stratum_scene_set_light(scene, 0, &lamp), STRATUM_OK);
    const RenderOutput brighter = render(scene, direct("mis", 2));
    const std::string path = testing::TempDir() + "stratum_light_linking.json";
    ASSERT_EQ(stratum_scene_save(scene, path.c_str()), STRATUM_OK) << stratum_last_error();
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(path.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    EXPECT_EQ(render(loaded, direct("mis", 2)).rgba, brighter.rgba);
    // 30 W against the first render's 20 W, the occluder passed: 1.5 times brighter everywhere.
    for (size_t i = 0; i < linked.rgba.size(); i += 4)
        EXPECT_NEAR(brighter.rgba[i], 1.5f * linked.rgba[i], 1e-5f * (1.0f + brighter.rgba[i])) << i / 4;
    std::remove(path.c_str());
    stratum_scene_destroy(loaded);
    stratum_scene_destroy(scene);
}

// NEE chooses among the lights that light the surface (RenderScene::lights_for, Cycles' light
// tree per receiver set): a floor lit by one of 16 point lamps around it (the others light set 0
// only) renders exactly as with that lamp alone, under the tree and the mixed choice. Rejecting
// the others' samples instead was measured at 37×, 232× and 1048× the pixel variance with 4, 16
// and 64 lamps under the tree (docs/cycles_models.md §17).
TEST(LightLinking, NeeChoosesAmongTheLightsOfTheReceiversSet) {
    const auto ring = [](uint32_t lamps, bool linked) {
        StratumScene* scene = make_floor_scene(Emitter::PointLamp, false);
        for (uint32_t i = 1; scene && i < lamps; ++i) {
            StratumLightDesc lamp{};
            lamp.type = STRATUM_LIGHT_POINT;
            lamp.color[0] = lamp.color[1] = lamp.color[2] = 1.0f;
            lamp.strength = 20.0f;
            std::copy(kIdentity, kIdentity + 16, lamp.transform);
            const float a = 6.2831853f * static_cast<float>(i) / static_cast<float>(lamps);
            lamp.transform[3] = 0.8f * std::cos(a);
            lamp.transform[7] = 0.8f * std::sin(a);
            lamp.transform[11] = 1.0f;
            if (stratum_scene_add_light(scene, &lamp) != STRATUM_OK)
                return static_cast<StratumScene*>(nullptr);
            const uint64_t default_set_only = 1;
            if (linked && stratum_scene_set_light_linking(scene, STRATUM_LINK_LIGHTS, i, 1, nullptr, nullptr,
                                                          &default_set_only, nullptr) != STRATUM_OK)
                return static_cast<StratumScene*>(nullptr);
        }
        const uint8_t floor_set = 1;
        if (linked && stratum_scene_set_light_linking(scene, STRATUM_LINK_INSTANCES, 0, 1, &floor_set,
                                                      nullptr, nullptr, nullptr) != STRATUM_OK)
            return static_cast<StratumScene*>(nullptr);
        return scene;
    };
    StratumScene* linked = ring(16, true);
    StratumScene* alone = ring(1, false);
    ASSERT_TRUE(linked && alone) << stratum_last_error();
    for (const char* selection : {"tree", "mixed"}) {
        Settings settings = direct("mis", 4);
        settings.emplace_back("light_selection", selection);
        const RenderOutput a = render(linked, settings), b = render(alone, settings);
        ASSERT_TRUE(a.error.empty() && b.error.empty()) << a.error << b.error;
        ASSERT_GT(max_value(b.rgba), 0.01);
        EXPECT_EQ(a.rgba, b.rgba) << selection;
    }
    stratum_scene_destroy(linked);
    stratum_scene_destroy(alone);
}
