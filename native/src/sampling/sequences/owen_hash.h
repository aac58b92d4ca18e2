// Base-2 Owen scrambling by hashing (Laine & Karras 2011; Burley 2020, "Practical Hash-based
// Owen Scrambling", JCGT 9(4), §3–4; Vegdahl 2021's improved hash). Pure sequence math.
//
// A nested uniform (Owen) scramble flips each bit of x by a random function of the more
// significant bits. On the bit-reversed value "more significant" becomes "less significant",
// and a hash whose output bit k depends only on input bits <= k (xor with x times an even
// constant, adding a constant, multiplying by an odd constant: all carry upwards only, and all
// are invertible) is then such a scramble. So owen(x) = reverse(hash(reverse(x))) is a bijection
// of 32-bit words that maps every aligned block [k 2^m, (k+1) 2^m) onto an aligned block, and
// applied to a coordinate it preserves (t,m,s)-nets.
#pragma once

#include <cstdint>

namespace stratum {

constexpr uint32_t reverse_bits32(uint32_t v) {
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
    v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
    return (v >> 16) | (v << 16);
}

// Vegdahl 2021 ("Building a better LK hash"): the Laine–Karras construction with constants of
// better avalanche than Burley's Listing 1, applied to reversed bits.
constexpr uint32_t vegdahl_permutation(uint32_t x, uint32_t seed) {
    x ^= x * 0x3d20adeau;
    x += seed;
    x *= (seed >> 16) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}

// Owen scramble of a 32-bit fraction (or of a sample index): bit k of the result is bit k of x
// flipped by a function of bits > k of x and of the seed.
constexpr uint32_t nested_uniform_scramble(uint32_t x, uint32_t seed) {
    return reverse_bits32(vegdahl_permutation(reverse_bits32(x), seed));
}

}  // namespace stratum
