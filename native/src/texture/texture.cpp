#include "texture/texture.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "texture/color_conversion.h"

namespace stratum {

namespace {

// Integer part (floor) and fraction of x.
float split_floor(float x, int* ix) {
    const float f = std::floor(x);
    *ix = static_cast<int>(f);
    return x - f;
}

int wrap_periodic(int i, int n) {
    const int m = i % n;
    return m < 0 ? m + n : m;
}

int wrap_clamp(int i, int n) { return std::clamp(i, 0, n - 1); }

// Tiles alternate between the image and its reflection: ..., 1, 0 | 0, 1, ..., n-1 | n-1, ...
int wrap_mirror(int i, int n) {
    const int m = std::abs(i + (i < 0 ? 1 : 0)) % (2 * n);
    return m >= n ? 2 * n - m - 1 : m;
}

// Index i into [0, n) under `extension`; -1 when Clip leaves the image.
int wrap(int i, int n, TextureExtension extension) {
    switch (extension) {
        case TextureExtension::Repeat:
            return wrap_periodic(i, n);
        case TextureExtension::Extend:
            return wrap_clamp(i, n);
        case TextureExtension::Mirror:
            return wrap_mirror(i, n);
        case TextureExtension::Clip:
            break;
    }
    return (i < 0 || i >= n) ? -1 : i;
}

Rgba texel_or_zero(const Texture& t, int x, int y) {
    if (x < 0 || y < 0) return {};
    return t.texel(static_cast<uint32_t>(x), static_cast<uint32_t>(y));
}

// A texel with its colour multiplied by its alpha (Cycles' associated storage) when `associate`.
Rgba associated(Rgba v, bool associate) {
    if (associate) v = {v.r * v.a, v.g * v.a, v.b * v.a, v.a};
    return v;
}

void accumulate(Rgba* sum, Rgba v, float w) {
    sum->r += w * v.r;
    sum->g += w * v.g;
    sum->b += w * v.b;
    sum->a += w * v.a;
}

}  // namespace

// Texels whose decoding is infinite were replaced at load (texture_building.h); the rounding of
// bilinear weights can still carry a value an ulp past the last one that decodes finite: saturate.
Rgba texture_decode(const Texture& t, Rgba v) {
    if (!t.srgb_encoded) return v;
    const auto decode = [](float c) {
        return std::min(srgb_texel_to_linear(c), std::numeric_limits<float>::max());
    };
    return {decode(v.r), decode(v.g), decode(v.b), v.a};
}

Rgba texture_lookup(const Texture& t, Vec2 uv) {
    return texture_decode(t, texture_lookup_encoded(t, uv, false));
}

Rgba texture_lookup_encoded(const Texture& t, Vec2 uv, bool associate) {
    const int w = static_cast<int>(t.width), h = static_cast<int>(t.height);
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return {};
    int ix = 0, iy = 0;
    if (t.interpolation == TextureInterpolation::Closest) {
        split_floor(uv.x * static_cast<float>(w), &ix);
        split_floor(uv.y * static_cast<float>(h), &iy);
        return associated(texel_or_zero(t, wrap(ix, w, t.extension), wrap(iy, h, t.extension)), associate);
    }
    // Texel i covers [i, i+1) in x = u w and is centred at i + 0.5: shifting by 0.5 puts the
    // two neighbours at floor(x) and floor(x) + 1 with weight fraction(x).
    const float tx = split_floor(uv.x * static_cast<float>(w) - 0.5f, &ix);
    const float ty = split_floor(uv.y * static_cast<float>(h) - 0.5f, &iy);
    const int x0 = wrap(ix, w, t.extension), x1 = wrap(ix + 1, w, t.extension);
    const int y0 = wrap(iy, h, t.extension), y1 = wrap(iy + 1, h, t.extension);
    Rgba sum;
    accumulate(&sum, associated(texel_or_zero(t, x0, y0), associate), (1.0f - tx) * (1.0f - ty));
    accumulate(&sum, associated(texel_or_zero(t, x1, y0), associate), tx * (1.0f - ty));
    accumulate(&sum, associated(texel_or_zero(t, x0, y1), associate), (1.0f - tx) * ty);
    accumulate(&sum, associated(texel_or_zero(t, x1, y1), associate), tx * ty);
    return sum;
}

}  // namespace stratum
