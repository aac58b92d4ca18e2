// Progress within a pass (render/renderer.h): tiles of at most 16² pixels publish and count their
// samples as they end, so the image and the sample counter move many times during the last
// pass of a render, which is half of its work.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "render_helpers.h"

using namespace stratum_test;

namespace {

constexpr int kSize = 64;    // 16 tiles of 16 x 16 pixels
constexpr int kSamples = 8;  // passes [0,1) [1,2) [2,4) [4,8)
constexpr int kLastPassBegin = 4;

StratumRenderer* start_sphere_interior_render() {
    const StratumMaterialDesc wall{STRATUM_MATERIAL_DIFFUSE, {0.7f, 0.7f, 0.7f},    1, 0, 0, 1.5f,
                                   {0.3f, 0.3f, 0.3f},       STRATUM_MICROFACET_GGX};
    StratumScene* scene = make_sphere_interior(wall, 8, 0, 0, 0.2f);
    if (scene == nullptr) return nullptr;
    StratumRenderer* r = nullptr;
    const bool created = stratum_renderer_create(scene, &r) == STRATUM_OK;
    stratum_scene_destroy(scene);
    if (!created) return nullptr;
    // One thread: the tiles of a pass end one after another, each adding its 256 pixels'
    // samples to the progress.
    for (const auto& [name, value] : {std::pair{"width", kSize},
                                      {"height", kSize},
                                      {"samples", kSamples},
                                      {"max_bounces", 4},
                                      {"threads", 1}}) {
        if (stratum_renderer_set_int(r, name, value) != STRATUM_OK) {
            stratum_renderer_destroy(r);
            return nullptr;
        }
    }
    if (stratum_renderer_start(r) != STRATUM_OK) {
        stratum_renderer_destroy(r);
        return nullptr;
    }
    return r;
}

}  // namespace

TEST(RenderProgress, MovesTileByTileWithinTheLastPass) {
    StratumRenderer* r = start_sphere_interior_render();
    ASSERT_NE(r, nullptr) << stratum_last_error();
    // Polled without pause while the render thread works: every value the progress takes in the
    // last pass that the poll sees. A tile of the last pass (256 pixels x 4 samples of paths up to
    // 5 rays) takes milliseconds, a poll well under one, so most tiles are seen; the checks below
    // need 4 of the 16.
    std::vector<StratumProgress> seen;
    StratumProgress p{};
    for (;;) {
        ASSERT_EQ(stratum_renderer_progress(r, &p), STRATUM_OK) << stratum_last_error();
        if (p.done) break;
        if (p.samples_done == kLastPassBegin && p.samples_in_progress == kSamples &&
            (seen.empty() || p.samples_average != seen.back().samples_average))
            seen.push_back(p);
    }
    for (size_t i = 0; i < seen.size(); ++i) {
        const StratumProgress& s = seen[i];
        EXPECT_GE(s.samples_average, kLastPassBegin);
        EXPECT_LE(s.samples_average, kSamples);
        // Tiles of 16 x 16 pixels: the average moves in steps of one tile's 256 pixels x 4
        // samples over 64 x 64 pixels, a quarter of a sample.
        const double tiles = (s.samples_average - kLastPassBegin) / 0.25;
        EXPECT_EQ(tiles, std::round(tiles)) << s.samples_average;
        EXPECT_NEAR(s.fraction_done, s.samples_average / kSamples, 1e-12);
        if (i > 0) {
            EXPECT_GT(s.samples_average, seen[i - 1].samples_average);
            // New pixels were published with each new count.
            EXPECT_GT(s.update_serial, seen[i - 1].update_serial);
        }
    }
    // Several values strictly between the passes' ends: the counter moved within the pass.
    size_t within = 0;
    for (const StratumProgress& s : seen)
        if (s.samples_average > kLastPassBegin && s.samples_average < kSamples) ++within;
    EXPECT_GE(within, 4u) << seen.size() << " values seen in the last pass";
    // At the end every pixel has every sample, and the average says so exactly.
    EXPECT_EQ(p.samples_done, kSamples);
    EXPECT_EQ(p.samples_in_progress, kSamples);
    EXPECT_EQ(p.samples_average, static_cast<double>(kSamples));
    EXPECT_EQ(p.fraction_done, 1.0);
    stratum_renderer_destroy(r);
}
