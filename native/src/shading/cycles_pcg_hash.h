// The integer hash Cycles 5.0 hashes Voronoi cells with (util/hash.h, hash_pcg{2,3,4}d_i and
// hash_int{2,3,4}_to_float{2,3,4}): Jarzynski and Olano's PCG-style 2D/3D/4D hashes ("Hash
// Functions for GPU Rendering", JCGT 2020) on signed 32-bit integers, keeping the low 31 bits, and
// a hash mapped to [0, 1] by * 2^-31. Blender 3.x and 4.0-4.5 hash cells with lookup3 instead
// (cycles_hash.h); a mode of the Voronoi node picks which. Signed overflow wraps (done here in
// unsigned arithmetic); the right shift is arithmetic, as on every compiler Cycles is built with.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

namespace stratum::cycles_pcg {

inline constexpr uint32_t kMultiplier = 1664525u, kIncrement = 1013904223u;

// x ^ (x >> 16) with x read as a signed integer (an arithmetic shift).
inline constexpr uint32_t xor_shift(uint32_t x) {
    return x ^ static_cast<uint32_t>(static_cast<int32_t>(x) >> 16);
}

inline constexpr std::array<uint32_t, 2> pcg2(int32_t x, int32_t y) {
    uint32_t a = static_cast<uint32_t>(x) * kMultiplier + kIncrement;
    uint32_t b = static_cast<uint32_t>(y) * kMultiplier + kIncrement;
    a += b * kMultiplier;
    b += a * kMultiplier;
    a = xor_shift(a), b = xor_shift(b);
    a += b * kMultiplier;
    b += a * kMultiplier;
    return {a & 0x7FFFFFFFu, b & 0x7FFFFFFFu};
}

inline constexpr std::array<uint32_t, 3> pcg3(int32_t x, int32_t y, int32_t z) {
    uint32_t a = static_cast<uint32_t>(x) * kMultiplier + kIncrement;
    uint32_t b = static_cast<uint32_t>(y) * kMultiplier + kIncrement;
    uint32_t c = static_cast<uint32_t>(z) * kMultiplier + kIncrement;
    for (int round = 0; round < 2; ++round) {
        if (round == 1) a = xor_shift(a), b = xor_shift(b), c = xor_shift(c);
        a += b * c;
        b += c * a;
        c += a * b;
    }
    return {a & 0x7FFFFFFFu, b & 0x7FFFFFFFu, c & 0x7FFFFFFFu};
}

inline constexpr std::array<uint32_t, 4> pcg4(int32_t x, int32_t y, int32_t z, int32_t w) {
    uint32_t a = static_cast<uint32_t>(x) * kMultiplier + kIncrement;
    uint32_t b = static_cast<uint32_t>(y) * kMultiplier + kIncrement;
    uint32_t c = static_cast<uint32_t>(z) * kMultiplier + kIncrement;
    uint32_t d = static_cast<uint32_t>(w) * kMultiplier + kIncrement;
    for (int round = 0; round < 2; ++round) {
        if (round == 1) a = xor_shift(a), b = xor_shift(b), c = xor_shift(c), d = xor_shift(d);
        a += b * d;
        b += c * a;
        c += a * b;
        d += b * c;
    }
    return {a & 0x7FFFFFFFu, b & 0x7FFFFFFFu, c & 0x7FFFFFFFu, d & 0x7FFFFFFFu};
}

// A 31-bit hash as a float in [0, 1]: converted to float (rounded), then * 2^-31.
inline float to_unit(uint32_t h) {
    return static_cast<float>(static_cast<int32_t>(h)) * (1.0f / 2147483648.0f);
}

// A float cell coordinate (an integer value) as the int Cycles converts it to; values outside the
// int range (and NaN) give INT_MIN, as x86's truncating conversion does, instead of undefined
// behaviour.
inline int32_t to_int(float f) {
    if (!(f >= -2147483648.0f && f < 2147483648.0f)) return INT32_MIN;
    return static_cast<int32_t>(f);
}

// Wrapping integer addition, as the int vectors' operator+ on Cycles' targets.
inline int32_t add(int32_t a, int32_t b) {
    return static_cast<int32_t>(static_cast<uint32_t>(a) + static_cast<uint32_t>(b));
}

}  // namespace stratum::cycles_pcg
