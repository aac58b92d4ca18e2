// Morton (Z-order) codes and base-4 digit permutations for screen-space blue-noise Sobol
// (Ahmed & Wonka 2020, "Screen-Space Blue-Noise Diffusion of Monte Carlo Sampling Error via
// Hierarchical Ordering of Pixels", §4). Pure sequence math.
#pragma once

#include <array>
#include <cstdint>

#include "sampling/hash.h"

namespace stratum {

// Spreads the 32 bits of v to the even bit positions of a 64-bit word.
constexpr uint64_t spread_bits(uint32_t v) {
    uint64_t x = v;
    x = (x | (x << 16)) & 0x0000ffff0000ffffull;
    x = (x | (x << 8)) & 0x00ff00ff00ff00ffull;
    x = (x | (x << 4)) & 0x0f0f0f0f0f0f0f0full;
    x = (x | (x << 2)) & 0x3333333333333333ull;
    x = (x | (x << 1)) & 0x5555555555555555ull;
    return x;
}

// Morton code: bit i of x goes to bit 2i, bit i of y to bit 2i+1, so each base-4 digit of the
// code is one level of a quadtree over the pixels (pixels sharing the higher digits form an
// aligned 2^k x 2^k square).
constexpr uint64_t morton_encode(uint32_t x, uint32_t y) { return spread_bits(x) | (spread_bits(y) << 1); }

// All 24 permutations of {0,1,2,3}, generated in lexicographic order (Lehmer code).
constexpr std::array<std::array<uint8_t, 4>, 24> make_base4_permutations() {
    std::array<std::array<uint8_t, 4>, 24> perms{};
    for (uint32_t p = 0; p < 24; ++p) {
        std::array<uint8_t, 4> left{0, 1, 2, 3};
        uint32_t n = 4, code = p, fact = 6;
        for (uint32_t i = 0; i < 4; ++i) {
            const uint32_t pick = code / fact;
            code %= fact;
            perms[p][i] = left[pick];
            for (uint32_t j = pick; j + 1 < n; ++j) left[j] = left[j + 1];
            --n;
            if (n > 0) fact /= n;
        }
    }
    return perms;
}

inline constexpr std::array<std::array<uint8_t, 4>, 24> kBase4Permutations = make_base4_permutations();

// One of the 24 permutations of a base-4 digit, chosen uniformly by a 64-bit key.
constexpr uint32_t permute_base4_digit(uint32_t digit, uint64_t key) {
    return kBase4Permutations[(mix_bits(key) >> 40) % 24][digit];
}

}  // namespace stratum
