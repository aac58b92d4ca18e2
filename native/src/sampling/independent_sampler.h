// `random`: independent uniform samples (textbook §4.1; pbrt-v4 IndependentSampler).
//
// | parameter | meaning |
// |-----------|---------|
// | seed      | mixed into the key of every value |
//
// Each value is the top 24 bits of a 64-bit hash of (pixel x, pixel y, sample index, seed,
// dimension): the sample's key (PixelSample::sample_key) xor the seed's, then one SplitMix64
// finalisation with the dimension (hash_more), whose full avalanche makes values of different
// dimensions, samples and seeds independent for all practical purposes. Random access costs that
// one mix per value; a PCG stream seeded by the hash, as before, added three LCG steps and a mix
// without adding independence the hash had not already given.
#pragma once

#include "sampling/hash.h"
#include "sampling/sampler.h"

namespace stratum {

class IndependentSampler final : public Sampler {
public:
    explicit IndependentSampler(const SamplerSettings& settings) : seed_key_(hash_words(settings.seed)) {}

    float get_1d(const PixelSample& s, uint32_t dimension) const override { return value(s, dimension); }
    // The pair is the two 1D values, so a dimension reads the same whether asked alone or in
    // its pair.
    Vec2 get_2d(const PixelSample& s, uint32_t dimension) const override {
        return {value(s, dimension), value(s, dimension + 1)};
    }

private:
    float value(const PixelSample& s, uint32_t dimension) const {
        return bits_to_unit_float(
            static_cast<uint32_t>(hash_more(s.sample_key ^ seed_key_, dimension) >> 32));
    }
    uint64_t seed_key_;
};

}  // namespace stratum
