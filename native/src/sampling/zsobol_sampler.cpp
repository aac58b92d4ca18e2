#include "sampling/zsobol_sampler.h"

#include <algorithm>

#include "sampling/hash.h"
#include "sampling/sequences/morton.h"
#include "sampling/sequences/owen_hash.h"
#include "sampling/sequences/sobol.h"

namespace stratum {

ZSobolSampler::ZSobolSampler(const SamplerSettings& settings) : seed_(settings.seed) {
    while ((uint64_t{1} << log2_samples_) < settings.samples) ++log2_samples_;
    const uint32_t resolution = std::max({settings.width, settings.height, 1u});
    while ((uint64_t{1} << morton_digits_) < resolution) ++morton_digits_;
    for (uint32_t pair = 0; pair < kCachedPairs; ++pair) {
        first_round_keys_[pair] = hash_words(pair, seed_, 0u, 0u);
        value_keys_[pair] = hash_words(pair, seed_, 0x250bu);
    }
}

uint64_t ZSobolSampler::round_key(uint32_t pair, uint64_t round) const {
    if (round == 0 && pair < kCachedPairs) return first_round_keys_[pair];
    return hash_words(pair, seed_, static_cast<uint32_t>(round), static_cast<uint32_t>(round >> 32));
}

uint64_t ZSobolSampler::value_key(uint32_t pair) const {
    return pair < kCachedPairs ? value_keys_[pair] : hash_words(pair, seed_, 0x250bu);
}

uint32_t ZSobolSampler::sobol_index(const PixelSample& s, uint32_t dimension) const {
    const uint32_t L = log2_samples_;
    const uint32_t pair = dimension >> 1;
    const uint64_t sample_mask = (uint64_t{1} << L) - 1;
    const uint64_t round = L >= 32 ? 0 : uint64_t{s.index} >> L;
    const uint64_t key = round_key(pair, round);

    // Base-4 Owen scramble of the pixel order: digit t is permuted by a hash of the original
    // digits above it (t+1 .. ), its position and the key; the digits above morton_digits_
    // (pixels outside the stated resolution) are kept.
    const uint64_t morton = morton_encode(s.x, s.y);
    uint64_t permuted = morton;
    for (uint32_t t = 0; t < morton_digits_; ++t) {
        const uint64_t higher = morton >> (2 * t + 2);
        const auto digit = static_cast<uint32_t>((morton >> (2 * t)) & 3u);
        const uint32_t p = permute_base4_digit(digit, key ^ mix_bits(higher * 32 + t));
        permuted = (permuted & ~(uint64_t{3} << (2 * t))) | (uint64_t{p} << (2 * t));
    }
    // Nested binary scramble of the sample bits: bit j flipped by a function of bits > j.
    const auto sample_key = static_cast<uint32_t>(hash_words(
        static_cast<uint32_t>(key), static_cast<uint32_t>(morton), static_cast<uint32_t>(morton >> 32)));
    const uint64_t sample =
        nested_uniform_scramble(static_cast<uint32_t>(s.index & sample_mask), sample_key) & sample_mask;
    return static_cast<uint32_t>((permuted << L) | sample);
}

void ZSobolSampler::get_2d_bits(const PixelSample& s, uint32_t dimension, uint32_t& x, uint32_t& y) const {
    const uint32_t index = sobol_index(s, dimension);
    const uint64_t k = value_key(dimension >> 1);
    x = owen_scrambled_sobol32(index, 0, static_cast<uint32_t>(k));
    y = owen_scrambled_sobol32(index, 1, static_cast<uint32_t>(k >> 32));
}

Vec2 ZSobolSampler::get_2d(const PixelSample& s, uint32_t dimension) const {
    uint32_t x = 0, y = 0;
    get_2d_bits(s, dimension, x, y);
    return {bits_to_unit_float(x), bits_to_unit_float(y)};
}

float ZSobolSampler::get_1d(const PixelSample& s, uint32_t dimension) const {
    const uint32_t index = sobol_index(s, dimension);
    const uint64_t k = value_key(dimension >> 1);
    const uint32_t component = dimension & 1u;
    const auto key = static_cast<uint32_t>(component ? k >> 32 : k);
    return bits_to_unit_float(owen_scrambled_sobol32(index, component, key));
}

}  // namespace stratum
