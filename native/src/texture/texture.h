// An image texture in render-ready form and its lookup, following Cycles' CPU image kernel
// (Cycles 3.4 / 5.0 intern/cycles/kernel/device/cpu/image.h, read for this file):
//
// | parameter     | meaning                                                              |
// |---------------|----------------------------------------------------------------------|
// | rgba          | linear (scene_linear or data) RGBA floats, straight alpha            |
// | rows          | row 0 is the BOTTOM of the picture: v = 0 is the bottom edge, as     |
// |               | Blender's UV space and Image.pixels, and as Cycles stores images     |
// | interpolation | Closest: texel floor(u w), floor(v h); Linear: bilinear between the  |
// |               | texel centres (i + 0.5)/w, i.e. x = u w - 0.5 before the floor       |
// | srgb_encoded  | the RGB of rgba are sRGB-encoded (an sRGB image): the lookup decodes |
// |               | after interpolating, negatives to 0, as Cycles' compress_as_srgb     |
// | extension     | Repeat (periodic), Extend (clamp to the edge texel), Clip (texels    |
// |               | outside the image are transparent black, each one separately in the |
// |               | bilinear sum), Mirror (reflected every other tile: -1 -> 0, w -> w-1)|
#pragma once

#include <cstdint>
#include <vector>

#include "core/math.h"
#include "core/uninitialized_allocator.h"

namespace stratum {

enum class TextureInterpolation : int32_t { Closest = 0, Linear = 1 };
enum class TextureExtension : int32_t { Repeat = 0, Extend = 1, Clip = 2, Mirror = 3 };

struct Rgba {
    float r = 0, g = 0, b = 0, a = 0;
};

struct Texture {
    uint32_t width = 0, height = 0;
    UninitializedVector<float> rgba;  // width*height*4, row 0 at v = 0 (bottom)
    TextureInterpolation interpolation = TextureInterpolation::Linear;
    TextureExtension extension = TextureExtension::Repeat;
    uint64_t replaced_texels = 0;  // texels that were NaN or infinite, now (0, 0, 0, 0)
    bool srgb_encoded = false;     // RGB holds sRGB-encoded values, decoded after interpolation

    // The texel in column x (left to right) and row y (bottom to top); both in range.
    Rgba texel(uint32_t x, uint32_t y) const {
        const float* p = &rgba[(static_cast<size_t>(y) * width + x) * 4];
        return {p[0], p[1], p[2], p[3]};
    }
};

// The texture's value at UV (u, v): u left to right, v bottom to top, [0,1]^2 one tile.
Rgba texture_lookup(const Texture& texture, Vec2 uv);

// The same lookup before the sRGB decoding, with each texel's colour multiplied by its alpha
// before interpolating when `associate` (Cycles stores colour images associated and interpolates
// them so: svm/image.h); texture_lookup(t, uv) = texture_decode(t, texture_lookup_encoded(t, uv,
// false)).
Rgba texture_lookup_encoded(const Texture& texture, Vec2 uv, bool associate);
// Decodes an interpolated value of an sRGB-encoded texture to linear (alpha is not encoded); the
// value itself for other textures.
Rgba texture_decode(const Texture& texture, Rgba value);

}  // namespace stratum
