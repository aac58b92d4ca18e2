// `zsobol`: screen-space blue-noise Sobol (Ahmed & Wonka 2020, "Screen-Space Blue-Noise
// Diffusion of Monte Carlo Sampling Error via Hierarchical Ordering of Pixels", SIGGRAPH Asia,
// §4–5; pbrt-v4 ZSobolSampler).
//
// | parameter | meaning |
// |-----------|---------|
// | samples   | rounded up to 2^L; a pixel owns an aligned block of 2^L indices |
// | width, height | number of base-4 Morton digits that are permuted |
// | seed      | keys the digit permutations and the Owen scrambles |
//
// One image-wide 2D Sobol sequence per dimension pair (d, d+1): the global index is
// Morton(x, y) << L | sample. Each base-4 digit of the Morton part is permuted by one of the 24
// permutations of {0..3}, chosen by a hash of the digits above it, its position, the pair and
// the seed (a base-4 Owen scramble of the pixel order), so the 4^t pixels of an aligned
// 2^t x 2^t square together own an aligned block of 4^t 2^L indices -- a (0, 2t+L, 2)-net,
// whose error is spread as blue noise over the square. The L sample bits get a nested binary
// scramble keyed by the pixel, so every aligned 2^m block of a pixel's samples is also an
// aligned index block (a (0,m,2)-net). The Sobol coordinates are Owen-scrambled with keys of
// (pair, seed) only, the same for all pixels (required for the joint nets).
// Sample indices >= 2^L start a new round with its own permutations. Indices use 32 bits:
// 2 log2(max(width, height)) + L <= 32 keeps the whole image in one sequence.
#pragma once

#include <array>
#include <cstdint>

#include "sampling/sampler.h"

namespace stratum {

class ZSobolSampler final : public Sampler {
public:
    explicit ZSobolSampler(const SamplerSettings& settings);

    float get_1d(const PixelSample& s, uint32_t dimension) const override;
    Vec2 get_2d(const PixelSample& s, uint32_t dimension) const override;

    // Global Sobol index of the sample for pair dimension & ~1, and the scrambled 32-bit fractions.
    uint32_t sobol_index(const PixelSample& s, uint32_t dimension) const;
    void get_2d_bits(const PixelSample& s, uint32_t dimension, uint32_t& x, uint32_t& y) const;
    uint32_t log2_samples() const { return log2_samples_; }

private:
    // The per-pair keys, which depend on the pair and the seed only, hashed once at construction
    // for the first kCachedPairs pairs (a path's dimensions rarely go beyond) and on demand after.
    static constexpr uint32_t kCachedPairs = 64;
    uint64_t round_key(uint32_t pair, uint64_t round) const;  // hash_words(pair, seed, round lo, hi)
    uint64_t value_key(uint32_t pair) const;                  // hash_words(pair, seed, 0x250b)

    uint32_t seed_;
    uint32_t log2_samples_ = 0;   // L
    uint32_t morton_digits_ = 0;  // base-4 digits of the Morton code that are permuted
    std::array<uint64_t, kCachedPairs> first_round_keys_{}, value_keys_{};
};

}  // namespace stratum
