#include "sampling/sobol_sampler.h"

#include "sampling/hash.h"
#include "sampling/sequences/owen_hash.h"
#include "sampling/sequences/sobol.h"

namespace stratum {

namespace {

struct PairKeys {
    uint32_t shuffle, x, y;
};

PairKeys pair_keys(const PixelSample& s, uint32_t pair, uint32_t seed) {
    const uint64_t k = hash_more(hash_more(s.pixel_key, pair), seed);  // hash_words(x, y, pair, seed)
    return {static_cast<uint32_t>(k), static_cast<uint32_t>(k >> 32), static_cast<uint32_t>(mix_bits(k))};
}

}  // namespace

void SobolSampler::get_2d_bits(const PixelSample& s, uint32_t dimension, uint32_t& x, uint32_t& y) const {
    const PairKeys keys = pair_keys(s, dimension >> 1, seed_);
    const uint32_t index = nested_uniform_scramble(s.index, keys.shuffle);
    x = owen_scrambled_sobol32(index, 0, keys.x);
    y = owen_scrambled_sobol32(index, 1, keys.y);
}

Vec2 SobolSampler::get_2d(const PixelSample& s, uint32_t dimension) const {
    uint32_t x = 0, y = 0;
    get_2d_bits(s, dimension, x, y);
    return {bits_to_unit_float(x), bits_to_unit_float(y)};
}

float SobolSampler::get_1d(const PixelSample& s, uint32_t dimension) const {
    const PairKeys keys = pair_keys(s, dimension >> 1, seed_);
    const uint32_t index = nested_uniform_scramble(s.index, keys.shuffle);
    const uint32_t component = dimension & 1u;
    return bits_to_unit_float(owen_scrambled_sobol32(index, component, component ? keys.y : keys.x));
}

}  // namespace stratum
