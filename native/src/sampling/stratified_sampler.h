// `stratified`: jittered sampling, one 2D grid per dimension pair (textbook 003 §4.2;
// pbrt-v4 StratifiedSampler).
//
// | parameter | meaning                                                                      |
// |-----------|------------------------------------------------------------------------------|
// | samples   | spp: the number of strata of every pair (or of every 1D dimension)            |
// | grid      | nx × ny = spp with ny the largest divisor ≤ √spp, if nx ≤ 2·ny (square spp:   |
// |           | √spp × √spp; 2^(2k+1): 2^(k+1) × 2^k); otherwise (3, 5, 7, 11, 14, ...) the   |
// |           | ceil grid nx = ⌈√spp⌉, ny = ⌈spp/nx⌉ of which a random subset of spp cells is |
// |           | used, one sample each (strata_grid)                                           |
// | shuffle   | sample i → cell π(i mod spp), π a keyed bijection of the nx·ny cells           |
// |           | (permute_index), keyed by (pixel, pair, i / spp, seed)                        |
// | jitter    | uniform within the cell, from a hash of (pixel, sample, dimension, seed)       |
// | 1D pairs  | pairs the named layout fills with two 1D quantities (dimensions.h: time,       |
// |           | light choice + roulette, BSDF lobe) get 1D strata of spp per dimension, i.e.   |
// |           | the `lhs` values (latin_hypercube_value)                                       |
//
// The sampler interface demands get_1d(d) == get_2d(d & ~1)[d & 1], so the choice between a 2D
// grid and 1D strata is made per pair from the layout rather than per call as in pbrt.
// Sample indices ≥ spp start a new, independently shuffled stratification per block of spp.
#pragma once

#include <bit>
#include <cstdint>

#include "sampling/dimensions.h"
#include "sampling/hash.h"
#include "sampling/sampler.h"

namespace stratum {

// A keyed bijection of [0, n) (pbrt-v4's PermutationElement idea; Kensler 2013, "Correlated
// Multi-Jittered Sampling", §3): a keyed bijection of [0, 2^b), 2^b ≥ n > 2^(b−1), made of four
// rounds of invertible steps on b-bit words (xor with a round key, multiply by an odd number,
// xor-shift right, add), applied repeatedly until the value falls below n ("cycle walking": the
// walk from i < n ends at the next element of i's cycle inside [0, n), so the map stays a
// bijection; expected walks < 2). Round keys come from SplitMix64 of the key. Our own rounds.
constexpr uint32_t permute_index(uint32_t i, uint32_t n, uint64_t key) {
    if (n <= 1) return 0;
    const int bits = std::bit_width(n - 1);
    const uint32_t mask = bits >= 32 ? ~0u : (1u << bits) - 1u;
    const int shift = (bits + 1) / 2, shift2 = bits - shift > 1 ? bits - shift : 1;
    uint64_t round_key[4];
    for (uint64_t& k : round_key) k = key = mix_bits(key + 0x9e3779b97f4a7c15ull);
    do {
        for (const uint64_t k : round_key) {
            const auto a = static_cast<uint32_t>(k), b = static_cast<uint32_t>(k >> 32);
            i = (i ^ a) & mask;
            i = (i * (b | 1u)) & mask;
            i ^= i >> shift;
            i = (i + (a >> 16)) & mask;
            i = (i * ((a >> 5) | 1u)) & mask;
            i ^= i >> shift2;
        }
    } while (i >= n);
    return i;
}

// A value in stratum `cell` of n equal 1D strata: (cell + jitter)/n with jitter from the top 24
// bits of `bits`, rounded to a float that provably lies in [cell/n, (cell+1)/n) (rounding alone
// can cross a stratum boundary) and is < 1.
float jittered_in_stratum(uint32_t cell, uint32_t n, uint32_t bits);

struct StrataGrid {
    uint32_t nx = 1, ny = 1;  // nx·ny ≥ spp; == spp when spp factors with aspect ≤ 2
};
constexpr StrataGrid strata_grid(uint32_t spp) {
    if (spp <= 1) return {1, 1};
    uint32_t ny = 1;
    for (uint32_t k = 1; static_cast<uint64_t>(k) * k <= spp; ++k)
        if (spp % k == 0) ny = k;
    const uint32_t nx = spp / ny;
    if (nx <= 2 * ny) return {nx, ny};
    uint32_t cx = 1;
    while (static_cast<uint64_t>(cx) * cx < spp) ++cx;
    return {cx, (spp + cx - 1) / cx};
}

// True when the named layout puts two 1D quantities (or one and an unused slot) in the pair that
// starts at even dimension `d`: (time, unused), (light choice, Russian roulette), (lobe, unused).
constexpr bool pair_holds_1d_quantities(uint32_t d) {
    static_assert(kDimFilter % 2 == 0 && kDimLens % 2 == 0 && kDimTime % 2 == 0);
    static_assert(kCameraDimensions % 2 == 0 && kBounceStride % 2 == 0);
    static_assert(kDimLightChoice % 2 == 0 && kDimRussianRoulette == kDimLightChoice + 1);
    static_assert(kDimLightPoint % 2 == 0 && kDimBsdfDirection % 2 == 0 && kDimBsdfLobe % 2 == 0);
    d &= ~1u;
    if (d < kCameraDimensions) return d == kDimTime;
    const uint32_t r = (d - kCameraDimensions) % kBounceStride;
    return r == kDimLightChoice || r == kDimBsdfLobe;
}

class StratifiedSampler final : public Sampler {
public:
    explicit StratifiedSampler(const SamplerSettings& settings);

    float get_1d(const PixelSample& s, uint32_t dimension) const override;
    Vec2 get_2d(const PixelSample& s, uint32_t dimension) const override;

    StrataGrid grid() const { return grid_; }
    // The grid cell (cx + nx·cy) of sample s in the pair starting at even `dimension`.
    uint32_t cell(const PixelSample& s, uint32_t dimension) const;

private:
    uint32_t spp_, seed_;
    StrataGrid grid_;
};

}  // namespace stratum
