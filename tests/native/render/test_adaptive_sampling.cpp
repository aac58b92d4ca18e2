// Adaptive sampling (render/adaptive_sampling.h, issue 16): Cycles' automatic values, the
// neighbourhood rule, unbiasedness on the closed sphere, each pixel's samples a power-of-two
// prefix of its sequence (a (0,k,2)-net for sobol), zsobol's blue noise kept, determinism, and
// the renders it refuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "error_spectrum.h"
#include "film/film.h"
#include "render/adaptive_sampling.h"
#include "render_helpers.h"
#include "sampling/sobol_sampler.h"
#include "sampling/zsobol_sampler.h"

using namespace stratum_test;

namespace {

// A rendered image with its sample counts.
struct AdaptiveRender {
    std::vector<float> rgba, counts;
    std::string notices, error;
};

AdaptiveRender render_with_counts(StratumScene* scene, const Settings& settings, uint32_t w, uint32_t h) {
    AdaptiveRender out;
    StratumRenderer* r = nullptr;
    EXPECT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    Settings all = settings;
    all.emplace_back("width", w);
    all.emplace_back("height", h);
    all.emplace_back("passes", "Debug Sample Count");
    out.error = apply_settings(r, all);
    if (out.error.empty() && !render_to_end(r)) out.error = stratum_last_error();
    if (out.error.empty()) {
        out.rgba.resize(size_t{w} * h * 4);
        out.counts.resize(size_t{w} * h);
        EXPECT_EQ(stratum_renderer_read_pixels(r, out.rgba.data(), out.rgba.size()), STRATUM_OK);
        EXPECT_EQ(stratum_renderer_read_pass(r, "Debug Sample Count", out.counts.data(), out.counts.size()),
                  STRATUM_OK);
        const char* notices = nullptr;
        if (stratum_renderer_notices(r, &notices) == STRATUM_OK && notices) out.notices = notices;
    }
    stratum_renderer_destroy(r);
    return out;
}

// A diffuse plane z = 0 seen from above (camera at z = 1, 90° field of view) lit by a sphere
// light off to one side: smooth direct lighting, where the low-discrepancy samplers' structure
// shows, and brightness falling across the frame, so pixels converge at different counts.
StratumScene* lit_plane(float light_radius) {
    StratumScene* scene = nullptr;
    stratum_scene_create(&scene);
    uint32_t mat = 0;
    const StratumMaterialDesc grey = diffuse_grey(0.7f);
    stratum_scene_add_material(scene, &grey, &mat);
    add_square_instance(scene, 0.0f, 4.0f, mat);
    StratumLightDesc light{};
    light.type = STRATUM_LIGHT_POINT;
    light.color[0] = light.color[1] = light.color[2] = 1.0f;
    light.strength = 40.0f;
    light.radius = light_radius;
    std::copy(kIdentity, kIdentity + 16, light.transform);
    light.transform[3] = 0.8f;
    light.transform[7] = 0.3f;
    light.transform[11] = 0.6f;
    stratum_scene_add_light(scene, &light);
    const StratumCameraDesc camera = camera_at(0, 0, 1);
    stratum_scene_set_camera(scene, &camera);
    return scene;
}

bool is_power_of_two(uint32_t n) { return n > 0 && (n & (n - 1)) == 0; }

}  // namespace

TEST(AdaptiveSampling, ResolvesCyclesAutomaticValues) {
    using stratum::AdaptiveSampling;
    using stratum::AdaptiveSettings;
    // Threshold 0.01: min samples ⌈16/0.01^0.3⌉ = ⌈63.7⌉ = 64 (Cycles' comment: "0.01 -> 64").
    AdaptiveSampling a = AdaptiveSampling::resolve(AdaptiveSettings{true, 0.01f, 0}, 1024);
    EXPECT_NEAR(a.threshold, 0.01, 1e-9);
    EXPECT_EQ(a.min_samples, 64u);
    // Threshold 0 = automatic, max(0.001, 1/samples): 1/4096 → 0.001, min ⌈16/0.001^0.3⌉ = 128.
    a = AdaptiveSampling::resolve(AdaptiveSettings{true, 0.0f, 0}, 4096);
    EXPECT_NEAR(a.threshold, 0.001, 1e-12);
    EXPECT_EQ(a.min_samples, 128u);
    a = AdaptiveSampling::resolve(AdaptiveSettings{true, 0.0f, 0}, 50);
    EXPECT_NEAR(a.threshold, 0.02, 1e-9);
    // An explicit minimum rounds up to a power of two, and never below 4 (as Cycles' max(4, ·)).
    EXPECT_EQ(AdaptiveSampling::resolve(AdaptiveSettings{true, 0.01f, 5}, 1024).min_samples, 8u);
    EXPECT_EQ(AdaptiveSampling::resolve(AdaptiveSettings{true, 0.01f, 1}, 1024).min_samples, 4u);
    // Checks at powers of two from the minimum, never at the last count.
    a = AdaptiveSampling::resolve(AdaptiveSettings{true, 0.01f, 16}, 100);
    EXPECT_FALSE(a.checks_at(8, 100));
    EXPECT_TRUE(a.checks_at(16, 100));
    EXPECT_FALSE(a.checks_at(48, 100));
    EXPECT_TRUE(a.checks_at(64, 100));
    EXPECT_FALSE(a.checks_at(64, 64));
}

// One noisy pixel among constant ones: it and its 8 neighbours keep sampling, the rest stop
// (Cycles' 3×3 dilation); a noisy pixel at the corner keeps only its 3 neighbours; in blocks,
// the blocks that hold any of them.
TEST(AdaptiveSampling, APixelStopsOnlyWhenItsNeighboursHaveConverged) {
    using namespace stratum;
    const Pass passes[] = {Pass::Error};
    for (const auto& [nx, ny] : {std::pair{2u, 2u}, std::pair{0u, 0u}}) {
        Film film(PixelRegion{0, 0, 6, 5}, 6, 5, PixelFilter(FilterType::Box, 1.0f), passes, false, true);
        std::vector<FilmSum> sums(film.sums_stride());
        for (uint32_t y = 0; y < 5; ++y)
            for (uint32_t x = 0; x < 6; ++x) {
                const size_t p = film.region().index(x, y);
                std::fill(sums.begin(), sums.end(), 0);
                for (uint32_t i = 0; i < 4; ++i) {
                    // Constant 0.5, or 0 and 1 alternating (a relative error far above 5·0.01).
                    const float v = x == nx && y == ny ? static_cast<float>(i % 2) : 0.5f;
                    film.add_sample(sums.data(), i, Rgb(v), 1.0f, nullptr);
                    if (is_power_of_two(i + 1)) film.store_sums(p, sums.data(), i + 1);
                }
            }
        AdaptiveSampling adaptive = AdaptiveSampling::resolve(AdaptiveSettings{true, 0.01f, 4}, 64);
        std::vector<uint8_t> stopped(30, 0);
        stop_converged_pixels(film, adaptive, stopped);
        for (uint32_t y = 0; y < 5; ++y)
            for (uint32_t x = 0; x < 6; ++x) {
                const bool near = std::abs(int(x) - int(nx)) <= 1 && std::abs(int(y) - int(ny)) <= 1;
                EXPECT_EQ(stopped[film.region().index(x, y)], near ? 0 : 1)
                    << "pixel (" << x << ", " << y << "), noisy pixel (" << nx << ", " << ny << ")";
            }
        // In aligned 4 × 4 blocks (the screen-space samplers) every block that holds one of
        // those pixels goes on whole: the block x, y < 4 here.
        adaptive.block = kScreenBlock;
        std::fill(stopped.begin(), stopped.end(), 0);
        stop_converged_pixels(film, adaptive, stopped);
        for (uint32_t y = 0; y < 5; ++y)
            for (uint32_t x = 0; x < 6; ++x)
                EXPECT_EQ(stopped[film.region().index(x, y)], x < 4 && y < 4 ? 0 : 1)
                    << "pixel (" << x << ", " << y << ") in 4 x 4 blocks, noisy pixel (" << nx << ", " << ny
                    << ")";
    }
}

// The metric mse (adaptive_sampling.h): n_i ∝ σ_i, a pixel converged once its pooled spread σ̃
// is at most λ n with λ = t² L̄² / mean σ̃. An 8 × 6 film of mean 0.5 everywhere, 4 samples a
// pixel alternating 0.5 ± a: a = 0.05 in columns x < 4, a = 0.2 (4x the spread) in x >= 4. The
// per-sample spread is σ = k a (k = √(4/3): film.h's unbiased variance of 4 samples). t is chosen
// so that λ·4 lands at the geometric mean of the two spreads, 2x from each: pooling moves mean σ̃
// by 5% (column 3 pools to (0.05 + 0.05 + 0.2)/3 k = 0.1 k), far inside that margin. So the calm
// columns 0–2 stop, the noisy ones go on, and column 3, calm but next to the noisy ones, goes on
// too (its pooled spread 0.1 k is above λ·4 = 0.095 k). Twice t stops every pixel (λ 4x), half of
// it none; a black film stops everywhere (no spread at all).
TEST(AdaptiveSampling, TheMseMetricGivesSamplesWhereTheSpreadIs) {
    using namespace stratum;
    const Pass passes[] = {Pass::Error};
    const auto film_of = [&](float low, float high) {
        auto film = std::make_unique<Film>(PixelRegion{0, 0, 8, 6}, 8, 6, PixelFilter(FilterType::Box, 1.0f),
                                           passes, false, true);
        std::vector<FilmSum> sums(film->sums_stride());
        for (uint32_t y = 0; y < 6; ++y)
            for (uint32_t x = 0; x < 8; ++x) {
                std::fill(sums.begin(), sums.end(), 0);
                const float a = x < 4 ? low : high;
                for (uint32_t i = 0; i < 4; ++i) {
                    const float v = i % 2 ? 0.5f + a : 0.5f - a;
                    film->add_sample(sums.data(), i, Rgb(v * (low > 0.0f ? 1.0f : 0.0f)), 1.0f, nullptr);
                    if (is_power_of_two(i + 1))
                        film->store_sums(film->region().index(x, y), sums.data(), i + 1);
                }
            }
        return film;
    };
    const double k = std::sqrt(4.0 / 3.0);
    // λ·4 = 0.1 k with mean σ = 0.125 k and L̄ = 0.5: t² = 0.025 k · 0.125 k / 0.25.
    const double t = std::sqrt(0.025 * k * 0.125 * k / 0.25);
    const auto stopped_at = [&](const Film& film, double threshold) {
        AdaptiveSampling adaptive = AdaptiveSampling::resolve(AdaptiveSettings{true, 0.01f, 4}, 64);
        adaptive.metric = AdaptiveMetric::Mse;
        adaptive.threshold = threshold;
        std::vector<uint8_t> stopped(48, 0);
        stop_converged_pixels(film, adaptive, stopped);
        return stopped;
    };
    const auto film = film_of(0.05f, 0.2f);
    const std::vector<uint8_t> at_t = stopped_at(*film, t);
    for (uint32_t y = 0; y < 6; ++y)
        for (uint32_t x = 0; x < 8; ++x)
            EXPECT_EQ(at_t[film->region().index(x, y)], x < 3 ? 1 : 0) << "pixel (" << x << ", " << y << ")";
    for (const uint8_t s : stopped_at(*film, 2.0 * t)) EXPECT_EQ(s, 1);
    for (const uint8_t s : stopped_at(*film, 0.5 * t)) EXPECT_EQ(s, 0);
    for (const uint8_t s : stopped_at(*film_of(0.0f, 0.0f), t)) EXPECT_EQ(s, 1);
}

// Acceptance 1: stopping on its own error can bias an estimator (a pixel whose samples came out
// with a small spread stops, and its value is kept). On the closed sphere (k = 0.8, 60 bounces:
// L = Σ 0.8^m, noisy) at the default threshold the image mean must stay within 0.5% of the
// closed form. Statistics: 8 seeds × 1024 pixels, the standard error σ of the mean from
// seed_stats; 4σ must be under 0.5% (the measurement resolves the bound it checks), and the
// measured bias under 0.5% (an unbiased renderer is 6σ from failing).
TEST(AdaptiveSampling, TheClosedSphereConvergesToItsClosedFormAtTheDefaultThreshold) {
    IntegratingSphere s = make_closed_sphere(0.8f, 1.0f);
    ASSERT_NE(s.scene, nullptr) << stratum_last_error();
    const double expected = sphere_b_radiance(1.0, 0.8, 0.0, 60);
    // The metric mse at threshold 0.05 (the default 0.01 asks for more than 1024 samples here).
    // One light per vertex (light_tree_splits 1): the noisier estimator is the harder case for a
    // bias from stopping, and with the tree's 8 splits every pixel of this uniform scene stops
    // at the same count under mse, which would leave nothing adaptive to measure.
    for (const auto& [sampler, metric] :
         {std::pair{"random", "relative"}, std::pair{"sobol", "relative"}, std::pair{"sobol", "mse"}}) {
        std::vector<PixelStats> images;
        double samples = 0;
        std::set<float> counts;
        for (uint32_t seed = 0; seed < 8; ++seed) {
            const AdaptiveRender r =
                render_with_counts(s.scene,
                                   {{"samples", 1024},
                                    {"max_bounces", 60},
                                    {"light_tree_splits", 1},
                                    {"seed", seed},
                                    {"sampler", sampler},
                                    {"use_adaptive_sampling", 1},
                                    {"adaptive_metric", metric},
                                    {"adaptive_threshold", metric[0] == 'm' ? 0.05 : 0.01}},
                                   32, 32);
            ASSERT_TRUE(r.error.empty()) << r.error;
            images.push_back(pixel_stats(r.rgba));
            for (const float c : r.counts) {
                samples += c / (8.0 * static_cast<double>(r.counts.size()));
                counts.insert(c);
            }
        }
        const SeedStats st = seed_stats(images);
        const double bias = st.mean / expected - 1.0;
        std::printf(
            "%-6s adaptive %-8s: mean %.5f, closed form %.5f, bias %+.3f%% (se %.3f%%), mean samples %.1f\n",
            sampler, metric, st.mean, expected, 100.0 * bias, 100.0 * st.standard_error / expected, samples);
        EXPECT_LT(4.0 * st.standard_error / expected, 0.005) << sampler << " " << metric;
        EXPECT_LT(std::abs(bias), 0.005) << sampler << " " << metric;
        // Adaptive for real: pixels stopped before the 1024 samples, at several counts.
        EXPECT_LT(samples, 1024.0) << sampler << " " << metric;
        EXPECT_GE(counts.size(), 2u) << sampler << " " << metric;
    }
    stratum_scene_destroy(s.scene);
}

// Acceptance 3: a pixel that stopped at 2^k holds the first 2^k samples of its sequence: its
// value is bit-identical to a fixed render of 2^k samples (sobol's points do not depend on the
// sample count), and for sobol those samples' dims (0, 1) form a (0,k,2)-net.
TEST(AdaptiveSampling, AStoppedPixelHoldsAPowerOfTwoPrefixOfItsSequence) {
    StratumScene* scene = lit_plane(0.3f);
    constexpr uint32_t kSize = 16, kSamples = 256;
    const AdaptiveRender adaptive = render_with_counts(scene,
                                                       {{"samples", kSamples},
                                                        {"seed", 5u},
                                                        {"sampler", "sobol"},
                                                        {"use_adaptive_sampling", 1},
                                                        {"adaptive_threshold", 0.02},
                                                        {"adaptive_min_samples", 4}},
                                                       kSize, kSize);
    ASSERT_TRUE(adaptive.error.empty()) << adaptive.error;
    std::map<uint32_t, std::vector<size_t>> pixels_by_count;
    for (size_t p = 0; p < adaptive.counts.size(); ++p) {
        const auto count = static_cast<uint32_t>(adaptive.counts[p]);
        ASSERT_TRUE(is_power_of_two(count) && count >= 4 && count <= kSamples) << "count " << count;
        pixels_by_count[count].push_back(p);
    }
    ASSERT_GE(pixels_by_count.size(), 2u) << "every pixel took the same count: adaptive sampling did nothing";
    for (const auto& [count, pixels] : pixels_by_count) {
        const AdaptiveRender fixed =
            render_with_counts(scene, {{"samples", count}, {"seed", 5u}, {"sampler", "sobol"}}, kSize, kSize);
        ASSERT_TRUE(fixed.error.empty()) << fixed.error;
        uint32_t k = 0;
        while ((1u << k) < count) ++k;
        for (const size_t p : pixels) {
            for (int c = 0; c < 4; ++c)
                ASSERT_EQ(adaptive.rgba[4 * p + c], fixed.rgba[4 * p + c])
                    << "pixel " << p << " at " << count;
            std::vector<float> xy(2 * count);
            const auto x = static_cast<uint32_t>(p % kSize), y = static_cast<uint32_t>(p / kSize);
            ASSERT_EQ(
                stratum_sampler_points("sobol", kSamples, 5, kSize, kSize, x, y, 0, 1, count, xy.data()),
                STRATUM_OK);
            for (uint32_t i = 0; i <= k; ++i) {
                std::vector<int> cells(count, 0);
                for (uint32_t j = 0; j < count; ++j) {
                    const auto cx = static_cast<uint32_t>(xy[2 * j] * float(1u << i));
                    const auto cy = static_cast<uint32_t>(xy[2 * j + 1] * float(1u << (k - i)));
                    ASSERT_EQ(cells[(size_t{cy} << i) | cx]++, 0)
                        << "pixel " << p << ": its " << count << " samples are no (0," << k << ",2)-net";
                }
            }
        }
        std::printf("%zu pixels stopped at %u samples\n", pixels.size(), count);
    }
    stratum_scene_destroy(scene);
}

// Acceptance 3: zsobol's error stays blue noise under adaptive sampling. As the samplers' test
// (test_sobol_samplers.cpp, ZSobolSampler.ErrorIsBlueNoiseAtFourSamplesPerPixel): 64² pixels,
// each integrating exp(a·u·v) over its dims-(0,1) samples, a rising from 0.5 to 3 across the
// image so the pixels converge at different counts; the pixels' samples go through the film and
// the adaptive rule exactly as the renderer's passes do (4 to 32 samples, checks at 4, 8, 16;
// zsobol's pixels stop in 4 × 4 blocks as the renderer stops them). Threshold 0.032 leaves
// 15/23/28/35% of zsobol's pixels at 4/8/16/32 samples. The low-frequency ratio
// (error_spectrum.h) of the adaptive image must stay below 0.65, and per-pixel sobol's above it
// (the check tells blue from white). Statistics: ~200 low frequencies × 4 seeds of exponentially
// distributed power: the ratio's relative standard error is ~1/√800 = 3.5%.
struct AdaptiveSpectrum {
    double ratio = 0, mean_samples = 0;
    std::map<uint32_t, size_t> histogram;  // pixels per final count
};

template <typename SamplerType>
AdaptiveSpectrum adaptive_spectrum(double threshold, uint32_t fixed_samples, bool screen_space) {
    using namespace stratum;
    constexpr uint32_t w = 64, kMaxSamples = 32;
    const auto a_of = [](uint32_t x) { return 0.5 + 2.5 * x / double(w - 1); };
    // ∫∫ exp(a u v) du dv = Σ_n a^n / (n! (n + 1)²).
    const auto integral = [](double a) {
        double sum = 0, term = 1;
        for (int n = 0; n < 40; ++n) {
            if (n > 0) term *= a / n;
            sum += term / ((n + 1.0) * (n + 1.0));
        }
        return sum;
    };
    AdaptiveSpectrum out;
    SpectrumBands bands;
    const Pass passes[] = {Pass::Error};
    for (uint32_t seed : {1u, 2u, 3u, 4u}) {
        const uint32_t total = threshold > 0 ? kMaxSamples : fixed_samples;
        const SamplerType sampler({total, seed, w, w});
        Film film(PixelRegion{0, 0, w, w}, w, w, PixelFilter(FilterType::Box, 1.0f), passes, false, true);
        AdaptiveSampling adaptive = AdaptiveSampling::resolve(
            AdaptiveSettings{threshold > 0, static_cast<float>(threshold), 4}, total);
        // As the renderer does for the screen-space samplers (render/adaptive_sampling.h).
        if (screen_space) adaptive.block = kScreenBlock;
        std::vector<uint8_t> stopped(size_t{w} * w, 0);
        std::vector<FilmSum> sums(film.sums_stride());
        for (uint32_t begin = 0; begin < total; begin = std::max(begin + 1, 2 * begin)) {
            const uint32_t end = std::min(total, std::max(begin + 1, 2 * begin));
            for (uint32_t y = 0; y < w; ++y)
                for (uint32_t x = 0; x < w; ++x) {
                    const size_t p = film.region().index(x, y);
                    if (stopped[p]) continue;
                    film.load_sums(p, sums.data());
                    for (uint32_t i = begin; i < end; ++i) {
                        const Vec2 u = sampler.get_2d({x, y, i}, 0);
                        film.add_sample(sums.data(), i,
                                        Rgb(static_cast<float>(std::exp(a_of(x) * u.x * u.y))), 1.0f,
                                        nullptr);
                    }
                    film.store_sums(p, sums.data(), end);
                }
            if (is_power_of_two(end)) {
                film.estimate_errors();
                if (adaptive.checks_at(end, total)) stop_converged_pixels(film, adaptive, stopped);
            }
        }
        std::vector<double> error(size_t{w} * w);
        for (uint32_t y = 0; y < w; ++y)
            for (uint32_t x = 0; x < w; ++x) {
                const size_t p = film.region().index(x, y);
                error[p] = film.mean(p).r - integral(a_of(x));
                ++out.histogram[film.sample_count(p)];
                out.mean_samples += film.sample_count(p) / (4.0 * w * w);
            }
        bands.add(error, w);
    }
    out.ratio = bands.low_frequency_ratio();
    return out;
}

TEST(AdaptiveSampling, ZSobolErrorStaysBlueNoise) {
    using stratum::SobolSampler;
    using stratum::ZSobolSampler;
    constexpr double kThreshold = 0.032;
    const AdaptiveSpectrum z = adaptive_spectrum<ZSobolSampler>(kThreshold, 0, true);
    const AdaptiveSpectrum s = adaptive_spectrum<SobolSampler>(kThreshold, 0, false);
    for (const auto& [name, r] : {std::pair{"zsobol", z}, std::pair{"sobol", s}}) {
        std::printf("%-6s adaptive: low-frequency ratio %.3f, mean samples %.2f, pixels at", name, r.ratio,
                    r.mean_samples);
        for (const auto& [count, n] : r.histogram) std::printf(" %u: %zu", count, n);
        std::printf("\n");
    }
    // Fixed counts bracketing the adaptive mean, for the closing note.
    for (const uint32_t fixed : {8u, 16u, 32u})
        std::printf("zsobol fixed %2u samples: low-frequency ratio %.3f\n", fixed,
                    adaptive_spectrum<ZSobolSampler>(0.0, fixed, true).ratio);
    EXPECT_LT(z.ratio, 0.65);
    EXPECT_GT(s.ratio, 0.65);
    // Adaptive for real: at least a tenth of the pixels at each of two counts.
    size_t counts_held = 0;
    for (const auto& [count, n] : z.histogram) counts_held += n >= 4 * 64 * 64 / 10 ? 1 : 0;
    EXPECT_GE(counts_held, 2u);
}

TEST(AdaptiveSampling, IsBitIdenticalForAnyThreadCount) {
    StratumScene* scene = lit_plane(0.3f);
    for (const auto& [metric, threshold] : {std::pair{"relative", 0.02}, std::pair{"mse", 0.1}}) {
        const Settings settings = {{"samples", 64},
                                   {"sampler", "zsobol"},
                                   {"use_adaptive_sampling", 1},
                                   {"seed", 2u},
                                   {"adaptive_threshold", threshold},
                                   {"adaptive_min_samples", 4},
                                   {"adaptive_metric", metric}};
        Settings one = settings, two = settings;
        one.emplace_back("threads", 1);
        two.emplace_back("threads", 2);
        const AdaptiveRender a = render_with_counts(scene, one, 24, 20),
                             b = render_with_counts(scene, two, 24, 20);
        ASSERT_TRUE(a.error.empty() && b.error.empty()) << a.error << b.error;
        EXPECT_TRUE(a.rgba == b.rgba) << metric;
        EXPECT_TRUE(a.counts == b.counts) << metric;
        // Adaptive for real: some pixels stopped before 64.
        EXPECT_LT(*std::min_element(a.counts.begin(), a.counts.end()), 64.0f) << metric;
    }
    stratum_scene_destroy(scene);
}

TEST(AdaptiveSampling, RefusesASampleSubsetAndTellsWhatItDoesNotApplyTo) {
    StratumScene* scene = lit_plane(0.3f);
    // A subset: refused at start, naming the settings.
    const AdaptiveRender subset = render_with_counts(
        scene, {{"samples", 16}, {"sample_offset", 4}, {"use_adaptive_sampling", 1}}, 8, 8);
    EXPECT_NE(subset.error.find("sample_offset = 4"), std::string::npos) << subset.error;
    // Light tracing: every pixel takes every sample, and a notice says why.
    const AdaptiveRender light = render_with_counts(
        scene, {{"samples", 16}, {"integrator", "light"}, {"use_adaptive_sampling", 1}}, 8, 8);
    ASSERT_TRUE(light.error.empty()) << light.error;
    EXPECT_NE(light.notices.find("Adaptive sampling is off for the light integrator"), std::string::npos)
        << light.notices;
    // A sampler laid out for the whole count: rendered, with a notice.
    const AdaptiveRender stratified = render_with_counts(
        scene, {{"samples", 16}, {"sampler", "stratified"}, {"use_adaptive_sampling", 1}}, 8, 8);
    ASSERT_TRUE(stratified.error.empty()) << stratified.error;
    EXPECT_NE(stratified.notices.find("whole sample count"), std::string::npos) << stratified.notices;
    // Its sums hold no common sample range: the exchange refuses them.
    StratumRenderer* r = nullptr;
    ASSERT_EQ(stratum_renderer_create(scene, &r), STRATUM_OK);
    ASSERT_EQ(apply_settings(r, {{"width", 8}, {"height", 8}, {"samples", 16}, {"use_adaptive_sampling", 1}}),
              "");
    ASSERT_TRUE(render_to_end(r));
    size_t bytes = 0;
    EXPECT_NE(stratum_renderer_sums_size(r, &bytes), STRATUM_OK);
    EXPECT_NE(std::string(stratum_last_error()).find("adaptive sampling"), std::string::npos);
    // Nor does it take other sums into its film.
    StratumRenderer* fixed = nullptr;
    ASSERT_EQ(stratum_renderer_create(scene, &fixed), STRATUM_OK);
    ASSERT_EQ(apply_settings(fixed, {{"width", 8}, {"height", 8}, {"samples", 16}}), "");
    ASSERT_TRUE(render_to_end(fixed));
    ASSERT_EQ(stratum_renderer_sums_size(fixed, &bytes), STRATUM_OK);
    std::vector<uint8_t> sums(bytes);
    ASSERT_EQ(stratum_renderer_read_sums(fixed, sums.data(), sums.size()), STRATUM_OK);
    EXPECT_NE(stratum_renderer_add_sums(r, sums.data(), sums.size()), STRATUM_OK);
    EXPECT_NE(std::string(stratum_last_error()).find("adaptive sampling"), std::string::npos);
    stratum_renderer_destroy(fixed);
    stratum_renderer_destroy(r);
    stratum_scene_destroy(scene);
}
