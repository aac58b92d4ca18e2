// The film (film/film.h): published means, passes, splats, and passes through the C ABI.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "film/film.h"
#include "render_helpers.h"

using namespace stratum;
using namespace stratum_test;

namespace {

const Pass kNormalOnly[] = {Pass::Normal};

// A 2 x 1 region at (1, 2) of a 4 x 4 frame, box filter of width 1 (one pixel per splat at a centre).
Film small_film(bool light_paths) {
    return Film(PixelRegion{1, 2, 2, 1}, 4, 4, PixelFilter(FilterType::Box, 1.0f), kNormalOnly, light_paths);
}

// A value well inside the fixed-point range.
FilmSum to_fixed_exact(double v) {
    bool clamped = false;
    const FilmSum s = to_fixed(v, kFixedSampleLimit, &clamped);
    EXPECT_FALSE(clamped);
    return s;
}

std::vector<float> read(const Film& film, Pass pass) {
    std::vector<float> out(film.region().pixel_count() * pass_info(pass).channels, -1.0f);
    EXPECT_TRUE(film.read(pass, out.data()));
    return out;
}

}  // namespace

TEST(Film, PublishesTheMeanOfEachPixelsSamplesForEveryPass) {
    Film film = small_film(false);
    ASSERT_EQ(film.sums_stride(), 7u);  // RGB, alpha, the normal's 3 channels
    const FilmSum sums[] = {to_fixed_exact(2), to_fixed_exact(4), to_fixed_exact(6),
                            to_fixed_exact(2), to_fixed_exact(1), 0,
                            to_fixed_exact(-1)};
    film.store_sums(0, sums, 2);
    film.publish(1, 3, 2, 3);
    EXPECT_EQ(read(film, Pass::Combined), (std::vector<float>{1, 2, 3, 1, 0, 0, 0, 0}));
    // The second pixel has no samples: it stays 0.
    EXPECT_EQ(read(film, Pass::Normal), (std::vector<float>{0.5f, 0, -0.5f, 0, 0, 0}));
}

TEST(Film, HoldsOnlyThePassesItWasMadeWith) {
    const Film film(PixelRegion{0, 0, 1, 1}, 1, 1, PixelFilter(FilterType::Box, 1.0f), {}, false);
    float out[3];
    EXPECT_FALSE(film.read(Pass::Normal, out));
    EXPECT_EQ(film.sums_stride(), 4u);
    std::vector<float> scratch;
    PassValues none(&film.layout(), scratch.data());
    EXPECT_FALSE(none.wants(Pass::Normal));
    none.write(Pass::Normal, Vec3(1, 2, 3));  // not held: nothing is written anywhere
}

TEST(Film, LightPathSplatsAddToTheCameraSamplesOverTheSampleIndices) {
    Film film = small_film(true);
    const FilmSum one = to_fixed_exact(1);
    const FilmSum sums[] = {one, one, one, one, 0, 0, 0};
    film.store_sums(1, sums, 1);
    std::vector<Splat> splats;
    // Film point at the centre of frame pixel (2, 2) = region pixel 1; outside the region: none.
    film.splat(Vec2{2.5f, 2.5f}, Rgb(3.0f), splats);
    film.splat(Vec2{0.5f, 0.5f}, Rgb(5.0f), splats);
    ASSERT_EQ(splats.size(), 1u);
    EXPECT_EQ(splats[0].pixel, 1u);
    splats.push_back({0, Rgb(std::numeric_limits<float>::quiet_NaN())});
    uint64_t clamped = 0;
    EXPECT_EQ(film.add_splats(splats, &clamped), 1u);  // the NaN is dropped, not summed
    EXPECT_EQ(clamped, 0u);
    film.publish_all(2);
    EXPECT_EQ(read(film, Pass::Combined), (std::vector<float>{0, 0, 0, 0, 2, 2, 2, 0.5f}));
}

TEST(Film, TheNormalPassThroughTheAbiFacesTheCameraAndLeavesTheImageAsItWas) {
    const StratumMaterialDesc wall{STRATUM_MATERIAL_DIFFUSE, {0.5f, 0.5f, 0.5f},    1, 0, 0, 1.5f,
                                   {0.2f, 0.2f, 0.2f},       STRATUM_MICROFACET_GGX};
    StratumScene* scene = make_sphere_interior(wall, 16, 0, 0, 0);
    ASSERT_NE(scene, nullptr) << stratum_last_error();
    const auto render_with = [&](const char* passes, std::vector<float>* normal) {
        StratumRenderer* r = nullptr;
        EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
        for (const char* name : {"width", "height"})
            EXPECT_EQ(stratum_renderer_set_int(r, name, 9), STRATUM_OK);
        EXPECT_EQ(stratum_renderer_set_int(r, "samples", 8), STRATUM_OK);
        EXPECT_EQ(stratum_renderer_set_string(r, "passes", passes), STRATUM_OK) << stratum_last_error();
        EXPECT_TRUE(render_to_end(r)) << stratum_last_error();
        std::vector<float> rgba(9 * 9 * 4);
        EXPECT_EQ(stratum_renderer_read_pixels(r, rgba.data(), rgba.size()), STRATUM_OK);
        if (normal) {
            normal->resize(9 * 9 * 3);
            EXPECT_EQ(stratum_renderer_read_pass(r, "Normal", normal->data(), normal->size()), STRATUM_OK)
                << stratum_last_error();
        } else {
            float n[9 * 9 * 3];
            EXPECT_EQ(stratum_renderer_read_pass(r, "Normal", n, 9 * 9 * 3), STRATUM_ERROR_INVALID_ARGUMENT);
            EXPECT_NE(std::string(stratum_last_error()).find("add it to the setting 'passes'"),
                      std::string::npos);
        }
        stratum_renderer_destroy(r);
        return rgba;
    };
    std::vector<float> normal;
    EXPECT_EQ(render_with("Normal", &normal), render_with("", nullptr));
    // The camera at the centre looks down -Z: the wall it sees in the middle pixel is at (0, 0, -1),
    // its normal turned toward the camera is +Z, up to the facets of a 16-ring sphere (each spans
    // 11.25 degrees: cos 11.25° > 0.98) and the 8 samples' spread over the pixel.
    const float* centre = &normal[(4 * 9 + 4) * 3];
    EXPECT_NEAR(centre[0], 0.0f, 0.2f);
    EXPECT_NEAR(centre[1], 0.0f, 0.2f);
    EXPECT_GT(centre[2], 0.98f);
    // Every pixel sees the wall from inside: unit normals (averaged over nearby facets) pointing
    // back toward the camera at the origin, i.e. against the view direction of their pixel.
    for (int y = 0; y < 9; ++y) {
        for (int x = 0; x < 9; ++x) {
            const float* n = &normal[(y * 9 + x) * 3];
            const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            EXPECT_GT(length, 0.95f) << x << ", " << y;
            EXPECT_LE(length, 1.0001f) << x << ", " << y;
            // View direction of the pixel centre for a 90° field of view: ((x+0.5)/4.5 - 1, ..., -1).
            const float dx = (static_cast<float>(x) + 0.5f) / 4.5f - 1.0f;
            const float dy = (static_cast<float>(y) + 0.5f) / 4.5f - 1.0f;
            EXPECT_LT(n[0] * dx + n[1] * dy - n[2], 0.0f) << x << ", " << y;
        }
    }
    stratum_scene_destroy(scene);
}

TEST(Film, AnUnknownPassIsRefusedNamingItAndTheKnownOnes) {
    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_string(r, "passes", "Normal,Glitter"), STRATUM_ERROR_INVALID_ARGUMENT);
    const std::string message = stratum_last_error();
    EXPECT_NE(message.find("'Glitter'"), std::string::npos) << message;
    EXPECT_NE(message.find("(known: Normal"), std::string::npos) << message;
    const char* name = nullptr;
    int32_t channels = 0;
    ASSERT_EQ(stratum_pass_info(1, &name, &channels, nullptr), STRATUM_OK);
    EXPECT_EQ(std::string(name), "Normal");
    EXPECT_EQ(channels, 3);
    EXPECT_EQ(stratum_pass_info(stratum_pass_count(), &name, &channels, nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
}
