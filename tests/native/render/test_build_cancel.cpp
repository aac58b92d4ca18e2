// Cancel reaches the BVH build (issue 12, point 8): Embree's build of a big scene is the one
// long step of a render that no sample loop checks, so the renderer hands Embree a progress
// callback that stops it. Also cancel during light tracing, whose particle passes are long.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <chrono>
#include <cstdio>
#include <vector>

#include "render_helpers.h"

using namespace stratum_test;

namespace {

// A flat, emissive n x n grid of quads (2 n² triangles) over [-1, 1]², seen by a camera 3
// above. Emissive: listing its triangles as lights is part of the build too.
StratumScene* grid_scene(uint32_t n) {
    StratumScene* scene = nullptr;
    stratum_scene_create(&scene);
    const StratumMaterialDesc grey{STRATUM_MATERIAL_DIFFUSE, {0.5f, 0.5f, 0.5f}, 1, 0, 0, 1.5f, {1, 1, 1},
                                   STRATUM_MICROFACET_GGX};
    stratum_scene_add_material(scene, &grey, nullptr);
    std::vector<float> positions;
    positions.reserve(3 * static_cast<size_t>(n + 1) * (n + 1));
    for (uint32_t j = 0; j <= n; ++j) {
        for (uint32_t i = 0; i <= n; ++i) {
            positions.insert(positions.end(),
                             {2.0f * static_cast<float>(i) / static_cast<float>(n) - 1.0f,
                              2.0f * static_cast<float>(j) / static_cast<float>(n) - 1.0f, 0.0f});
        }
    }
    std::vector<uint32_t> triangles;
    triangles.reserve(6 * static_cast<size_t>(n) * n);
    for (uint32_t j = 0; j < n; ++j) {
        for (uint32_t i = 0; i < n; ++i) {
            const uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
            triangles.insert(triangles.end(), {a, b, d, a, d, c});
        }
    }
    const std::vector<uint32_t> materials(triangles.size() / 3, 0u);
    const StratumMeshDesc mesh{positions.data(), static_cast<uint32_t>(positions.size() / 3),
                               triangles.data(), static_cast<uint32_t>(triangles.size() / 3),
                               nullptr,          nullptr,
                               materials.data()};
    uint32_t id = 0;
    EXPECT_EQ(stratum_scene_add_mesh(scene, &mesh, &id), STRATUM_OK) << stratum_last_error();
    stratum_scene_add_instance(scene, id, kIdentity);
    const StratumCameraDesc camera = camera_at(0, 0, 3);
    stratum_scene_set_camera(scene, &camera);
    return scene;
}

// Cancels `r` after `delay_ms`, returns the seconds until the render ended.
double cancel_after(StratumRenderer* r, int delay_ms) {
    int32_t done = 0;
    stratum_renderer_wait(r, delay_ms, &done);
    EXPECT_EQ(done, 0) << "the render ended before it could be cancelled";
    const auto t0 = std::chrono::steady_clock::now();
    stratum_renderer_cancel(r);
    stratum_renderer_wait(r, 10000, &done);
    EXPECT_EQ(done, 1);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

// 2M triangles on one thread: Embree builds them in about a second here, so a cancel 100 ms in
// lands in the build. The render ends cancelled, with no error and no sample, within the
// 0.5 s the issue asks (the figure is printed).
TEST(BuildCancel, CancelDuringTheBvhBuildEndsTheRender) {
    StratumScene* scene = grid_scene(1000);
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    stratum_scene_destroy(scene);
    for (const auto& [name, value] :
         {std::pair{"width", 16}, std::pair{"height", 16}, std::pair{"threads", 1}})
        ASSERT_EQ(stratum_renderer_set_int(r, name, value), STRATUM_OK);
    ASSERT_EQ(stratum_renderer_start(r), STRATUM_OK);
    const double seconds = cancel_after(r, 100);
    StratumProgress p{};
    EXPECT_EQ(stratum_renderer_progress(r, &p), STRATUM_OK) << stratum_last_error();
    EXPECT_EQ(p.cancelled, 1);
    EXPECT_EQ(p.build_seconds, 0.0) << "the build finished before the cancel";
    EXPECT_EQ(p.samples_done, 0);
    std::printf("cancel during the BVH build of 2M triangles: render ended after %.3f s\n", seconds);
    EXPECT_LT(seconds, 0.5);
    // The next start builds again, and a render to the end works.
    ASSERT_EQ(stratum_renderer_set_int(r, "threads", 0), STRATUM_OK);
    ASSERT_TRUE(render_to_end(r)) << stratum_last_error();
    EXPECT_EQ(stratum_renderer_progress(r, &p), STRATUM_OK) << stratum_last_error();
    EXPECT_EQ(p.cancelled, 0);
    EXPECT_GT(p.build_seconds, 0.0);
    stratum_renderer_destroy(r);
}

// The light tracer's particle passes (one particle per frame pixel and sample index, with up to
// 1024 bounces here) check cancel between batches of particles.
TEST(BuildCancel, CancelDuringLightTracingIsPrompt) {
    StratumScene* scene = grid_scene(4);
    StratumLightDesc lamp{};
    lamp.type = STRATUM_LIGHT_POINT;
    lamp.color[0] = lamp.color[1] = lamp.color[2] = 1.0f;
    lamp.strength = 100.0f;
    std::copy(kIdentity, kIdentity + 16, lamp.transform);
    lamp.transform[11] = 1.0f;
    stratum_scene_add_light(scene, &lamp);
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    stratum_scene_destroy(scene);
    for (const auto& [name, value] : {std::pair{"width", 256}, std::pair{"height", 256},
                                      std::pair{"samples", 1 << 16}, std::pair{"max_bounces", 1024}})
        ASSERT_EQ(stratum_renderer_set_int(r, name, value), STRATUM_OK);
    ASSERT_EQ(stratum_renderer_set_string(r, "integrator", "light"), STRATUM_OK);
    ASSERT_EQ(stratum_renderer_start(r), STRATUM_OK);
    const double seconds = cancel_after(r, 300);
    std::printf("cancel during light tracing: render ended after %.3f s\n", seconds);
    EXPECT_LT(seconds, 0.5);
    stratum_renderer_destroy(r);
}
