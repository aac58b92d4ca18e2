#include "texture/texture_building.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <cmath>
#include <functional>
#include <limits>
#include <type_traits>

namespace stratum {

namespace {

// The colour channels are the first ones other than alpha; grey images repeat their one channel.
struct ChannelMap {
    int colour[3] = {0, 0, 0};
    int alpha = -1;
    int count = 0;
};

ChannelMap channel_map(const StoredImage& image) {
    ChannelMap map;
    map.alpha = image.alpha_channel;
    map.count = image.channels;
    for (int c = 0, k = 0; c < image.channels && k < 3; ++c) {
        if (c != image.alpha_channel) map.colour[k++] = c;
    }
    if (image.channels - (image.alpha_channel >= 0 ? 1 : 0) < 3)
        map.colour[1] = map.colour[2] = map.colour[0];
    return map;
}

// One stored row as RGBA of the stored type; alpha missing reads the type's one.
template <typename T>
void expand_row(const T* src, const ChannelMap& map, uint32_t width, T one, T* rgba) {
    for (uint32_t x = 0; x < width; ++x, src += map.count, rgba += 4) {
        for (int k = 0; k < 3; ++k) rgba[k] = src[map.colour[k]];
        rgba[3] = map.alpha >= 0 ? src[map.alpha] : one;
    }
}

void unassociate(float* rgba, uint32_t width) {
    for (uint32_t x = 0; x < width; ++x, rgba += 4) {
        const float a = rgba[3];
        if (a > 0.0f) {
            const float inverse = 1.0f / a;
            for (int k = 0; k < 3; ++k) rgba[k] *= inverse;
        }
    }
}

bool finite_texel(const float* rgba) {
    return std::isfinite(rgba[0]) && std::isfinite(rgba[1]) && std::isfinite(rgba[2]) &&
           std::isfinite(rgba[3]);
}

// An sRGB-encoded channel whose decoding ((c + 0.055) / 1.055)^2.4 overflows: c above ~1.2e16,
// only in float images. Its scene-linear value is infinite, so it is a texel not finite after
// conversion although it is decoded only at lookup; the comparison keeps pow off the common path.
bool decodes_to_infinity(float encoded) {
    return encoded > 1e15f && !std::isfinite(srgb_texel_to_linear(encoded));
}

// Whether the texel's scene-linear value is finite: its stored value when it is scene linear, its
// decoded value when it is still sRGB-encoded.
bool finite_scene_linear(const float* rgba, bool srgb_encoded) {
    if (!finite_texel(rgba)) return false;
    return !srgb_encoded ||
           !(decodes_to_infinity(rgba[0]) || decodes_to_infinity(rgba[1]) || decodes_to_infinity(rgba[2]));
}

// Marks the row's texels that are not finite as stored: an OCIO transform may turn a NaN into a
// number (Blender 3.4's sRGB gives 0), which Cycles then renders, but the file still held it.
void mark_non_finite(const float* rgba, uint32_t width, std::vector<uint8_t>& stored_non_finite) {
    for (uint32_t x = 0; x < width; ++x, rgba += 4) stored_non_finite[x] = !finite_texel(rgba);
}

// Zeroes the texels not finite after conversion (Cycles' rule); counts those and the ones marked.
uint64_t replace_non_finite(float* rgba, uint32_t width, const std::vector<uint8_t>& stored_non_finite,
                            bool srgb_encoded) {
    uint64_t replaced = 0;
    for (uint32_t x = 0; x < width; ++x, rgba += 4) {
        const bool converted_finite = finite_scene_linear(rgba, srgb_encoded);
        if (!converted_finite) rgba[0] = rgba[1] = rgba[2] = rgba[3] = 0.0f;
        replaced += !converted_finite || stored_non_finite[x];
    }
    return replaced;
}

template <typename T>
uint64_t convert_rows(const StoredImage& image, const SceneLinearConversion& conversion, bool srgb_encoded,
                      float* out) {
    const ChannelMap map = channel_map(image);
    const uint32_t width = image.width, height = image.height;
    const size_t stride = static_cast<size_t>(width) * map.count;
    const T* stored = static_cast<const T*>(image.data);
    constexpr T one = std::is_floating_point_v<T> ? T(1) : std::numeric_limits<T>::max();
    // 16 rows per task: an 8192-wide row is 128 KiB of floats, so a task amortises its start.
    return tbb::parallel_reduce(
        tbb::blocked_range<uint32_t>(0, height, 16), uint64_t{0},
        [&](const tbb::blocked_range<uint32_t>& rows, uint64_t replaced) {
            std::vector<T> row_rgba(std::is_floating_point_v<T> ? 0 : static_cast<size_t>(width) * 4);
            std::vector<uint8_t> stored_non_finite(width, 0);
            for (uint32_t y = rows.begin(); y != rows.end(); ++y) {
                const uint32_t src_row = image.top_to_bottom ? height - 1 - y : y;
                float* dst = out + static_cast<size_t>(y) * width * 4;
                if constexpr (std::is_floating_point_v<T>) {
                    expand_row(stored + src_row * stride, map, width, one, dst);
                    if (image.associated_alpha) unassociate(dst, width);
                    mark_non_finite(dst, width, stored_non_finite);
                    conversion.apply(dst, width);
                } else {
                    expand_row(stored + src_row * stride, map, width, one, row_rgba.data());
                    conversion.apply(row_rgba.data(), dst, width);
                }
                replaced += replace_non_finite(dst, width, stored_non_finite, srgb_encoded);
            }
            return replaced;
        },
        std::plus<uint64_t>());
}

}  // namespace

SceneLinearTexels scene_linear_texels(const StoredImage& image,
                                      const SceneLinearConversion& conversion_asked) {
    SceneLinearTexels texels;
    texels.srgb_encoded = conversion_asked.is_srgb_curve();
    const SceneLinearConversion& conversion =
        texels.srgb_encoded ? conversion_to_scene_linear(nullptr, "Non-Color") : conversion_asked;
    texels.rgba.resize(static_cast<size_t>(image.width) * image.height * 4);
    switch (image.format) {
        case StoredFormat::U8:
            texels.replaced_texels =
                convert_rows<uint8_t>(image, conversion, texels.srgb_encoded, texels.rgba.data());
            break;
        case StoredFormat::U16:
            texels.replaced_texels =
                convert_rows<uint16_t>(image, conversion, texels.srgb_encoded, texels.rgba.data());
            break;
        case StoredFormat::F32:
            texels.replaced_texels =
                convert_rows<float>(image, conversion, texels.srgb_encoded, texels.rgba.data());
            break;
    }
    return texels;
}

}  // namespace stratum
