// `bluenoise`: the coursework's blue-noise texture sampler (seed 001 §4.3.5; Georgiev & Fajardo
// 2016, "Blue-noise dithered sampling"): every value is a texel of one 128 × 128 void-and-cluster
// rank texture (sequences/void_and_cluster.h) read at the pixel's position plus an offset per
// (dimension, sample), so for every (dimension, sample) neighbouring pixels read neighbouring
// texels and the per-pixel values form a blue-noise image.
//
// | parameter | meaning                                                                      |
// |-----------|------------------------------------------------------------------------------|
// | texture   | 128², σ = 1.5, 10 % initial ones, PCG32 seed kTextureSeed; generated on first  |
// |           | use (thread-safe static, ~1 s), identical on every run                         |
// | value     | (rank + 0.5)/16384: the 16384 midpoints of [0,1), mean exactly 1/2, max        |
// |           | 16383.5/16384 < 1 (exact in float)                                            |
// | texel     | column = (x + sx + i·kx) mod 128, row = (y + sy + i·ky) mod 128               |
// | lookup    | shift (sx, sy) and odd strides (kx, ky), 7 hashed bits each, per               |
// |           | (dimension, block i / 128, seed)                                               |
// | seed      | only through the lookup; the texture itself is fixed                          |
//
// The coursework reads at (x + 99523·d + 2399·i + 2549·depth, y + 100937·d + 1091·i + 133337·depth)
// mod 128 (its fig. 34; our dimension index already encodes the bounce, dimensions.h). We keep
// the form "pixel + offset + i·stride" and hash the constants instead, for three reasons:
//  * with fixed constants two dimensions d, d' are read at the same lag (d − d')·(99523, 100937)
//    for every sample and pixel, so they are correlated by the texture's autocorrelation at that
//    lag (|r| ~ 1/128; measured 0.016 over 32² pixels × 64 samples, beyond the 4/√N the generic
//    sampler tests allow). Strides that differ per dimension make the lag change with i;
//  * an odd stride has period exactly 128 in each axis, so a pixel's 128 samples of a block read
//    128 distinct texels, and the per-block hash keeps block b + 1 from repeating block b (fixed
//    constants repeat every 128 samples);
//  * the seed changes the image (the texture is fixed).
// For every (dimension, sample) the values across pixels are the texture, toroidally shifted:
// blue noise in screen space. A pixel's samples within one dimension are texels along a line,
// not a stratified set: the error is distributed as blue noise across pixels, not reduced per
// pixel (research/samplers.md §4), and the pattern repeats every 128 pixels.
#pragma once

#include <cstdint>
#include <vector>

#include "sampling/sampler.h"

namespace stratum {

class BlueNoiseSampler final : public Sampler {
public:
    static constexpr uint32_t kSize = 128;
    static constexpr double kSigma = 1.5;
    static constexpr double kInitialFraction = 0.1;
    static constexpr uint64_t kTextureSeed = 0x626c75656e6f6973ull;

    explicit BlueNoiseSampler(const SamplerSettings& settings) : seed_(settings.seed) {}

    float get_1d(const PixelSample& s, uint32_t dimension) const override {
        return rank_to_value(ranks()[texel(s, dimension)]);
    }
    Vec2 get_2d(const PixelSample& s, uint32_t dimension) const override {
        return {get_1d(s, dimension), get_1d(s, dimension + 1)};
    }

    // Row-major index (row·128 + column) of the texel that supplies (s, dimension).
    uint32_t texel(const PixelSample& s, uint32_t dimension) const;

    // The rank texture, generated once per process.
    static const std::vector<uint32_t>& ranks();
    static constexpr float rank_to_value(uint32_t rank) {
        return (static_cast<float>(rank) + 0.5f) * (1.0f / static_cast<float>(kSize * kSize));
    }

private:
    uint32_t seed_;
};

}  // namespace stratum
