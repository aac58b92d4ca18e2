// Cycles' shadow catcher (integrators/shadow_catcher.h, film/shadow_catcher_film.h) on an
// analytic setup: a catcher floor (z = 0) seen straight down by an orthographic camera over
// [−1, 1]², a sun straight down, and an occluder the camera does not see (its camera bit off)
// over the half x < 0 of the floor, direct light only. The floor's light is ρE/π in the open and
// 0 in the umbra; its catcher-only copy sees ρE/π everywhere. The main path and its copy make the
// same computation in the open, so the ratio there is exactly 1; in the umbra it is exactly 0.
// Pixel centres lie at x = −1 + (i + ½)/4, so columns 0–3 are in the umbra and 4–7 in the open.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "film/shadow_catcher_film.h"
#include "render_helpers.h"

using namespace stratum_test;

namespace {

constexpr int kSize = 8;
constexpr float kAlbedo = 0.8f;

struct SceneOptions {
    bool catcher_holdout = false;  // the floor is also a holdout: it must not split
    float background = 0.0f;       // grey world radiance
};

StratumScene* catcher_scene(const SceneOptions& o = {}) {
    StratumScene* scene = nullptr;
    stratum_scene_create(&scene);
    const StratumMaterialDesc floor = diffuse_grey(kAlbedo);
    uint32_t floor_mat = 0, occluder_mat = 0;
    EXPECT_EQ(stratum_scene_add_material(scene, &floor, &floor_mat), STRATUM_OK);
    const StratumMaterialDesc occluder = diffuse_grey(0.5f);
    EXPECT_EQ(stratum_scene_add_material(scene, &occluder, &occluder_mat), STRATUM_OK);
    const auto add = [&](const float(&corners)[12], uint32_t material, uint32_t visibility, bool holdout) {
        StratumInstanceDesc d{};
        d.visibility = visibility;
        d.holdout = holdout ? 1 : 0;
        EXPECT_TRUE(add_quad_instance(scene, corners, material, d)) << stratum_last_error();
    };
    const float floor_corners[12] = {-2, -2, 0, 2, -2, 0, 2, 2, 0, -2, 2, 0};
    add(floor_corners, floor_mat, STRATUM_VISIBLE_ALL | STRATUM_VISIBLE_SHADOW_CATCHER, o.catcher_holdout);
    const float occluder_corners[12] = {-3, -3, 1, 0, -3, 1, 0, 3, 1, -3, 3, 1};
    add(occluder_corners, occluder_mat, STRATUM_VISIBLE_ALL & ~STRATUM_VISIBLE_CAMERA, false);
    StratumLightDesc sun{};
    sun.type = STRATUM_LIGHT_SUN;
    sun.color[0] = sun.color[1] = sun.color[2] = 1.0f;
    sun.strength = 3.0f;
    std::copy(kIdentity, kIdentity + 16, sun.transform);  // shines down −Z
    EXPECT_EQ(stratum_scene_add_light(scene, &sun), STRATUM_OK);
    const float world[3] = {o.background, o.background, o.background};
    stratum_scene_set_background(scene, world);
    StratumCameraDesc camera = camera_at(0.0f, 0.0f, 3.0f);
    camera.type = STRATUM_CAMERA_ORTHOGRAPHIC;
    camera.ortho_scale = 2.0f;
    EXPECT_EQ(stratum_scene_set_camera(scene, &camera), STRATUM_OK);
    return scene;
}

struct Output {
    std::vector<float> rgba, catcher;  // Combined; the Shadow Catcher pass (when asked for)
    std::string notices;
};

Output render_catcher(StratumScene* scene, const char* passes, int64_t film_transparent,
                      const char* integrator = "path") {
    Output out;
    StratumRenderer* r = nullptr;
    EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    EXPECT_EQ(apply_settings(r, {{"width", kSize},
                                 {"height", kSize},
                                 {"samples", 2},
                                 {"max_bounces", 0},
                                 {"filter_type", "box"},
                                 {"filter_width", 0.01},
                                 {"film_transparent", film_transparent},
                                 {"integrator", integrator},
                                 {"passes", passes}}),
              "");
    EXPECT_TRUE(render_to_end(r)) << stratum_last_error();
    out.rgba.resize(kSize * kSize * 4);
    EXPECT_EQ(stratum_renderer_read_pixels(r, out.rgba.data(), out.rgba.size()), STRATUM_OK);
    if (std::strlen(passes) > 0) {
        out.catcher.resize(kSize * kSize * 3);
        EXPECT_EQ(stratum_renderer_read_pass(r, "Shadow Catcher", out.catcher.data(), out.catcher.size()),
                  STRATUM_OK)
            << stratum_last_error();
    }
    const char* notices = nullptr;
    if (stratum_renderer_notices(r, &notices) == STRATUM_OK && notices) out.notices = notices;
    stratum_renderer_destroy(r);
    return out;
}

bool in_umbra(int pixel) { return pixel % kSize < kSize / 2; }

}  // namespace

TEST(ShadowCatcher, PassIsZeroInTheUmbraAndOneInTheOpenAndCombinedIsThePlainMatte) {
    StratumScene* scene = catcher_scene();
    const Output out = render_catcher(scene, "Shadow Catcher", 0);
    for (int p = 0; p < kSize * kSize; ++p) {
        const float expected = in_umbra(p) ? 0.0f : 1.0f;
        for (int c = 0; c < 3; ++c) EXPECT_EQ(out.catcher[3 * p + c], expected) << "pixel " << p;
        // With the pass asked for, Combined is the matte: the catcher is transparent, shadowless.
        for (int c = 0; c < 4; ++c) EXPECT_EQ(out.rgba[4 * p + c], 0.0f) << "pixel " << p << " channel " << c;
    }
    stratum_scene_destroy(scene);
}

TEST(ShadowCatcher, WithoutThePassCombinedHoldsTheShadowAsAlphaOnATransparentFilm) {
    StratumScene* scene = catcher_scene();
    const Output out = render_catcher(scene, "", 1);
    for (int p = 0; p < kSize * kSize; ++p) {
        for (int c = 0; c < 3; ++c) EXPECT_EQ(out.rgba[4 * p + c], 0.0f) << "pixel " << p;
        EXPECT_EQ(out.rgba[4 * p + 3], in_umbra(p) ? 1.0f : 0.0f) << "pixel " << p;
    }
    stratum_scene_destroy(scene);
}

TEST(ShadowCatcher, HoldoutCatcherDoesNotSplit) {
    StratumScene* scene = catcher_scene({.catcher_holdout = true});
    const Output out = render_catcher(scene, "Shadow Catcher", 0);
    for (int p = 0; p < kSize * kSize; ++p) {
        for (int c = 0; c < 3; ++c) EXPECT_EQ(out.catcher[3 * p + c], 1.0f) << "pixel " << p;
        for (int c = 0; c < 4; ++c) EXPECT_EQ(out.rgba[4 * p + c], 0.0f) << "pixel " << p;
    }
    stratum_scene_destroy(scene);
}

TEST(ShadowCatcher, AnIntegratorThatDoesNotSplitRendersTheCatcherPlainAndSaysSo) {
    StratumScene* scene = catcher_scene();
    const Output out = render_catcher(scene, "Shadow Catcher", 0, "radiosity");
    EXPECT_NE(out.notices.find("shadow catchers as ordinary objects"), std::string::npos) << out.notices;
    for (float v : out.catcher) EXPECT_EQ(v, 1.0f);
    // The lit half of the floor shows its light in Combined.
    EXPECT_GT(out.rgba[4 * (kSize - 1)], 0.1f);
    stratum_scene_destroy(scene);
}

// Cycles' film_calculate_shadow_catcher_matte_with_shadow over the Background pass (opaque film),
// with the means of film/shadow_catcher_film.h's sums written out by hand.
TEST(ShadowCatcher, MatteWithShadowOverTheBackgroundFollowsCyclesReadOut) {
    using namespace stratum;
    // Half the samples split on the catcher (matte transparency ½), half met an object of
    // radiance (0.4, 0.2, 0.1) (the matte). Combined − matte = (0.1, 0.1, 0.1); catcher-only 0.2.
    const double means[kShadowCatcherSums] = {0.2, 0.2, 0.2, 0.4, 0.2, 0.1, 0.5, 0.5, 0.6, 0.6, 0.6};
    const Rgb combined(0.5f, 0.3f, 0.2f);
    const Rgb pass = shadow_catcher_pass(combined, 1.0f, means);
    EXPECT_NEAR(pass.r, 0.5f, 1e-6f);
    EXPECT_NEAR(pass.b, 0.5f, 1e-6f);
    // α = 1 − ½; matte alpha = ½ (1 − ½) + ½ = ¾; RGB = matte + background × ¼.
    const auto over = matte_combined(CatcherCombined::MatteWithShadowOverBackground, pass, means);
    EXPECT_NEAR(over[0], 0.4f + 0.6f * 0.25f, 1e-6f);
    EXPECT_NEAR(over[2], 0.1f + 0.6f * 0.25f, 1e-6f);
    EXPECT_EQ(over[3], 1.0f);
    const auto transparent = matte_combined(CatcherCombined::MatteWithShadow, pass, means);
    EXPECT_NEAR(transparent[3], 0.75f, 1e-6f);
    const auto matte = matte_combined(CatcherCombined::Matte, pass, means);
    EXPECT_NEAR(matte[3], 0.5f, 1e-6f);
    // No sample split: the ratio is 1 whatever the sums (Cycles: "no shadow catcher object in
    // this pixel"); a zero catcher-only channel divides to 1.
    double unsplit[kShadowCatcherSums] = {};
    EXPECT_EQ(shadow_catcher_pass(combined, 1.0f, unsplit).g, 1.0f);
    unsplit[7] = 1.0;
    EXPECT_EQ(shadow_catcher_pass(combined, 1.0f, unsplit).g, 1.0f);
}

// The catcher's sums follow the film's exchange: sample ranges rendered apart and added give the
// whole render's Combined, Shadow Catcher and light-group passes bit for bit, and the thread count
// changes nothing (issue 34, acceptance 2: determinism and the Dask merge with the switches on).
// Every other Light Paths switch is on too: per-kind limits, both clamps, Filter Glossy, no
// caustics. A grey world makes every pixel noisy (environment light samples).
TEST(ShadowCatcher, SplitSampleRangesAndThreadCountsGiveTheSameBits) {
    StratumScene* scene = catcher_scene({.background = 0.5f});
    ASSERT_EQ(stratum_scene_set_world_lightgroup(scene, 1), STRATUM_OK);
    const auto run = [&](int64_t offset, int64_t count, int64_t threads, std::vector<uint8_t>* sums) {
        StratumRenderer* r = nullptr;
        EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
        EXPECT_EQ(apply_settings(r, {{"width", kSize},
                                     {"height", kSize},
                                     {"samples", 4},
                                     {"seed", 5},
                                     {"threads", threads},
                                     {"sample_offset", offset},
                                     {"sample_count", count},
                                     {"diffuse_bounces", 2},
                                     {"glossy_bounces", 1},
                                     {"transmission_bounces", 1},
                                     {"clamp_direct", 2.0},
                                     {"clamp_indirect", 0.5},
                                     {"filter_glossy", 1.0},
                                     {"caustics_reflective", 0},
                                     {"caustics_refractive", 0},
                                     {"lightgroups", 1},
                                     {"passes", "Shadow Catcher"}}),
                  "");
        EXPECT_TRUE(render_to_end(r)) << stratum_last_error();
        size_t bytes = 0;
        EXPECT_EQ(stratum_renderer_sums_size(r, &bytes), STRATUM_OK);
        sums->resize(bytes);
        EXPECT_EQ(stratum_renderer_read_sums(r, sums->data(), bytes), STRATUM_OK);
        return r;
    };
    const auto read = [](StratumRenderer* r) {
        std::vector<float> rgba(kSize * kSize * 4), catcher(kSize * kSize * 3);
        EXPECT_EQ(stratum_renderer_read_pixels(r, rgba.data(), rgba.size()), STRATUM_OK);
        EXPECT_EQ(stratum_renderer_read_pass(r, "Shadow Catcher", catcher.data(), catcher.size()),
                  STRATUM_OK);
        std::vector<float> group(kSize * kSize * 3);
        EXPECT_EQ(stratum_renderer_read_lightgroup(r, 1, group.data(), group.size()), STRATUM_OK)
            << stratum_last_error();
        rgba.insert(rgba.end(), catcher.begin(), catcher.end());
        rgba.insert(rgba.end(), group.begin(), group.end());
        return rgba;
    };
    std::vector<uint8_t> whole_sums, first, second, threaded_sums;
    StratumRenderer* whole = run(0, 0, 1, &whole_sums);
    const std::vector<float> expected = read(whole);
    stratum_renderer_destroy(whole);
    StratumRenderer* threaded = run(0, 0, 2, &threaded_sums);
    EXPECT_TRUE(read(threaded) == expected);
    stratum_renderer_destroy(threaded);
    stratum_renderer_destroy(run(0, 1, 1, &first));
    stratum_renderer_destroy(run(1, 3, 1, &second));
    StratumRenderer* into = nullptr;
    EXPECT_EQ(stratum_renderer_create(scene, &into), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_add_sums(into, second.data(), second.size()), STRATUM_OK)
        << stratum_last_error();
    EXPECT_EQ(stratum_renderer_add_sums(into, first.data(), first.size()), STRATUM_OK)
        << stratum_last_error();
    const std::vector<float> merged = read(into);
    EXPECT_TRUE(merged == expected);
    // The umbra is darker than the open floor in the ratio, and not exactly 0: the sky lights it.
    EXPECT_LT(expected[4 * kSize * kSize + 0], expected[4 * kSize * kSize + 3 * (kSize - 1)]);
    stratum_renderer_destroy(into);
    stratum_scene_destroy(scene);
}

// Light groups on split paths (integrators/light_group_writer.h): NEE after a split never reaches
// them; emission met after it (here the grey world, seen by the catcher's scattered rays of the
// main path and of its copy) does only under Cycles 3.x's rule (lightgroup_split_emission 1).
TEST(ShadowCatcher, LightGroupsAfterTheSplitFollowTheCyclesVersion) {
    StratumScene* scene = catcher_scene({.background = 0.5f});
    ASSERT_EQ(stratum_scene_set_world_lightgroup(scene, 1), STRATUM_OK);
    const auto world_group = [&](int64_t split_emission) {
        StratumRenderer* r = nullptr;
        EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
        EXPECT_EQ(apply_settings(r, {{"width", kSize},
                                     {"height", kSize},
                                     {"samples", 2},
                                     {"max_bounces", 1},
                                     {"lightgroups", 1},
                                     {"lightgroup_split_emission", split_emission}}),
                  "");
        EXPECT_TRUE(render_to_end(r)) << stratum_last_error();
        std::vector<float> group(kSize * kSize * 3);
        EXPECT_EQ(stratum_renderer_read_lightgroup(r, 1, group.data(), group.size()), STRATUM_OK)
            << stratum_last_error();
        stratum_renderer_destroy(r);
        return group;
    };
    // Every camera ray meets the catcher floor first: every path splits before any light.
    for (float v : world_group(0)) EXPECT_EQ(v, 0.0f);
    const std::vector<float> cycles3 = world_group(1);
    for (int p = 0; p < kSize * kSize; ++p) EXPECT_GT(cycles3[3 * p], 0.0f) << "pixel " << p;
    stratum_scene_destroy(scene);
}
