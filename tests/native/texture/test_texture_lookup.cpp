// Texture lookup (texture/texture.h) against Cycles' CPU image kernel conventions: texel
// centres at (i + 0.5)/w, closest = floor(u w), and the four extension modes. Values are exact
// (bilinear weights of 0.5 and 0.25 are exact in float).
#include <gtest/gtest.h>

#include "texture/texture.h"

using namespace stratum;

namespace {

// A 4x1 texture whose texel i has red = i + 1 (alpha 1).
Texture row_texture(TextureInterpolation interpolation, TextureExtension extension) {
    Texture t;
    t.width = 4;
    t.height = 1;
    t.rgba = {1, 0, 0, 1, 2, 0, 0, 1, 3, 0, 0, 1, 4, 0, 0, 1};
    t.interpolation = interpolation;
    t.extension = extension;
    return t;
}

float red(const Texture& t, float u, float v = 0.5f) { return texture_lookup(t, {u, v}).r; }

}  // namespace

TEST(TextureLookup, ClosestPicksTheTexelContainingUv) {
    const Texture t = row_texture(TextureInterpolation::Closest, TextureExtension::Repeat);
    EXPECT_EQ(red(t, 0.0f), 1.0f);
    EXPECT_EQ(red(t, 0.2499f), 1.0f);
    EXPECT_EQ(red(t, 0.25f), 2.0f);
    EXPECT_EQ(red(t, 0.99f), 4.0f);
}

TEST(TextureLookup, LinearIsExactAtTexelCentresAndAveragesBetweenThem) {
    const Texture t = row_texture(TextureInterpolation::Linear, TextureExtension::Extend);
    EXPECT_EQ(red(t, 0.125f), 1.0f);  // centre of texel 0
    EXPECT_EQ(red(t, 0.375f), 2.0f);  // centre of texel 1
    EXPECT_EQ(red(t, 0.25f), 1.5f);   // the boundary: halfway between the centres
    EXPECT_EQ(red(t, 0.3125f), 1.75f);
}

TEST(TextureLookup, LinearInTwoDimensionsWeighsFourTexels) {
    Texture t;
    t.width = t.height = 2;
    // Row 0 (bottom): 0, 1; row 1 (top): 2, 3.
    t.rgba = {0, 0, 0, 1, 1, 0, 0, 1, 2, 0, 0, 1, 3, 0, 0, 1};
    t.extension = TextureExtension::Extend;
    EXPECT_EQ(red(t, 0.5f, 0.5f), 1.5f);
    EXPECT_EQ(red(t, 0.25f, 0.75f), 2.0f);
    EXPECT_EQ(red(t, 0.75f, 0.25f), 1.0f);
}

TEST(TextureLookup, RepeatTilesAndWrapsTheBilinearNeighbours) {
    const Texture closest = row_texture(TextureInterpolation::Closest, TextureExtension::Repeat);
    EXPECT_EQ(red(closest, 1.3f), red(closest, 0.3f));
    EXPECT_EQ(red(closest, -0.1f), 4.0f);
    const Texture linear = row_texture(TextureInterpolation::Linear, TextureExtension::Repeat);
    EXPECT_EQ(red(linear, 0.0f), 2.5f);  // between texel 3 (4) and texel 0 (1)
}

TEST(TextureLookup, ExtendClampsToTheEdgeTexel) {
    const Texture closest = row_texture(TextureInterpolation::Closest, TextureExtension::Extend);
    EXPECT_EQ(red(closest, -3.0f), 1.0f);
    EXPECT_EQ(red(closest, 7.0f), 4.0f);
    const Texture linear = row_texture(TextureInterpolation::Linear, TextureExtension::Extend);
    EXPECT_EQ(red(linear, 0.0f), 1.0f);
    EXPECT_EQ(red(linear, 1.0f), 4.0f);
}

TEST(TextureLookup, ClipIsTransparentBlackOutsideAndFadesAtTheEdge) {
    const Texture closest = row_texture(TextureInterpolation::Closest, TextureExtension::Clip);
    const Rgba outside = texture_lookup(closest, {1.01f, 0.5f});
    EXPECT_EQ(outside.r, 0.0f);
    EXPECT_EQ(outside.a, 0.0f);
    EXPECT_EQ(red(closest, 0.99f), 4.0f);
    EXPECT_EQ(red(closest, 0.5f, 1.5f), 0.0f);
    const Texture linear = row_texture(TextureInterpolation::Linear, TextureExtension::Clip);
    // At u = 0 the left neighbour is outside: half of texel 0, alpha 0.5. Rows: the single
    // row is at v = 0.5 exactly, so only it contributes.
    const Rgba edge = texture_lookup(linear, {0.0f, 0.5f});
    EXPECT_EQ(edge.r, 0.5f);
    EXPECT_EQ(edge.a, 0.5f);
}

TEST(TextureLookup, MirrorReflectsEveryOtherTile) {
    const Texture closest = row_texture(TextureInterpolation::Closest, TextureExtension::Mirror);
    EXPECT_EQ(red(closest, 1.125f), 4.0f);   // texel 4 -> 3
    EXPECT_EQ(red(closest, 1.375f), 3.0f);   // texel 5 -> 2
    EXPECT_EQ(red(closest, -0.125f), 1.0f);  // texel -1 -> 0
    EXPECT_EQ(red(closest, -0.375f), 2.0f);  // texel -2 -> 1
    EXPECT_EQ(red(closest, 2.125f), 1.0f);   // texel 8 -> 0: period 2 tiles
    const Texture linear = row_texture(TextureInterpolation::Linear, TextureExtension::Mirror);
    EXPECT_EQ(red(linear, 1.0f), 4.0f);  // texels 3 and 4 -> 3: the mirrored edge is flat
}
