// A frame's samples split into ranges rendered apart (sample_offset, sample_count), their exact
// sums added (stratum_renderer_read_sums / _add_sums): every pass bit-identical to one render of
// all the samples, for every sampler, for splits into halves, uneven parts and single samples
// (the error pass: see `comparable`).
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "render_helpers.h"
#include "setting_choices.h"

using namespace stratum_test;

namespace {

constexpr int64_t kSize = 12;
constexpr int64_t kSamples = 8;
// Passes of every kind the film merges: Average (Normal), FirstSample (Depth), SampleCount,
// StandardError.
constexpr const char* kPasses = "Normal,Depth,Debug Sample Count,Stratum Error";
const std::vector<std::pair<const char*, int32_t>> kPassChannels = {
    {"Combined", 4}, {"Normal", 3}, {"Depth", 1}, {"Debug Sample Count", 1}, {"Stratum Error", 3}};

// A diffuse sphere under a sky and a point light, seen from outside: noise in every pass.
StratumScene* lit_sphere() {
    StratumScene* scene = nullptr;
    stratum_scene_create(&scene);
    const StratumMaterialDesc grey{STRATUM_MATERIAL_DIFFUSE, {0.6f, 0.5f, 0.4f}, 1, 0, 0, 1.5f, {0, 0, 0},
                                   STRATUM_MICROFACET_GGX};
    uint32_t mat = 0;
    stratum_scene_add_material(scene, &grey, &mat);
    add_mesh_instance(scene, make_sphere(1.0f, 12, 24), mat);
    const float sky[3] = {0.3f, 0.4f, 0.5f};
    stratum_scene_set_background(scene, sky);
    StratumLightDesc light{};
    light.type = STRATUM_LIGHT_POINT;
    light.color[0] = light.color[1] = light.color[2] = 1.0f;
    light.strength = 50.0f;
    light.radius = 0.1f;
    std::copy(kIdentity, kIdentity + 16, light.transform);
    light.transform[3] = 2.0f;
    light.transform[11] = 2.0f;
    stratum_scene_add_light(scene, &light);
    const StratumCameraDesc camera = camera_at(0, 0, 3);
    stratum_scene_set_camera(scene, &camera);
    return scene;
}

struct Passes {
    std::vector<std::vector<float>> values;  // kPassChannels' order
    bool operator==(const Passes&) const = default;
};

Passes read_passes(StratumRenderer* r) {
    Passes out;
    for (const auto& [name, channels] : kPassChannels) {
        std::vector<float> v(static_cast<size_t>(kSize * kSize * channels));
        EXPECT_EQ(stratum_renderer_read_pass(r, name, v.data(), v.size()), STRATUM_OK)
            << stratum_last_error();
        out.values.push_back(std::move(v));
    }
    return out;
}

StratumRenderer* start(StratumScene* scene, const char* sampler, const char* integrator, int64_t offset,
                       int64_t count) {
    StratumRenderer* r = nullptr;
    EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    EXPECT_EQ(apply_settings(r, {{"width", kSize},
                                 {"height", kSize},
                                 {"samples", kSamples},
                                 {"seed", 3},
                                 {"sample_offset", offset},
                                 {"sample_count", count},
                                 {"sampler", sampler},
                                 {"integrator", integrator},
                                 {"passes", kPasses}}),
              "");
    EXPECT_TRUE(render_to_end(r)) << stratum_last_error();
    return r;
}

std::vector<uint8_t> sums_of(StratumRenderer* r) {
    size_t bytes = 0;
    EXPECT_EQ(stratum_renderer_sums_size(r, &bytes), STRATUM_OK) << stratum_last_error();
    std::vector<uint8_t> sums(bytes);
    EXPECT_EQ(stratum_renderer_read_sums(r, sums.data(), sums.size()), STRATUM_OK) << stratum_last_error();
    return sums;
}

// The passes of the sample ranges `parts` (offset, count), rendered apart and added into an
// empty renderer in reverse order (addition is exact, so the order cannot matter).
Passes merged(StratumScene* scene, const char* sampler, const char* integrator,
              const std::vector<std::pair<int64_t, int64_t>>& parts) {
    std::vector<std::vector<uint8_t>> sums;
    for (const auto& [offset, count] : parts) {
        StratumRenderer* r = start(scene, sampler, integrator, offset, count);
        sums.push_back(sums_of(r));
        stratum_renderer_destroy(r);
    }
    StratumRenderer* into = nullptr;
    EXPECT_EQ(stratum_renderer_create(scene, &into), STRATUM_OK);
    for (auto it = sums.rbegin(); it != sums.rend(); ++it)
        EXPECT_EQ(stratum_renderer_add_sums(into, it->data(), it->size()), STRATUM_OK)
            << stratum_last_error();
    Passes out = read_passes(into);
    stratum_renderer_destroy(into);
    return out;
}

// The passes the exchange keeps bit for bit. The Stratum Error pass of combined sums is the
// independent-samples estimate (film/film.h: a render's prefix sums, which measure a
// low-discrepancy sampler's gain, are its own); for the independent samplers that is the whole
// render's too.
Passes comparable(Passes passes, const std::string& sampler) {
    if (sampler != "random" && sampler != "lcg") passes.values.pop_back();  // Stratum Error, the last
    return passes;
}

}  // namespace

TEST(FilmExchange, SplitSampleRangesAddUpToTheWholeRenderBitForBitForEverySampler) {
    StratumScene* scene = lit_sphere();
    const std::vector<std::vector<std::pair<int64_t, int64_t>>> splits = {
        {{0, 4}, {4, 0}},                                                   // halves (count 0: up to samples)
        {{0, 3}, {3, 5}},                                                   // uneven
        {{0, 1}, {1, 6}, {7, 1}},                                           // a single first and last sample
        {{0, 1}, {1, 1}, {2, 1}, {3, 1}, {4, 1}, {5, 1}, {6, 1}, {7, 1}}};  // one sample each
    for (const char* sampler : setting_choices("sampler")) {
        StratumRenderer* whole = start(scene, sampler, "path", 0, 0);
        const Passes expected = read_passes(whole);
        stratum_renderer_destroy(whole);
        for (const auto& split : splits)
            EXPECT_TRUE(comparable(merged(scene, sampler, "path", split), sampler) ==
                        comparable(expected, sampler))
                << sampler << ", split into " << split.size() << " ranges";
    }
    stratum_scene_destroy(scene);
}

TEST(FilmExchange, LightTracingSplatsAddUpToTheWholeRender) {
    StratumScene* scene = lit_sphere();
    StratumRenderer* whole = start(scene, "sobol", "light", 0, 0);
    const Passes expected = read_passes(whole);
    stratum_renderer_destroy(whole);
    EXPECT_TRUE(comparable(merged(scene, "sobol", "light", {{0, 5}, {5, 3}}), "sobol") ==
                comparable(expected, "sobol"));
    stratum_scene_destroy(scene);
}

TEST(FilmExchange, RefusesSumsThatDoNotBelongTogether) {
    StratumScene* scene = lit_sphere();
    StratumRenderer* a = start(scene, "random", "path", 0, 4);
    const std::vector<uint8_t> first = sums_of(a);
    // Ranges that overlap or leave a gap would count a sample twice or miss one.
    EXPECT_EQ(stratum_renderer_add_sums(a, first.data(), first.size()), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(std::string(stratum_last_error()).find("do not meet"), std::string::npos)
        << stratum_last_error();
    StratumRenderer* gap = start(scene, "random", "path", 5, 2);
    const std::vector<uint8_t> later = sums_of(gap);
    EXPECT_EQ(stratum_renderer_add_sums(a, later.data(), later.size()), STRATUM_ERROR_INVALID_ARGUMENT);
    // Another frame size.
    StratumRenderer* other = nullptr;
    stratum_renderer_create(scene, &other);
    stratum_renderer_set_int(other, "width", 8);
    stratum_renderer_set_int(other, "height", 8);
    stratum_renderer_set_int(other, "samples", kSamples);
    stratum_renderer_set_int(other, "sample_offset", 4);
    render_to_end(other);
    const std::vector<uint8_t> small = sums_of(other);
    EXPECT_EQ(stratum_renderer_add_sums(a, small.data(), small.size()), STRATUM_ERROR_INVALID_ARGUMENT);
    // Bytes that are not sums: truncated, or garbage.
    EXPECT_EQ(stratum_renderer_add_sums(a, first.data(), first.size() - 1), STRATUM_ERROR_INVALID_ARGUMENT);
    const std::vector<uint8_t> junk(64, 0x5a);
    EXPECT_EQ(stratum_renderer_add_sums(a, junk.data(), junk.size()), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_renderer_add_sums(a, nullptr, 16), STRATUM_ERROR_INVALID_ARGUMENT);
    std::vector<uint8_t> wrong_size(first.size() + 1);
    EXPECT_EQ(stratum_renderer_read_sums(a, wrong_size.data(), wrong_size.size()),
              STRATUM_ERROR_INVALID_ARGUMENT);
    // A subset outside the samples.
    EXPECT_EQ(stratum_renderer_set_int(a, "sample_offset", kSamples), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_start(a), STRATUM_ERROR_INVALID_STATE);
    EXPECT_EQ(stratum_renderer_set_int(a, "sample_offset", 2), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_set_int(a, "sample_count", kSamples - 1), STRATUM_OK);
    EXPECT_EQ(stratum_renderer_start(a), STRATUM_ERROR_INVALID_STATE);
    EXPECT_NE(std::string(stratum_last_error()).find("exceeds samples"), std::string::npos)
        << stratum_last_error();
    for (StratumRenderer* r : {a, gap, other}) stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
}
