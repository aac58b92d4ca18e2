// `lcg`: the "standard" sampler of the coursework (seed 001 §4.3.1): the minstd LCG with
// std::uniform_real_distribution, the default of most C++ programs.
//
// | parameter  | meaning                                                              |
// |------------|----------------------------------------------------------------------|
// | engine     | minstd_rand0: x ← 16807·x mod (2^31 − 1) (sequences/minstd.h)         |
// | seeding    | one engine per (pixel, sample, dimension, seed): state = 1 + H mod     |
// |            | (2^31 − 2), H = 64-bit avalanche hash of the five words (hash.h)      |
// | discard    | none: the hashed state is already uniform; the value is the engine's  |
// |            | first output 16807·state mod m (a bijection of the state)             |
// | mapping    | (x − 1)/(2^31 − 2), as uniform_real_distribution<float>, < 1          |
// | seed       | mixed into the hash                                                   |
//
// Unlike the coursework's one shared static engine (whose values depend on thread scheduling),
// every value is a pure function of (pixel, sample, dimension, seed). The engine is seeded by a
// real hash, never by a linear combination such as x + W·y + sample: minstd's first outputs of
// neighbouring seeds s, s + 1 differ by 16807/m ≈ 8e-6, so linearly seeded streams are almost
// identical (Cycles #109907; research/samplers.md pitfall 1). Each dimension has its own engine,
// so a pair (d, d+1) is not two consecutive minstd outputs, which lie on 2D lattice lines.
#pragma once

#include "sampling/sampler.h"

namespace stratum {

class LcgSampler final : public Sampler {
public:
    explicit LcgSampler(const SamplerSettings& settings) : seed_(settings.seed) {}

    float get_1d(const PixelSample& s, uint32_t dimension) const override;
    Vec2 get_2d(const PixelSample& s, uint32_t dimension) const override;

    // The engine state that starts the stream of one (pixel, sample, dimension).
    uint32_t initial_state(const PixelSample& s, uint32_t dimension) const;

private:
    uint32_t seed_;
};

}  // namespace stratum
