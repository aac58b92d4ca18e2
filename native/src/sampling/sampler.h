// The sampler interface. A sampler is a pure function of (pixel, sample index, dimension) for
// a fixed seed and sample count: the same arguments give the same value in any visiting order,
// so images are bit-identical for any thread count or tile order (DESIGN.md).
#pragma once

#include <cstdint>
#include <memory>

#include "core/math.h"

namespace stratum {

struct PixelSample {
    uint32_t x = 0, y = 0;  // pixel
    uint32_t index = 0;     // sample index within the pixel, 0 .. samples-1
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
