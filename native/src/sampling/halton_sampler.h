// `halton`, `halton_rd`, `halton_owen`: the Halton sequence, image-wide, with a per-pixel index
// offset (Halton 1960; pbrt-v4 §8.6 "Halton Sampler"; Owen 2017, "A randomized Halton
// algorithm in R", §3 for the random digit permutations; pbrt-v4 §8.6.3 for base-b Owen).
//
// | parameter | meaning |
// |-----------|---------|
// | width, height | size the pixel tile: 2^j >= min(width, 128), 3^k >= min(height, 128) |
// | samples   | not used: the sequence is progressive (any prefix of 2^j'3^k' samples is stratified) |
// | seed      | with the pixel, picks where in its index list a pixel starts; keys the digit permutations
// (`_rd`, `_owen`) |
//
// Dimensions 0 and 1 (the pixel filter offset) use bases 2 and 3, dimension d >= 2 the prime
// kPrimes[2 + (d-2) mod (kPrimeCount-2)], so bases 2 and 3 never return in higher dimensions.
// The digit map is the only difference between the three samplers:
//   none:           digits as they are;
//   permute digits: one keyed permutation of [0, b) per dimension, applied to every one of the
//                   digit_count(b) digits, trailing zeros included (research pitfall 4);
//   owen:           each digit permuted by a permutation keyed by (dimension, seed, position,
//                   the output digits above it): base-b Owen scrambling, never a base-2 hash on
//                   an odd base (pitfall 3).
#pragma once

#include <cstdint>

#include "sampling/sampler.h"

namespace stratum {

enum class HaltonRandomization { None, PermuteDigits, Owen };

class HaltonSampler : public Sampler {
public:
    HaltonSampler(const SamplerSettings& settings, HaltonRandomization randomization);

    float get_1d(const PixelSample& s, uint32_t dimension) const override;
    Vec2 get_2d(const PixelSample& s, uint32_t dimension) const override {
        return {get_1d(s, dimension), get_1d(s, dimension + 1)};
    }

    // The index in the image-wide Halton sequence that sample s.index of pixel (s.x, s.y) uses.
    uint64_t halton_index(const PixelSample& s) const;
    uint32_t tile_width() const { return scale2_; }   // 2^j
    uint32_t tile_height() const { return scale3_; }  // 3^k

private:
    HaltonRandomization randomization_;
    uint32_t seed_;
    uint32_t exponent2_ = 0, exponent3_ = 0;  // j, k
    uint32_t scale2_ = 1, scale3_ = 1;        // 2^j, 3^k
    uint64_t stride_ = 1;                     // 2^j 3^k: indices per pixel per sample
    uint64_t crt_weight2_ = 0, crt_weight3_ = 0;
};

class PlainHaltonSampler final : public HaltonSampler {
public:
    explicit PlainHaltonSampler(const SamplerSettings& s) : HaltonSampler(s, HaltonRandomization::None) {}
};

class PermutedHaltonSampler final : public HaltonSampler {
public:
    explicit PermutedHaltonSampler(const SamplerSettings& s)
        : HaltonSampler(s, HaltonRandomization::PermuteDigits) {}
};

class OwenHaltonSampler final : public HaltonSampler {
public:
    explicit OwenHaltonSampler(const SamplerSettings& s) : HaltonSampler(s, HaltonRandomization::Owen) {}
};

}  // namespace stratum
