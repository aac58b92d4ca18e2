// Hash-driven permutations of {0, ..., n-1} evaluated one element at a time, for scrambling
// base-b digits (random digit permutation, base-b Owen scrambling) and for the base-4 digit
// permutations of ZSobol. Pure sequence math.
//
// permutation_element(i, n, key) is the image of i under a permutation chosen by `key`. It is a
// bijection of [0, n) for every key: a keyed bijection of the w-bit integers (w = bits of n-1)
// built only from invertible steps (xor with a key word, multiplication by an odd constant,
// xor with a right shift, all modulo 2^w), iterated ("cycle walking") until the value falls
// back into [0, n), then a keyed rotation modulo n. Cycle walking keeps bijectivity: following
// the w-bit permutation's cycle from an element of [0, n) to the next element of [0, n) is the
// induced permutation of [0, n). Idea after Kensler 2013 (Pixar TM 13-01, §3); constants ours.
#pragma once

#include <cstdint>

#include "sampling/hash.h"

namespace stratum {

constexpr uint32_t permutation_element(uint32_t i, uint32_t n, uint64_t key) {
    if (n <= 1) return 0;
    uint32_t mask = n - 1;
    mask |= mask >> 1;
    mask |= mask >> 2;
    mask |= mask >> 4;
    mask |= mask >> 8;
    mask |= mask >> 16;
    const uint64_t k = mix_bits(key ^ 0x2545f4914f6cdd1dull);
    const auto k0 = static_cast<uint32_t>(k), k1 = static_cast<uint32_t>(k >> 32);
    const uint32_t odd = (k1 | 1u);
    do {
        i ^= k0;
        i = (i * 0x9e3779b1u) & mask;
        i ^= i >> 3;
        i = (i * odd) & mask;
        i ^= (k0 >> 11) & mask;
        i ^= i >> 1;
        i = (i * 0x85ebca77u) & mask;
        i ^= (k1 >> 7) & mask;
        i ^= i >> 5;
        i = (i * 0xc2b2ae3du) & mask;
        i ^= i >> 2;
    } while (i >= n);
    return static_cast<uint32_t>((i + k1 % n) % n);
}

}  // namespace stratum
