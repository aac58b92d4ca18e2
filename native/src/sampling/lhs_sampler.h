// `lhs`: Latin hypercube / N-rooks sampling (textbook 003 §4.2; McKay, Beckman, Conover 1979;
// Shirley 1991).
//
// | parameter | meaning                                                                    |
// |-----------|----------------------------------------------------------------------------|
// | samples   | spp: the number of 1D strata of every dimension                              |
// | shuffle   | sample i → stratum π_d(i mod spp), π_d a keyed bijection of [0, spp)         |
// |           | (permute_index), keyed by (pixel, dimension, i / spp, seed)                 |
// | jitter    | uniform within the stratum, from a hash of (pixel, sample, dimension, seed)  |
//
// Every dimension is stratified on its own and the permutations of different dimensions are
// independent, so any 2D projection is an N-rooks pattern: each row and each column of the
// spp × spp grid holds exactly one sample. Indices ≥ spp start a new, independently shuffled
// block of spp.
#pragma once

#include "sampling/sampler.h"

namespace stratum {

// The value of dimension `dimension` of sample s in a Latin hypercube of `spp` points.
float latin_hypercube_value(const PixelSample& s, uint32_t dimension, uint32_t spp, uint32_t seed);
// Its stratum in [0, spp).
uint32_t latin_hypercube_stratum(const PixelSample& s, uint32_t dimension, uint32_t spp, uint32_t seed);

class LhsSampler final : public Sampler {
public:
    explicit LhsSampler(const SamplerSettings& settings)
        : spp_(settings.samples > 0 ? settings.samples : 1), seed_(settings.seed) {}

    float get_1d(const PixelSample& s, uint32_t dimension) const override {
        return latin_hypercube_value(s, dimension, spp_, seed_);
    }
    Vec2 get_2d(const PixelSample& s, uint32_t dimension) const override {
        return {get_1d(s, dimension), get_1d(s, dimension + 1)};
    }

private:
    uint32_t spp_, seed_;
};

}  // namespace stratum
