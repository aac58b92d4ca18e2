// Light groups (film/light_groups.h, integrators/light_group_writer.h): each emitter's clamped
// contributions go to its group, at every bounce and seen directly, so groups that hold every
// emitter sum to Combined per pixel, to float rounding (each sums the same contributions in
// another order: relative 1e-5 covers the float additions of a few dozen contributions).
// Scene: a grey floor and a wall under two area lamps (groups 1 and 2), an emissive quad in
// group 1 and a grey world in group 2, three bounces with clamping on, seen from above (each
// sample at its pixel's centre); lamp 2 faces the camera, so its own pixels are in group 2 alone.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "render_helpers.h"

using namespace stratum_test;

namespace {

constexpr int kSize = 16;

// `lamp2_seen`: whether camera rays see lamp 2.
StratumScene* two_group_scene(bool lamp2_seen) {
    StratumScene* scene = nullptr;
    stratum_scene_create(&scene);
    const StratumMaterialDesc grey = diffuse_grey(0.7f);
    StratumMaterialDesc glow{STRATUM_MATERIAL_EMISSION, {0, 0, 0}, 0, 0, 0, 1.5f, {3.0f, 2.0f, 1.0f},
                             STRATUM_MICROFACET_GGX};
    uint32_t grey_mat = 0, glow_mat = 0;
    stratum_scene_add_material(scene, &grey, &grey_mat);
    stratum_scene_add_material(scene, &glow, &glow_mat);
    const auto add = [&](const float(&corners)[12], uint32_t material, uint32_t group) {
        StratumInstanceDesc d{};
        d.visibility = STRATUM_VISIBLE_ALL;
        d.lightgroup = group;
        EXPECT_TRUE(add_quad_instance(scene, corners, material, d)) << stratum_last_error();
    };
    const float floor[12] = {-3, -3, 0, 3, -3, 0, 3, 3, 0, -3, 3, 0};
    const float wall[12] = {2, -3, 0, 2, 3, 0, 2, 3, 2, 2, -3, 2};
    const float glow_quad[12] = {-1.5f, -1.5f, 0.01f, -0.5f, -1.5f, 0.01f,
                                 -0.5f, -0.5f, 0.01f, -1.5f, -0.5f, 0.01f};
    add(floor, grey_mat, 0);
    add(wall, grey_mat, 0);
    add(glow_quad, glow_mat, 1);
    for (uint32_t group : {1u, 2u}) {
        StratumLightDesc lamp{};
        lamp.type = STRATUM_LIGHT_AREA_RECTANGLE;
        lamp.color[0] = 1.0f;
        lamp.color[1] = group == 1 ? 0.8f : 0.4f;
        lamp.color[2] = group == 1 ? 0.5f : 1.0f;
        lamp.strength = 200.0f;
        lamp.size_x = lamp.size_y = 1.0f;
        std::copy(kIdentity, kIdentity + 16, lamp.transform);
        lamp.transform[3] = group == 1 ? -1.0f : 0.0f;
        lamp.transform[11] = group == 1 ? 1.5f : 1.0f;
        if (group == 2) lamp.transform[10] = lamp.transform[5] = -1.0f;  // faces up, to the camera
        if (group == 2 && !lamp2_seen) lamp.visibility = STRATUM_VISIBLE_ALL & ~STRATUM_VISIBLE_CAMERA;
        lamp.lightgroup = group;
        EXPECT_EQ(stratum_scene_add_light(scene, &lamp), STRATUM_OK) << stratum_last_error();
    }
    const float world[3] = {0.2f, 0.3f, 0.4f};
    stratum_scene_set_background(scene, world);
    EXPECT_EQ(stratum_scene_set_world_lightgroup(scene, 2), STRATUM_OK);
    const StratumCameraDesc camera = camera_at(0.0f, 0.0f, 4.0f);
    stratum_scene_set_camera(scene, &camera);
    return scene;
}

struct Groups {
    std::vector<float> rgba, g1, g2;
};

Groups render_groups(bool lamp2_seen) {
    StratumScene* scene = two_group_scene(lamp2_seen);
    StratumRenderer* r = nullptr;
    Groups out;
    EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    EXPECT_EQ(apply_settings(r, {{"width", kSize},
                                 {"height", kSize},
                                 {"samples", 8},
                                 {"filter_type", "box"},
                                 {"filter_width", 0.01},
                                 {"max_bounces", 3},
                                 {"clamp_direct", 2.0},
                                 {"clamp_indirect", 0.5},
                                 {"lightgroups", 2}}),
              "");
    EXPECT_TRUE(render_to_end(r)) << stratum_last_error();
    out.rgba.resize(kSize * kSize * 4);
    out.g1.resize(kSize * kSize * 3);
    out.g2.resize(kSize * kSize * 3);
    EXPECT_EQ(stratum_renderer_read_pixels(r, out.rgba.data(), out.rgba.size()), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_read_lightgroup(r, 1, out.g1.data(), out.g1.size()), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_read_lightgroup(r, 2, out.g2.data(), out.g2.size()), STRATUM_OK);
    std::vector<float> none(kSize * kSize * 3);
    EXPECT_NE(stratum_renderer_read_lightgroup(r, 3, none.data(), none.size()), STRATUM_OK);
    stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
    return out;
}

}  // namespace

TEST(LightGroups, GroupsOfEveryEmitterSumToCombinedPerPixel) {
    const Groups out = render_groups(true);
    double lit1 = 0.0, lit2 = 0.0;
    for (int p = 0; p < kSize * kSize; ++p) {
        for (int c = 0; c < 3; ++c) {
            const double combined = out.rgba[4 * p + c], sum = double{out.g1[3 * p + c]} + out.g2[3 * p + c];
            EXPECT_NEAR(sum, combined, 1e-5 * combined + 1e-7) << "pixel " << p << " channel " << c;
        }
        lit1 += out.g1[3 * p];
        lit2 += out.g2[3 * p];
    }
    EXPECT_GT(lit1, 1.0);
    EXPECT_GT(lit2, 1.0);
}

// The same samples with lamp 2 hidden from the camera (seeing a lamp draws no random number):
// group 1 keeps its bits, and group 2 loses exactly the lamp's clamped radiance (its channel sum
// 3 × clamp_direct = 6: 200 W / (π · 1 m²) ≈ 64 per channel is above it) where the camera saw it.
TEST(LightGroups, ALampSeenDirectlyIsInItsOwnGroupAlone) {
    const Groups seen = render_groups(true), hidden = render_groups(false);
    EXPECT_TRUE(seen.g1 == hidden.g1);
    int lamp_pixels = 0;
    for (int p = 0; p < kSize * kSize; ++p) {
        double added = 0.0;
        for (int c = 0; c < 3; ++c) added += double{seen.g2[3 * p + c]} - hidden.g2[3 * p + c];
        if (std::abs(added) < 1e-6) continue;
        ++lamp_pixels;
        EXPECT_NEAR(added, 6.0, 1e-4) << "pixel " << p;
    }
    EXPECT_GT(lamp_pixels, 0);
}

TEST(LightGroups, ALightGroupAboveTheLimitIsRefusedByName) {
    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    EXPECT_EQ(stratum_scene_set_world_lightgroup(scene, STRATUM_MAX_LIGHT_GROUPS + 1),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("world lightgroup"), std::string::npos);
    StratumLightDesc lamp{};
    lamp.type = STRATUM_LIGHT_POINT;
    lamp.strength = 1.0f;
    std::copy(kIdentity, kIdentity + 16, lamp.transform);
    lamp.lightgroup = 65;
    EXPECT_EQ(stratum_scene_add_light(scene, &lamp), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("light lightgroup = 65"), std::string::npos);
    stratum_scene_destroy(scene);
}

TEST(LightGroups, AnIntegratorThatWritesNoneSaysSoAndLeavesThemBlack) {
    StratumScene* scene = two_group_scene(true);
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    ASSERT_EQ(apply_settings(
                  r, {{"width", 4}, {"height", 4}, {"samples", 1}, {"integrator", "ao"}, {"lightgroups", 1}}),
              "");
    ASSERT_TRUE(render_to_end(r)) << stratum_last_error();
    const char* notices = nullptr;
    ASSERT_EQ(stratum_renderer_notices(r, &notices), STRATUM_OK);
    EXPECT_NE(std::string(notices ? notices : "").find("writes no light groups"), std::string::npos)
        << notices;
    std::vector<float> group(4 * 4 * 3, -1.0f);
    ASSERT_EQ(stratum_renderer_read_lightgroup(r, 1, group.data(), group.size()), STRATUM_OK);
    for (float v : group) EXPECT_EQ(v, 0.0f);
    stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
}
