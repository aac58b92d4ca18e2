// `random`: independent uniform samples (textbook §4.1; pbrt-v4 IndependentSampler).
//
// | parameter | meaning |
// |-----------|---------|
// | seed      | mixed into the key of every value |
//
// Each value is the first output of a PCG32 stream whose state and stream are a 64-bit hash of
// (pixel x, pixel y, sample index, dimension, seed), so values are independent across all four
// and random access costs one hash and one PCG step.
#pragma once

#include "sampling/hash.h"
#include "sampling/pcg32.h"
#include "sampling/sampler.h"

namespace stratum {

class IndependentSampler final : public Sampler {
public:
    explicit IndependentSampler(const SamplerSettings& settings) : seed_(settings.seed) {}

    float get_1d(const PixelSample& s, uint32_t dimension) const override {
        return value(s.sample_key, dimension);
    }
    // The pair is the two 1D values, so a dimension reads the same whether asked alone or in
    // its pair.
    Vec2 get_2d(const PixelSample& s, uint32_t dimension) const override {
        return {value(s.sample_key, dimension), value(s.sample_key, dimension + 1)};
    }

private:
    // hash_words(x, y, index, dimension, seed) = hash_more(hash_more(sample_key, dimension), seed).
    float value(uint64_t sample_key, uint32_t dimension) const {
        const uint64_t key = hash_more(hash_more(sample_key, dimension), seed_);
        return bits_to_unit_float(Pcg32(key, mix_bits(key ^ 0xda942042e4dd58b5ull)).next_u32());
    }
    uint32_t seed_;
};

}  // namespace stratum
