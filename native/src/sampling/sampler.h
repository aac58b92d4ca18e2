// The sampler interface. A sampler is a pure function of (pixel, sample index, dimension) for
// a fixed seed and sample count: the same arguments give the same value in any visiting order,
// so images are bit-identical for any thread count or tile order (DESIGN.md).
#pragma once

#include <cstdint>
#include <memory>

#include "core/math.h"
#include "sampling/hash.h"

namespace stratum {

// One sample of one pixel, with its hash keys computed once: samplers that key every value by
// the pixel or the sample continue from these (hash_more) rather than hash them again per value.
// The members are const, so a key cannot fall out of step with its pixel or index.
struct PixelSample {
    PixelSample(uint32_t pixel_x, uint32_t pixel_y, uint32_t sample_index)
        : x(pixel_x),
          y(pixel_y),
          index(sample_index),
          pixel_key(hash_words(pixel_x, pixel_y)),
          sample_key(hash_more(pixel_key, sample_index)) {}
    const uint32_t x, y;        // pixel
    const uint32_t index;       // sample index within the pixel, 0 .. samples-1
    const uint64_t pixel_key;   // hash_words(x, y)
    const uint64_t sample_key;  // hash_words(x, y, index)
};

struct SamplerSettings {
    uint32_t samples = 1;  // samples per pixel the render will take (stratified samplers use it)
    uint32_t seed = 0;
    uint32_t width = 1, height = 1;
};

class Sampler {
public:
    virtual ~Sampler() = default;
    // Value of one dimension, in [0,1).
    virtual float get_1d(const PixelSample& s, uint32_t dimension) const = 0;
    // Values of the pair (dimension, dimension + 1), in [0,1)^2; `dimension` is even.
    virtual Vec2 get_2d(const PixelSample& s, uint32_t dimension) const = 0;
};

}  // namespace stratum
