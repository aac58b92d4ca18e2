// `sobol`: padded Owen-scrambled Sobol, per pixel (Burley 2020, "Practical Hash-based Owen
// Scrambling", JCGT 9(4): §4 nested uniform scrambling, §5 shuffling, §6 padding; pbrt-v4
// PaddedSobolSampler, Cycles sobol_burley.h).
//
// | parameter | meaning |
// |-----------|---------|
// | samples   | not used: any aligned block of 2^m samples of a pixel is a (0,m,2)-net |
// | seed      | mixed with the pixel and the dimension pair into every scramble key |
//
// Every 2D pair (d, d+1), d even, is its own 2D Sobol sequence (dimensions 0 and 1, a
// (0,2)-sequence): key = hash(pixel, d/2, seed); the sample index is shuffled by a nested
// uniform scramble keyed by it (aligned blocks of indices go to aligned blocks, so nets stay
// nets), then each coordinate is Owen-scrambled with its own key (Vegdahl's hash on reversed
// bits). A 1D dimension d is component d & 1 of pair d & ~1, so get_1d agrees with get_2d.
#pragma once

#include <cstdint>

#include "sampling/sampler.h"

namespace stratum {

class SobolSampler final : public Sampler {
public:
    explicit SobolSampler(const SamplerSettings& settings) : seed_(settings.seed) {}

    float get_1d(const PixelSample& s, uint32_t dimension) const override;
    Vec2 get_2d(const PixelSample& s, uint32_t dimension) const override;

    // The scrambled 32-bit fractions of pair dimension & ~1 (for exact net tests).
    void get_2d_bits(const PixelSample& s, uint32_t dimension, uint32_t& x, uint32_t& y) const;

private:
    uint32_t seed_;
};

}  // namespace stratum
