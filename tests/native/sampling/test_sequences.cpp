// Pure sequence math of the Halton and Sobol families (native/src/sampling/sequences): primes,
// radical inverse and its inverse, digit permutations, base-b Owen scrambling, float rounding
// that keeps strata, Sobol generator matrices, hashed Owen scrambling, Morton codes.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

#include "sampling/pcg32.h"
#include "sampling/sequences/morton.h"
#include "sampling/sequences/owen_hash.h"
#include "sampling/sequences/primes.h"
#include "sampling/sequences/radical_inverse.h"
#include "sampling/sequences/sobol.h"

using namespace stratum;

TEST(SequencePrimes, TableHoldsTheFirstPrimesInOrder) {
    EXPECT_EQ(kPrimes[0], 2u);
    EXPECT_EQ(kPrimes[4], 11u);
    EXPECT_EQ(kPrimes[999], 7919u);  // the 1000th prime
    uint32_t expected_count = 0;
    for (uint32_t n = 2; n <= kPrimes[kPrimeCount - 1]; ++n) {
        bool prime = true;
        for (uint32_t d = 2; d * d <= n; ++d) prime = prime && n % d != 0;
        if (prime) {
            ASSERT_EQ(kPrimes[expected_count++], n);
        }
    }
    EXPECT_EQ(expected_count, kPrimeCount);
}

TEST(SequenceRadicalInverse, Base2IsBitReversalExactly) {
    Pcg32 rng(7, 1);
    for (uint32_t k = 0; k < 100000; ++k) {
        const uint32_t a = k < 65536 ? k : rng.next_u32();
        ASSERT_EQ(radical_inverse(2, a), reverse_bits32(a) * 0x1p-32) << a;
    }
}

TEST(SequenceRadicalInverse, SmallValuesInBase3And5) {
    EXPECT_DOUBLE_EQ(radical_inverse(3, 1), 1.0 / 3.0);
    EXPECT_DOUBLE_EQ(radical_inverse(3, 2), 2.0 / 3.0);
    EXPECT_DOUBLE_EQ(radical_inverse(3, 3), 1.0 / 9.0);
    EXPECT_DOUBLE_EQ(radical_inverse(3, 5), 2.0 / 3.0 + 1.0 / 9.0);   // 5 = 12_3
    EXPECT_DOUBLE_EQ(radical_inverse(5, 7), 2.0 / 5.0 + 1.0 / 25.0);  // 7 = 12_5
}

TEST(SequenceRadicalInverse, DigitFractionAgreesWithReference) {
    for (uint32_t base : {2u, 3u, 5u, 7u, 101u, 7919u}) {
        ASSERT_GE(int_pow(base, digit_count(base)), uint64_t{1} << 26);
        ASSERT_LT(int_pow(base, digit_count(base) - 1), uint64_t{1} << 26);
        for (uint64_t a = 0; a < 5000; ++a) {
            const float u = to_unit_float(radical_inverse_digits(base, a));
            ASSERT_NEAR(u, radical_inverse(base, a), 0x1p-24) << base << " " << a;
        }
    }
}

TEST(SequenceRadicalInverse, InverseRoundTrips) {
    for (uint32_t base : {2u, 3u, 5u, 7919u}) {
        for (uint32_t n = 0; n <= std::min(4u, digit_count(base)); ++n) {
            const uint64_t count = int_pow(base, n);
            for (uint64_t y = 0; y < std::min<uint64_t>(count, 4000); ++y) {
                const uint64_t a = inverse_radical_inverse(y, base, n);
                ASSERT_LT(a, count);
                // The first n digits of phi_b(a) read y, and inverting phi_b(a)'s digits gives a back.
                const DigitFraction f = radical_inverse_digits(base, a);
                ASSERT_EQ(f.numerator / int_pow(base, f.digits - n), y) << base << " " << n;
                ASSERT_EQ(inverse_radical_inverse(a, base, n), y);
            }
        }
    }
}

TEST(SequenceDigitPermutation, IsABijectionForEveryLengthAndKey) {
    std::vector<uint32_t> lengths;
    for (uint32_t n = 1; n <= 300; ++n) lengths.push_back(n);
    for (uint32_t p : {kPrimes[100], kPrimes[500], kPrimes[999], kPrimes[kPrimeCount - 1]})
        lengths.push_back(p);
    for (uint32_t n : lengths) {
        for (uint64_t key : {uint64_t{0}, uint64_t{1}, uint64_t{0xdeadbeef}, ~uint64_t{0}}) {
            std::vector<bool> hit(n, false);
            for (uint32_t i = 0; i < n; ++i) {
                const uint32_t j = permutation_element(i, n, key);
                ASSERT_LT(j, n);
                ASSERT_FALSE(hit[j]) << "n=" << n << " key=" << key;
                hit[j] = true;
            }
        }
    }
}

TEST(SequenceDigitPermutation, ImagesAreUniformOverKeys) {
    // Over K keys, P(pi(0) = j) = 1/n; the count has standard deviation sqrt(K (1/n)(1 - 1/n)).
    // Accept within 5 sigma for every j (n = 3, 5, 7, 8: 23 counts).
    const uint32_t keys = 30000;
    for (uint32_t n : {3u, 5u, 7u, 8u}) {
        std::vector<int> count(n, 0);
        for (uint32_t k = 0; k < keys; ++k) ++count[permutation_element(0, n, k)];
        const double expected = double(keys) / n, sigma = std::sqrt(keys * (1.0 / n) * (1.0 - 1.0 / n));
        for (uint32_t j = 0; j < n; ++j) EXPECT_NEAR(count[j], expected, 5 * sigma) << n << " " << j;
    }
}

namespace {
uint64_t leading_digits(const DigitFraction& f, uint32_t n) {
    return f.numerator / int_pow(f.base, f.digits - n);
}
}  // namespace

TEST(SequenceOwenBaseB, IsABijectionOnDigitStringsOfFixedLength) {
    // The first n output digits of all b^n strings of n input digits are all different, and the
    // same holds for the random digit permutation; the scramble depends on the key.
    for (uint32_t base : {2u, 3u, 5u, 7u}) {
        for (uint32_t n = 1; int_pow(base, n) <= 3125; ++n) {
            for (uint64_t key : {uint64_t{3}, uint64_t{0x1234567}}) {
                std::set<uint64_t> owen, permuted;
                for (uint64_t a = 0; a < int_pow(base, n); ++a) {
                    owen.insert(leading_digits(owen_scrambled_radical_inverse(base, a, key), n));
                    permuted.insert(leading_digits(permuted_radical_inverse(base, a, key), n));
                }
                ASSERT_EQ(owen.size(), int_pow(base, n)) << base << " " << n;
                ASSERT_EQ(permuted.size(), int_pow(base, n)) << base << " " << n;
            }
        }
    }
    int same = 0;
    for (uint64_t a = 0; a < 100; ++a)
        same += owen_scrambled_radical_inverse(3, a, 1).numerator ==
                owen_scrambled_radical_inverse(3, a, 2).numerator;
    EXPECT_LE(same, 1);
}

TEST(SequenceOwenBaseB, PermutesTrailingZeroDigits) {
    // Pitfall 4: a = 1 has one non-zero digit, but every position is mapped, so for a key whose
    // permutation moves 0 the digits below the first are not all zero.
    int moved = 0;
    for (uint64_t key = 0; key < 50; ++key) {
        const DigitFraction f = permuted_radical_inverse(3, 1, key);
        moved += f.numerator % int_pow(3, f.digits - 1) != 0;
    }
    EXPECT_GE(moved, 25);
}

TEST(SequenceToUnitFloat, StaysInTheStratumOfTheLeadingDigits) {
    // 0.0111...1 in base 2 rounds to 0.5 to nearest; it must stay below 0.5.
    const DigitFraction below_half{(uint64_t{1} << 25) - 1, 2, 26};
    EXPECT_LT(to_unit_float(below_half), 0.5f);
    EXPECT_LT(to_unit_float({int_pow(3, 17) - 1, 3, 17}), 1.0f);
    Pcg32 rng(11, 3);
    for (uint32_t base : {2u, 3u, 5u, 7u, 7919u}) {
        const uint32_t m = digit_count(base);
        const uint64_t full = int_pow(base, m);
        for (int k = 0; k < 20000; ++k) {
            // Half the values sit next to a boundary of a coarse stratum (digits 0...0 or b-1...b-1 after
            // it).
            uint64_t num = ((uint64_t{rng.next_u32()} << 32) | rng.next_u32()) % full;
            const uint64_t coarse = int_pow(base, m - std::min(m, 3u));
            if (k % 4 == 1) num -= num % coarse;
            if (k % 4 == 2) num = num - num % coarse + coarse - 1;
            const float u = to_unit_float({num, base, m});
            ASSERT_LT(u, 1.0f);
            // Guaranteed for the leading n digits with b^n <= 2^22 (strata >= 4 floats wide).
            for (uint32_t n = 1; n <= std::min(m, 3u) && int_pow(base, n) <= (1u << 22); ++n) {
                // floor(u b^n) exactly: u = mant 2^e with a 24-bit integer mant.
                int e = 0;
                const double mant = std::frexp(static_cast<double>(u), &e);
                const auto mi = static_cast<uint64_t>(std::ldexp(mant, 24));
                const uint64_t cell = (mi * int_pow(base, n)) >> (24 - e);  // < 2^24 * 7919^3 < 2^64
                ASSERT_EQ(cell, num / int_pow(base, m - n)) << base << " " << num;
            }
        }
    }
}

TEST(SequenceSobol, Dimension0IsVanDerCorputAndDimension1FollowsItsRecurrence) {
    for (uint32_t i = 0; i < 8192; ++i) ASSERT_EQ(sobol_sample32(i, 0), reverse_bits32(i));
    // m_k for x + 1 (Joe & Kuo's second dimension): 1, 3, 5, 15, 17, 51, 85, 255.
    const uint32_t m[] = {1, 3, 5, 15, 17, 51, 85, 255};
    for (uint32_t k = 1; k <= 8; ++k) EXPECT_EQ(kSobolMatrices[1][k - 1], m[k - 1] << (32 - k));
    EXPECT_EQ(sobol_sample32(1, 1), 0x80000000u);
    EXPECT_EQ(sobol_sample32(2, 1), 0xc0000000u);
    EXPECT_EQ(sobol_sample32(3, 1), 0x40000000u);
}

TEST(SequenceSobol, FastFormsEqualTheGeneratorMatrices) {
    // sobol_sample32 reverses bits (dimension 0) and looks bytes up (dimension 1): both must be
    // the matrix-times-digits definition, for low indices and for scrambled (random) ones.
    uint64_t state = 0x853c49e6748fea9bull;
    for (uint32_t n = 0; n < 100000; ++n) {
        state = state * 6364136223846793005ull + 1442695040888963407ull;
        const uint32_t index = n < 50000 ? n : static_cast<uint32_t>(state >> 32);
        for (uint32_t dim = 0; dim < 2; ++dim) {
            ASSERT_EQ(sobol_sample32(index, dim),
                      detail::sobol_sample32_by_columns(index, kSobolMatrices[dim]))
                << index << " " << dim;
        }
    }
}

TEST(SequenceSobol, FirstPointsFormNets) {
    // Unscrambled dims (0,1): each aligned block of 2^m points has one point in every
    // 2^i x 2^(m-i) elementary interval.
    for (uint32_t m = 0; m <= 10; ++m) {
        for (uint32_t block = 0; block < 4; ++block) {
            for (uint32_t i = 0; i <= m; ++i) {
                std::vector<int> cells(1u << m, 0);
                for (uint32_t n = block << m; n < (block + 1) << m; ++n) {
                    const uint32_t cx = i == 0 ? 0 : sobol_sample32(n, 0) >> (32 - i);
                    const uint32_t cy = m - i == 0 ? 0 : sobol_sample32(n, 1) >> (32 - (m - i));
                    ASSERT_EQ(cells[(cy << i) | cx]++, 0) << m << " " << i;
                }
            }
        }
    }
}

TEST(SequenceOwenHash, NestedScramblesAreBijectionsThatKeepAlignedBlocks) {
    // Bit j of the result depends on bits >= j only: the top 16 bits of scramble(v << 16)
    // depend only on v, and all 2^16 of them differ; a block of 2^m consecutive values maps
    // to 2^m values sharing their top 32-m bits.
    for (uint32_t seed : {0u, 1u, 0x9e3779b9u, 0xffffffffu}) {
        std::vector<bool> hit(1u << 16, false);
        for (uint32_t v = 0; v < (1u << 16); ++v) {
            const uint32_t top = nested_uniform_scramble(v << 16, seed) >> 16;
            ASSERT_FALSE(hit[top]);
            hit[top] = true;
            ASSERT_EQ(nested_uniform_scramble((v << 16) | 0x1234u, seed) >> 16, top);
        }
    }
    EXPECT_NE(nested_uniform_scramble(0, 1), nested_uniform_scramble(0, 2));
}

TEST(SequenceMorton, InterleavesBitsAndPermutesBase4Digits) {
    EXPECT_EQ(morton_encode(1, 0), 1u);
    EXPECT_EQ(morton_encode(0, 1), 2u);
    EXPECT_EQ(morton_encode(3, 3), 15u);
    EXPECT_EQ(morton_encode(5, 2), 0b011001u);
    EXPECT_EQ(morton_encode(0xffffffffu, 0), 0x5555555555555555ull);
    std::set<std::array<uint8_t, 4>> distinct(kBase4Permutations.begin(), kBase4Permutations.end());
    EXPECT_EQ(distinct.size(), 24u);
    for (const auto& p : kBase4Permutations) EXPECT_EQ(std::set<uint8_t>(p.begin(), p.end()).size(), 4u);
    // The key picks each of the 24 permutations about equally often (1000 keys: 41.7 each, sd 6.3).
    std::vector<int> picks(24, 0);
    for (uint64_t key = 0; key < 1000; ++key) {
        std::array<uint8_t, 4> p{};
        for (uint32_t d = 0; d < 4; ++d) p[d] = static_cast<uint8_t>(permute_base4_digit(d, key));
        ++picks[static_cast<size_t>(std::find(kBase4Permutations.begin(), kBase4Permutations.end(), p) -
                                    kBase4Permutations.begin())];
    }
    for (int c : picks) EXPECT_NEAR(c, 1000.0 / 24.0, 5 * std::sqrt(1000.0 / 24.0 * 23.0 / 24.0));
}
