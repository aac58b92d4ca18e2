// Progressive rendering through the C ABI: cancel stops promptly and keeps the partial image;
// a captured scene file renders the same image as the scene it was saved from.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "integrators/integrator.h"
#include "render/render_settings.h"
#include "render/setting_registry.h"
#include "render_helpers.h"

using namespace stratum_test;

namespace {

StratumScene* lit_sphere_interior() {
    const StratumMaterialDesc wall{STRATUM_MATERIAL_DIFFUSE, {0.7f, 0.7f, 0.7f},    1, 0, 0, 1.5f,
                                   {0.3f, 0.3f, 0.3f},       STRATUM_MICROFACET_GGX};
    StratumScene* scene = make_sphere_interior(wall, 8, 0, 0, 0.2f);
    EXPECT_NE(scene, nullptr) << stratum_last_error();
    return scene;
}

}  // namespace

TEST(Renderer, CancelStopsWithinHalfASecondAndKeepsThePartialImage) {
    StratumScene* scene = lit_sphere_interior();
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    stratum_scene_destroy(scene);
    ASSERT_EQ(stratum_renderer_set_int(r, "width", 256), STRATUM_OK);
    ASSERT_EQ(stratum_renderer_set_int(r, "height", 256), STRATUM_OK);
    ASSERT_EQ(stratum_renderer_set_int(r, "samples", 1 << 20), STRATUM_OK);
    ASSERT_EQ(stratum_renderer_set_int(r, "max_bounces", 64), STRATUM_OK);
    ASSERT_EQ(stratum_renderer_start(r), STRATUM_OK);
    // Settings cannot change under a running render.
    EXPECT_EQ(stratum_renderer_set_int(r, "samples", 4), STRATUM_ERROR_INVALID_STATE);
    // Cancel once two samples are in, however long they take (sanitizers on a loaded machine,
    // the light tree splitting the emissive walls into 8 light samples per vertex): the wait is
    // bounded at 60 s so that a render making no progress fails instead of hanging.
    StratumProgress p{};
    for (int i = 0; i < 1200 && p.samples_done < 2; ++i) {
        int32_t done = 0;
        stratum_renderer_wait(r, 50, &done);
        ASSERT_EQ(stratum_renderer_progress(r, &p), STRATUM_OK);
    }
    ASSERT_GE(p.samples_done, 2);
    const auto t0 = std::chrono::steady_clock::now();
    ASSERT_EQ(stratum_renderer_cancel(r), STRATUM_OK);
    int32_t done = 0;
    ASSERT_EQ(stratum_renderer_wait(r, 5000, &done), STRATUM_OK);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_EQ(done, 1);
    EXPECT_LT(seconds, 0.5);
    ASSERT_EQ(stratum_renderer_progress(r, &p), STRATUM_OK);
    EXPECT_EQ(p.cancelled, 1);
    EXPECT_LT(p.samples_done, 1 << 20);
    std::vector<float> rgba(256 * 256 * 4);
    ASSERT_EQ(stratum_renderer_read_pixels(r, rgba.data(), rgba.size()), STRATUM_OK);
    double sum = 0;
    for (float v : rgba) {
        ASSERT_TRUE(std::isfinite(v));
        sum += v;
    }
    EXPECT_GT(sum, 0.0);
    stratum_renderer_destroy(r);
}

TEST(Renderer, CapturedSceneFileRendersTheSameImage) {
    StratumScene* scene = lit_sphere_interior();
    const std::string path = ::testing::TempDir() + "stratum_captured_scene.json";
    ASSERT_EQ(stratum_scene_save(scene, path.c_str()), STRATUM_OK) << stratum_last_error();
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(path.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    const auto a = render(scene, {{"width", 24}, {"height", 16}, {"samples", 4}});
    const auto b = render(loaded, {{"width", 24}, {"height", 16}, {"samples", 4}});
    EXPECT_EQ(a.rgba, b.rgba);
    stratum_scene_destroy(scene);
    stratum_scene_destroy(loaded);

    // A corrupted file is an I/O error with a message, and no scene.
    std::FILE* f = std::fopen(path.c_str(), "w");
    std::fputs("{\"format\": \"stratum-scene\", \"version\": 1, \"materials\": [{\"model\": 9}]}", f);
    std::fclose(f);
    StratumScene* bad = nullptr;
    EXPECT_NE(stratum_scene_load(path.c_str(), &bad), STRATUM_OK);
    EXPECT_EQ(bad, nullptr);
    EXPECT_NE(std::string(stratum_last_error()).find(path), std::string::npos) << stratum_last_error();
    std::remove(path.c_str());
}

// The benchmark ceiling traces at least the camera rays, and bounces while paths hit.
TEST(Renderer, RayThroughputCountsTheRayMix) {
    StratumScene* scene = lit_sphere_interior();
    double rays = 0, seconds = 0;
    // Inside a closed sphere every path hits at every vertex: each of the 4 vertices traces a
    // continuation ray and a shadow ray, so exactly 2 * (max_bounces + 1) rays per camera ray.
    ASSERT_EQ(stratum_scene_measure_ray_throughput(scene, 8, 4, 2, 3, 1, &rays, &seconds), STRATUM_OK);
    EXPECT_EQ(rays, 8.0 * 4.0 * 2.0 * 2.0 * 4.0);
    EXPECT_GT(seconds, 0.0);
    EXPECT_EQ(stratum_scene_measure_ray_throughput(scene, 0, 4, 2, 3, 1, &rays, &seconds),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("resolution 0x4"), std::string::npos)
        << stratum_last_error();
    stratum_scene_destroy(scene);
}

// A border render traces only the region, with the full frame's camera and sampler
// coordinates: its pixels are bit-identical to the same pixels of the full render, and
// read_pixels returns the region (crop_width x crop_height, rows bottom to top).
TEST(Renderer, BorderRenderEqualsTheCropOfTheFullRender) {
    StratumScene* scene = lit_sphere_interior();
    constexpr int64_t kW = 40, kH = 30, kX = 7, kY = 11, kCw = 19, kCh = 13;
    const auto full = render(scene, {{"width", kW}, {"height", kH}, {"samples", 8}, {"seed", 3}});
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    for (const auto& [name, value] : {std::pair<const char*, int64_t>{"width", kW},
                                      {"height", kH},
                                      {"samples", 8},
                                      {"seed", 3},
                                      {"crop_x", kX},
                                      {"crop_y", kY},
                                      {"crop_width", kCw},
                                      {"crop_height", kCh}}) {
        ASSERT_EQ(stratum_renderer_set_int(r, name, value), STRATUM_OK) << stratum_last_error();
    }
    ASSERT_TRUE(render_to_end(r)) << stratum_last_error();
    std::vector<float> region(static_cast<size_t>(kCw * kCh * 4));
    // The full frame's size is refused: the image is the region.
    std::vector<float> too_big(static_cast<size_t>(kW * kH * 4));
    EXPECT_EQ(stratum_renderer_read_pixels(r, too_big.data(), too_big.size()),
              STRATUM_ERROR_INVALID_ARGUMENT);
    ASSERT_EQ(stratum_renderer_read_pixels(r, region.data(), region.size()), STRATUM_OK)
        << stratum_last_error();
    size_t equal = 0;
    for (int64_t y = 0; y < kCh; ++y) {
        for (int64_t x = 0; x < kCw; ++x) {
            for (int c = 0; c < 4; ++c) {
                const float a = region[static_cast<size_t>((y * kCw + x) * 4 + c)];
                const float b = full.rgba[static_cast<size_t>(((y + kY) * kW + (x + kX)) * 4 + c)];
                equal += a == b;
            }
        }
    }
    EXPECT_EQ(equal, region.size());
    stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
}

// A region outside the frame, or a partial crop description, is refused at start by name.
TEST(Renderer, BorderRegionIsValidatedByName) {
    StratumScene* scene = lit_sphere_interior();
    const auto start_error = [&](std::initializer_list<std::pair<const char*, int64_t>> ints) {
        StratumRenderer* r = nullptr;
        EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
        for (const auto& [name, value] : ints)
            EXPECT_EQ(stratum_renderer_set_int(r, name, value), STRATUM_OK);
        const StratumStatus status = stratum_renderer_start(r);
        std::string error = status == STRATUM_OK ? "" : stratum_last_error();
        int32_t done = 0;
        while (status == STRATUM_OK && !done) stratum_renderer_wait(r, 1000, &done);
        stratum_renderer_destroy(r);
        return error;
    };
    EXPECT_NE(
        start_error({{"width", 16}, {"height", 8}, {"crop_x", 10}, {"crop_width", 7}, {"crop_height", 2}})
            .find("crop_x = 10 + crop_width = 7 exceeds width = 16"),
        std::string::npos);
    EXPECT_NE(
        start_error({{"width", 16}, {"height", 8}, {"crop_y", 4}, {"crop_width", 2}, {"crop_height", 5}})
            .find("crop_y = 4 + crop_height = 5 exceeds height = 8"),
        std::string::npos);
    EXPECT_NE(start_error({{"width", 16}, {"height", 8}, {"crop_width", 2}}).find("crop_height = 0"),
              std::string::npos);
    EXPECT_NE(
        start_error({{"width", 16}, {"height", 8}, {"crop_x", 3}}).find("crop_width = 0 (the whole frame)"),
        std::string::npos);
    EXPECT_EQ(start_error({{"width", 16},
                           {"height", 8},
                           {"samples", 1},
                           {"crop_x", 9},
                           {"crop_y", 7},
                           {"crop_width", 7},
                           {"crop_height", 1}}),
              "");
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_int(r, "film_transparent", 2), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("'film_transparent' = 2"), std::string::npos);
    EXPECT_EQ(stratum_renderer_set_int(r, "film_transparent", 1), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_int(r, "crop_width", -1), STRATUM_ERROR_INVALID_ARGUMENT);
    stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
}

// Film > Transparent reaches the integrator, which turns escaped rays into alpha 0.
TEST(Renderer, FilmTransparentReachesTheIntegratorSettings) {
    stratum::RenderSettings s;
    EXPECT_FALSE(s.estimator.film_transparent);
    EXPECT_EQ(stratum::set_int_setting(s, "film_transparent", 1), "");
    EXPECT_TRUE(s.estimator.film_transparent);
}
