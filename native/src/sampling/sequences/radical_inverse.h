// Radical inverse in prime bases and its digit-level building blocks. Pure sequence math.
//
// The radical inverse of a = sum_i d_i b^i is phi_b(a) = sum_i d_i b^-(i+1): the base-b digits
// of a mirrored about the radix point (Halton 1960; pbrt-v4 §8.6.1). The samplers work on a
// fixed number of digits per base, digit_count(b): the fewest digits with b^M >= 2^26, i.e.
// finer than a quarter of the float spacing just below 1 (float precision, research
// samplers.md pitfall 4). Digits are accumulated as an integer over b^M and scaled once
// (pitfall 8); to_unit_float then rounds so the float stays inside the base-b stratum its
// leading digits name (see there).
#pragma once

#include <cmath>
#include <cstdint>

#include "core/math.h"  // kOneMinusEpsilon
#include "sampling/sequences/digit_permutation.h"
#include "sampling/sequences/primes.h"

namespace stratum {

// Digits per base: the fewest M with b^M >= 2^26 (b^M < 2^26 * b <= 2^39 for the table).
constexpr uint32_t digit_count(uint32_t base) {
    uint32_t m = 0;
    for (uint64_t p = 1; p < (uint64_t{1} << 26); p *= base) ++m;
    return m;
}

constexpr uint64_t int_pow(uint64_t base, uint32_t e) {
    uint64_t r = 1;
    while (e-- > 0) r *= base;
    return r;
}

// An exact value in [0,1): numerator / base^digits with 0 <= numerator < base^digits. The
// leading (most significant) digit of the numerator is the first digit after the radix point.
struct DigitFraction {
    uint64_t numerator = 0;
    uint32_t base = 2;
    uint32_t digits = 0;
};

// phi_b(a) computed over all digits of a as an integer and scaled once (exact for base 2 and
// a < 2^53). Reference value for tests and documentation; samplers use radical_inverse_digits.
inline double radical_inverse(uint32_t base, uint64_t a) {
    uint64_t reversed = 0, scale = 1;
    // Stop before reversed * base could overflow; the digits left out are below 2^-52.
    const uint64_t limit = ~uint64_t{0} / base - base;
    while (a != 0 && reversed < limit) {
        reversed = reversed * base + a % base;
        scale *= base;
        a /= base;
    }
    return static_cast<double>(reversed) / static_cast<double>(scale);
}

// The digit map of a scrambled radical inverse: `map(digit, position, prefix)` returns the
// digit written at `position` (0 = first after the radix point) given the digit d of a and the
// already written, more significant output digits `prefix` (an integer with `position` digits).
// It must be a bijection of [0, base) for each (position, prefix); then every output prefix of
// length k comes from exactly one input prefix, so strata of b^-k are preserved.
// All digit_count(base) positions are mapped, including the trailing zeros of a (pitfall 4).
template <typename DigitMap>
constexpr DigitFraction radical_inverse_digits(uint32_t base, uint64_t a, DigitMap&& map) {
    DigitFraction f{0, base, digit_count(base)};
    for (uint32_t position = 0; position < f.digits; ++position) {
        const auto digit = static_cast<uint32_t>(a % base);
        a /= base;
        f.numerator = f.numerator * base + map(digit, position, f.numerator);
    }
    return f;
}

constexpr DigitFraction radical_inverse_digits(uint32_t base, uint64_t a) {
    return radical_inverse_digits(base, a, [](uint32_t d, uint32_t, uint64_t) { return d; });
}

// Random digit permutation (Owen 2017, §3; Faure's idea with random permutations): one keyed
// permutation of [0, base) applied to every digit position.
constexpr DigitFraction permuted_radical_inverse(uint32_t base, uint64_t a, uint64_t key) {
    return radical_inverse_digits(
        base, a, [&](uint32_t d, uint32_t, uint64_t) { return permutation_element(d, base, key); });
}

// Base-b Owen scrambling (Owen 1995; pbrt-v4 OwenScrambledRadicalInverse): the permutation of
// each digit is keyed by its position and the output digits above it. (prefix, position) ->
// prefix * 32 + position is injective because prefix < base^digits < 2^39 and position < 32.
constexpr DigitFraction owen_scrambled_radical_inverse(uint32_t base, uint64_t a, uint64_t key) {
    return radical_inverse_digits(base, a, [&](uint32_t d, uint32_t position, uint64_t prefix) {
        return permutation_element(d, base, key ^ ((prefix << 5) | position));
    });
}

// Inverse of the first n_digits digits of the radical inverse: the a in [0, b^n) whose phi_b(a)
// lies in [y b^-n, (y+1) b^-n), i.e. whose n lowest digits are those of y, mirrored.
constexpr uint64_t inverse_radical_inverse(uint64_t y, uint32_t base, uint32_t n_digits) {
    uint64_t a = 0;
    for (uint32_t i = 0; i < n_digits; ++i) {
        a = a * base + y % base;
        y /= base;
    }
    return a;
}

// numerator / base^digits as a float in [0,1) that lies in the same base-b stratum of width
// b^-K as the exact value, for K = the most leading digits with b^K <= 2^22 (such a stratum is
// at least four floats wide). Plain rounding does not give that: e.g. base 2 digits
// 0.0111...1 (26 digits) round to 0.5 and leave their half, and a base-3 stratum boundary c/3^k
// is never a float. The bound test f * b^K >= prefix is exact in double (24 + 22 bits).
inline float to_unit_float(const DigitFraction& f) {
    const double scale = static_cast<double>(int_pow(f.base, f.digits));
    float u = static_cast<float>(static_cast<double>(f.numerator) / scale);
    uint32_t k = 0;
    uint64_t bk = 1;
    while (k < f.digits && bk * f.base <= (uint64_t{1} << 22)) {
        bk *= f.base;
        ++k;
    }
    const uint64_t prefix = f.numerator / int_pow(f.base, f.digits - k);
    const double lo = static_cast<double>(prefix), hi = static_cast<double>(prefix + 1);
    const double b = static_cast<double>(bk);
    while (static_cast<double>(u) * b < lo) u = std::nextafter(u, 1.0f);
    while (static_cast<double>(u) * b >= hi) u = std::nextafter(u, 0.0f);
    return u < kOneMinusEpsilon ? u : kOneMinusEpsilon;
}

}  // namespace stratum
