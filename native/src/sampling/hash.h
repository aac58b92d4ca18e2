// Integer hashing: the source of decorrelation for every sampler. Pure functions.
// Decorrelating streams needs a real avalanche hash of (pixel, sample, dimension, seed);
// a linear combination of them correlates streams (Cycles #109907, research/samplers.md §5.1).
#pragma once

#include <cstdint>

namespace stratum {

// SplitMix64 finaliser (Steele, Lea, Flood 2014): full 64-bit avalanche.
constexpr uint64_t mix_bits(uint64_t v) {
    v ^= v >> 30;
    v *= 0xbf58476d1ce4e5b9ull;
    v ^= v >> 27;
    v *= 0x94d049bb133111ebull;
    v ^= v >> 31;
    return v;
}

// Hash of several 32-bit words: each word is mixed into the running state, so permuting the
// arguments changes the result (hash(1,2) != hash(2,1)).
// hash_words(a, b, c) == hash_more(hash_words(a, b), c): a caller hashing several tuples with a
// common prefix hashes the prefix once.
constexpr uint64_t hash_more(uint64_t h, uint32_t word) {
    return mix_bits(h ^ (static_cast<uint64_t>(word) + 0x632be59bd9b4e019ull));
}
template <typename... Words>
constexpr uint64_t hash_words(Words... words) {
    uint64_t h = 0x9e3779b97f4a7c15ull;
    ((h = hash_more(h, static_cast<uint32_t>(words))), ...);
    return h;
}

// Maps 32 random bits to [0,1): the top 24 bits give an exactly representable float < 1.
constexpr float bits_to_unit_float(uint32_t bits) { return static_cast<float>(bits >> 8) * 0x1p-24f; }

}  // namespace stratum
