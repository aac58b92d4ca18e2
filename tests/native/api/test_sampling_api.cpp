// The sampling entry points of the C ABI: dimension names follow dimensions.h, raw points are
// exactly the sampler's own values, warps are unit vectors with their densities, and bad
// input is rejected with a message that names the value.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "sampling/bluenoise_sampler.h"
#include "sampling/dimensions.h"
#include "sampling/hemisphere.h"
#include "sampling/sampler_registry.h"

namespace {

using namespace stratum;

std::string name_of(uint32_t dimension) {
    const char* name = nullptr;
    EXPECT_EQ(stratum_dimension_name(dimension, &name), STRATUM_OK) << stratum_last_error();
    return name ? name : "";
}

std::string last_error() { return stratum_last_error(); }

}  // namespace

TEST(SamplingApi, LayoutSizesAreThoseOfDimensionsH) {
    EXPECT_EQ(stratum_camera_dimensions(), kCameraDimensions);
    EXPECT_EQ(stratum_bounce_dimension_stride(), kBounceStride);
}

TEST(SamplingApi, CameraDimensionNames) {
    EXPECT_EQ(name_of(kDimFilter), "filter.x");
    EXPECT_EQ(name_of(kDimFilter + 1), "filter.y");
    EXPECT_EQ(name_of(kDimLens), "lens.u");
    EXPECT_EQ(name_of(kDimLens + 1), "lens.v");
    EXPECT_EQ(name_of(kDimTime), "time");
    EXPECT_EQ(name_of(0), "filter.x");  // the pixel filter pair comes first
}

TEST(SamplingApi, BounceDimensionNames) {
    for (uint32_t bounce : {0u, 1u, 7u, 1000u}) {
        const std::string p = "bounce" + std::to_string(bounce) + ".";
        EXPECT_EQ(name_of(bounce_dimension(bounce, kDimLightChoice)), p + "light_choice");
        EXPECT_EQ(name_of(bounce_dimension(bounce, kDimRussianRoulette)), p + "russian_roulette");
        EXPECT_EQ(name_of(bounce_dimension(bounce, kDimLightPoint)), p + "light.u");
        EXPECT_EQ(name_of(bounce_dimension(bounce, kDimLightPoint) + 1), p + "light.v");
        EXPECT_EQ(name_of(bounce_dimension(bounce, kDimBsdfDirection)), p + "bsdf.u");
        EXPECT_EQ(name_of(bounce_dimension(bounce, kDimBsdfDirection) + 1), p + "bsdf.v");
        EXPECT_EQ(name_of(bounce_dimension(bounce, kDimBsdfLobe)), p + "bsdf_lobe");
    }
    EXPECT_EQ(name_of(kCameraDimensions), "bounce0.light_choice");
}

TEST(SamplingApi, EveryDimensionHasAUniqueNameExceptUnusedSlots) {
    std::set<std::string> seen;
    for (uint32_t d = 0; d < kCameraDimensions + 3 * kBounceStride; ++d) {
        const std::string name = name_of(d);
        ASSERT_FALSE(name.empty()) << d;
        if (name.find("unused") != std::string::npos) continue;
        EXPECT_TRUE(seen.insert(name).second) << "duplicate " << name;
    }
    // Huge dimensions have names too (bounce blocks repeat without end).
    EXPECT_EQ(name_of(0xffffffffu).rfind("bounce", 0), 0u);
}

TEST(SamplingApi, NamesStayValidAcrossCalls) {
    const char *a = nullptr, *b = nullptr;
    ASSERT_EQ(stratum_dimension_name(kDimLens, &a), STRATUM_OK);
    ASSERT_EQ(stratum_dimension_name(bounce_dimension(3, kDimBsdfLobe), &b), STRATUM_OK);
    for (uint32_t d = 0; d < 100; ++d) name_of(d);
    EXPECT_STREQ(a, "lens.u");
    EXPECT_STREQ(b, "bounce3.bsdf_lobe");
    EXPECT_EQ(stratum_dimension_name(0, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("out_name"), std::string::npos);
}

TEST(SamplingApi, PointsAreTheSamplersOwnValues) {
    constexpr uint32_t kSamples = 16, kSeed = 7, kWidth = 8, kHeight = 4, kX = 5, kY = 3, kCount = 40;
    SamplerSettings settings;
    settings.samples = kSamples;
    settings.seed = kSeed;
    settings.width = kWidth;
    settings.height = kHeight;
    const uint32_t bsdf = bounce_dimension(1, kDimBsdfDirection);
    for (const SamplerEntry& entry : sampler_registry()) {
        SCOPED_TRACE(entry.info.name);
        const auto sampler = entry.create(settings);
        std::vector<float> xy(2 * kCount, -1.0f);
        // A 2D pair (even dimension, next one): get_2d, as the integrators read it.
        for (uint32_t dim : {uint32_t{kDimFilter}, bsdf}) {
            ASSERT_EQ(stratum_sampler_points(entry.info.name, kSamples, kSeed, kWidth, kHeight, kX, kY, dim,
                                             dim + 1, kCount, xy.data()),
                      STRATUM_OK)
                << last_error();
            for (uint32_t i = 0; i < kCount; ++i) {
                const Vec2 p = sampler->get_2d(PixelSample{kX, kY, i}, dim);
                EXPECT_EQ(xy[2 * i], p.x) << "dim " << dim << " sample " << i;
                EXPECT_EQ(xy[2 * i + 1], p.y) << "dim " << dim << " sample " << i;
                EXPECT_GE(xy[2 * i], 0.0f);
                EXPECT_LT(xy[2 * i], 1.0f);
            }
        }
        // Any other pair of dimensions: two 1D values.
        const uint32_t a = kDimTime, b = bounce_dimension(0, kDimLightChoice) + 2 * kBounceStride;
        ASSERT_EQ(stratum_sampler_points(entry.info.name, kSamples, kSeed, kWidth, kHeight, kX, kY, a, b,
                                         kCount, xy.data()),
                  STRATUM_OK)
            << last_error();
        for (uint32_t i = 0; i < kCount; ++i) {
            EXPECT_EQ(xy[2 * i], sampler->get_1d(PixelSample{kX, kY, i}, a)) << i;
            EXPECT_EQ(xy[2 * i + 1], sampler->get_1d(PixelSample{kX, kY, i}, b)) << i;
        }
    }
}

TEST(SamplingApi, PointsRejectBadInputNamingTheValue) {
    std::vector<float> xy(8);
    auto call = [&](const char* s, uint32_t samples, uint32_t w, uint32_t h, uint32_t px, uint32_t py,
                    uint32_t count, float* out) {
        return stratum_sampler_points(s, samples, 0, w, h, px, py, 0, 1, count, out);
    };
    EXPECT_EQ(call("no_such_sampler", 4, 8, 8, 0, 0, 4, xy.data()), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("no_such_sampler"), std::string::npos) << last_error();
    EXPECT_NE(last_error().find("random"), std::string::npos) << "lists the known samplers";
    EXPECT_EQ(call(nullptr, 4, 8, 8, 0, 0, 4, xy.data()), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(call("random", 0, 8, 8, 0, 0, 4, xy.data()), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("samples = 0"), std::string::npos) << last_error();
    EXPECT_EQ(call("random", 4, 0, 8, 0, 0, 4, xy.data()), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("width = 0"), std::string::npos) << last_error();
    EXPECT_EQ(call("random", 4, 8, 8, 8, 0, 4, xy.data()), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("(8, 0)"), std::string::npos) << last_error();
    EXPECT_EQ(call("random", 4, 8, 8, 0, 9, 4, xy.data()), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("(0, 9)"), std::string::npos) << last_error();
    EXPECT_EQ(call("random", 4, 8, 8, 0, 0, (1u << 20) + 1, xy.data()), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("count = 1048577"), std::string::npos) << last_error();
    EXPECT_EQ(call("random", 4, 8, 8, 0, 0, 4, nullptr), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("out_xy"), std::string::npos) << last_error();
    // Beyond `samples` is allowed: the sampler is defined for any index.
    EXPECT_EQ(call("random", 2, 8, 8, 7, 7, 4, xy.data()), STRATUM_OK) << last_error();
    EXPECT_EQ(last_error(), "");
}

TEST(SamplingApi, HemisphereWarpsGiveUnitVectorsAndTheirDensities) {
    constexpr uint32_t kCount = 64;
    std::vector<float> uv(2 * kCount), xyz(3 * kCount), pdf(kCount);
    for (uint32_t i = 0; i < kCount; ++i) {
        uv[2 * i] = static_cast<float>(i) / kCount;
        uv[2 * i + 1] = (static_cast<float>(i) + 0.5f) / kCount;
    }
    uv[2] = 1.0f;  // 1 is accepted (clamped below 1)
    for (const RegistryEntry& e : hemisphere_registry()) {
        SCOPED_TRACE(e.name);
        HemisphereDistribution d;
        ASSERT_TRUE(parse_hemisphere(e.name, &d));
        ASSERT_EQ(stratum_warp_hemisphere(e.name, uv.data(), kCount, xyz.data(), pdf.data()), STRATUM_OK)
            << last_error();
        for (uint32_t i = 0; i < kCount; ++i) {
            const Vec3 w{xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
            EXPECT_NEAR(length(w), 1.0f, 1e-5f) << i;
            EXPECT_GE(w.z, 0.0f) << i;
            EXPECT_EQ(pdf[i], hemisphere_pdf(d, w.z)) << i;
            if (i != 1) {  // uv[1].u was clamped
                const Vec3 expected = sample_hemisphere(d, Vec2{uv[2 * i], uv[2 * i + 1]});
                EXPECT_EQ(w.x, expected.x) << i;
                EXPECT_EQ(w.z, expected.z) << i;
            }
        }
        // pdf is optional
        EXPECT_EQ(stratum_warp_hemisphere(e.name, uv.data(), kCount, xyz.data(), nullptr), STRATUM_OK);
    }
}

TEST(SamplingApi, HemisphereWarpRejectsBadInputNamingTheIndex) {
    std::vector<float> uv = {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f};
    std::vector<float> xyz(9);
    EXPECT_EQ(stratum_warp_hemisphere("spiral", uv.data(), 3, xyz.data(), nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("spiral"), std::string::npos) << last_error();
    EXPECT_NE(last_error().find("cosine"), std::string::npos) << "lists the known distributions";
    uv[3] = std::numeric_limits<float>::quiet_NaN();
    EXPECT_EQ(stratum_warp_hemisphere("cosine", uv.data(), 3, xyz.data(), nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("uv[1].v = nan"), std::string::npos) << last_error();
    uv[3] = 0.4f;
    uv[4] = -0.25f;
    EXPECT_EQ(stratum_warp_hemisphere("uniform", uv.data(), 3, xyz.data(), nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("uv[2].u"), std::string::npos) << last_error();
    uv[4] = 1.5f;
    EXPECT_EQ(stratum_warp_hemisphere("uniform", uv.data(), 3, xyz.data(), nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("uv[2].u"), std::string::npos) << last_error();
    uv[4] = 0.5f;
    EXPECT_EQ(stratum_warp_hemisphere(nullptr, uv.data(), 3, xyz.data(), nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_warp_hemisphere("cosine", nullptr, 3, xyz.data(), nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_warp_hemisphere("cosine", uv.data(), 3, nullptr, nullptr),
              STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_warp_hemisphere("cosine", uv.data(), 3, xyz.data(), nullptr), STRATUM_OK);
}

TEST(SamplingApi, BlueNoiseTextureIsThePermutationOfRanksTheSamplerReads) {
    constexpr uint32_t kTexels = BlueNoiseSampler::kSize * BlueNoiseSampler::kSize;
    std::vector<float> texture(kTexels, -1.0f);
    ASSERT_EQ(stratum_bluenoise_texture(texture.data(), kTexels), STRATUM_OK) << last_error();
    // value = (rank + 0.5)/16384 exactly in float: every rank 0..16383 appears once.
    std::vector<int> seen(kTexels, 0);
    for (uint32_t i = 0; i < kTexels; ++i) {
        const float rank = texture[i] * float(kTexels) - 0.5f;
        ASSERT_EQ(rank, std::floor(rank)) << "texel " << i << " value " << texture[i];
        ASSERT_GE(rank, 0.0f);
        ASSERT_LT(rank, float(kTexels));
        ++seen[static_cast<size_t>(rank)];
    }
    for (uint32_t r = 0; r < kTexels; ++r) ASSERT_EQ(seen[r], 1) << "rank " << r;
    // Row-major, the sampler's own texture.
    const std::vector<uint32_t>& ranks = BlueNoiseSampler::ranks();
    for (uint32_t i = 0; i < kTexels; ++i) ASSERT_EQ(texture[i], BlueNoiseSampler::rank_to_value(ranks[i]));
}

TEST(SamplingApi, BlueNoiseTextureRejectsAWrongCountOrNull) {
    std::vector<float> texture(128 * 128 + 1);
    EXPECT_EQ(stratum_bluenoise_texture(texture.data(), 64 * 64), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("count = 4096"), std::string::npos) << last_error();
    EXPECT_EQ(stratum_bluenoise_texture(texture.data(), 128 * 128 + 1), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_EQ(stratum_bluenoise_texture(nullptr, 128 * 128), STRATUM_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_error().find("out is NULL"), std::string::npos) << last_error();
}
