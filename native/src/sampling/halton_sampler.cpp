#include "sampling/halton_sampler.h"

#include <algorithm>

#include "sampling/hash.h"
#include "sampling/sequences/primes.h"
#include "sampling/sequences/radical_inverse.h"

namespace stratum {

namespace {

// Tiles are at most this many pixels on a side before they repeat (pbrt-v4 MaxHaltonResolution).
constexpr uint32_t kMaxTileResolution = 128;
// Each pixel starts at position (pixel shift) < 2^40 of its index list a0 + n S, so indices
// stay below (2^40 + 2^32) * 2^7 * 3^5 < 2^56.
constexpr uint32_t kPixelShiftBits = 40;

// x^-1 mod m by the extended Euclidean algorithm (gcd(x, m) = 1).
uint64_t modular_inverse(uint64_t x, uint64_t m) {
    if (m == 1) return 0;
    int64_t r0 = static_cast<int64_t>(m), r1 = static_cast<int64_t>(x % m), t0 = 0, t1 = 1;
    while (r1 != 0) {
        const int64_t q = r0 / r1;
        int64_t t = t0 - q * t1;
        t0 = t1;
        t1 = t;
        t = r0 - q * r1;
        r0 = r1;
        r1 = t;
    }
    const int64_t mm = static_cast<int64_t>(m);
    return static_cast<uint64_t>(((t0 % mm) + mm) % mm);
}

}  // namespace

// Pixel to index (pbrt-v4 §8.6.2). Dimension 0 is phi_2(a), so floor(2^j phi_2(a)) = x holds
// exactly when the j lowest base-2 digits of a, mirrored, are x: a = r2 mod 2^j with
// r2 = inverse_radical_inverse(x, 2, j). Likewise floor(3^k phi_3(a)) = y exactly when
// a = r3 mod 3^k. 2^j and 3^k are coprime, so by the Chinese remainder theorem these two
// congruences select one residue a0 mod S = 2^j 3^k:
//   a0 = (r2 * 3^k * (3^k)^-1 mod 2^j  +  r3 * 2^j * (2^j)^-1 mod 3^k) mod S,
// and the pixel's samples are the indices a0 + n S, n = 0, 1, 2, ... Inside the pixel,
// dimension 0 is 2^j phi_2(a) - x = phi_2(a >> j) and dimension 1 is phi_3(a / 3^k).
// Stratification: a >> j = a0 >> j + n 3^k and a / 3^k = a0 / 3^k + n 2^j, so for any
// N = 2^j' 3^k' consecutive n the pair (n 3^k mod 2^j', n 2^j mod 3^k') runs through all of
// Z/2^j' x Z/3^k' (CRT again, 3^k and 2^j being units): the N points fall one in each cell of
// the 2^j' x 3^k' grid. Because this holds for any N consecutive n, each pixel starts at its
// own n = hash(x, y, seed) (a random start, Wang & Hickernell 2000): without it pixels a whole
// tile apart repeat each other (pbrt-v4), and pixels whose a0 differ only in low digits share
// their dims-(0,1) points (a0 >> j and a0 / 3^k equal). A bijective digit map (permutation,
// Owen) keeps the cells distinct, so all three variants are stratified.
HaltonSampler::HaltonSampler(const SamplerSettings& settings, HaltonRandomization randomization)
    : randomization_(randomization), seed_(settings.seed) {
    while (scale2_ < std::min(settings.width, kMaxTileResolution)) {
        scale2_ *= 2;
        ++exponent2_;
    }
    while (scale3_ < std::min(settings.height, kMaxTileResolution)) {
        scale3_ *= 3;
        ++exponent3_;
    }
    stride_ = uint64_t{scale2_} * scale3_;
    crt_weight2_ = uint64_t{scale3_} * modular_inverse(scale3_, scale2_);
    crt_weight3_ = uint64_t{scale2_} * modular_inverse(scale2_, scale3_);
}

uint64_t HaltonSampler::halton_index(const PixelSample& s) const {
    const uint32_t px = s.x % scale2_, py = s.y % scale3_;
    const uint64_t r2 = inverse_radical_inverse(px, 2, exponent2_);
    const uint64_t r3 = inverse_radical_inverse(py, 3, exponent3_);
    const uint64_t a0 = (r2 * crt_weight2_ + r3 * crt_weight3_) % stride_;
    const uint64_t pixel_shift = hash_more(s.pixel_key, seed_) >> (64 - kPixelShiftBits);
    return a0 + (pixel_shift + s.index) * stride_;
}

float HaltonSampler::get_1d(const PixelSample& s, uint32_t dimension) const {
    const uint64_t a = halton_index(s);
    uint32_t base = 2;
    uint64_t digits_of = a;
    if (dimension == 0) {
        digits_of = a >> exponent2_;
    } else if (dimension == 1) {
        base = 3;
        digits_of = a / scale3_;
    } else {
        base = kPrimes[2 + (dimension - 2) % (kPrimeCount - 2)];
    }
    switch (randomization_) {
        case HaltonRandomization::None:
            return to_unit_float(radical_inverse_digits(base, digits_of));
        case HaltonRandomization::PermuteDigits:
            return to_unit_float(
                permuted_radical_inverse(base, digits_of, hash_words(seed_, dimension, 0x7e2d1u)));
        case HaltonRandomization::Owen:
            return to_unit_float(
                owen_scrambled_radical_inverse(base, digits_of, hash_words(seed_, dimension, 0x0e3au)));
    }
    return 0.0f;
}

}  // namespace stratum
