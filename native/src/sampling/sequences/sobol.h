// The first two dimensions of the Sobol sequence (Sobol 1967; Bratley & Fox 1988, §2; Joe & Kuo
// 2008, §2) as 32-bit fractions. Pure sequence math. Dimensions 0 and 1 form a (0,2)-sequence
// in base 2: every aligned block of 2^m points is a (0,m,2)-net.
//
// Dimension j has direction numbers v_k = m_k / 2^k (k = 1..32), stored as V_k = m_k << (32-k),
// and the point of index i is the xor of V_k over the set bits k-1 of i (generator matrix times
// the digits of i). Dimension 0 uses V_k = 2^(32-k): the bit reversal of i (van der Corput).
// Dimension 1 comes from the primitive polynomial x + 1 (degree s = 1, no inner coefficients):
// the recurrence m_k = 2^s m_{k-s} xor m_{k-s} becomes m_k = 2 m_{k-1} xor m_{k-1}, m_1 = 1
// (so m = 1, 3, 5, 15, 17, 51, ...: Pascal's triangle mod 2).
#pragma once

#include <array>
#include <cstdint>

#include "sampling/sequences/owen_hash.h"

namespace stratum {

using SobolMatrix = std::array<uint32_t, 32>;  // column k-1 holds V_k

namespace detail {

constexpr SobolMatrix sobol_matrix_dim0() {
    SobolMatrix v{};
    for (uint32_t k = 1; k <= 32; ++k) v[k - 1] = 1u << (32 - k);
    return v;
}

constexpr SobolMatrix sobol_matrix_dim1() {
    SobolMatrix v{};
    uint64_t m = 1;  // m_1; every m_k < 2^k, so V_k = m_k << (32 - k) fits in 32 bits
    for (uint32_t k = 1; k <= 32; ++k) {
        v[k - 1] = static_cast<uint32_t>(m << (32 - k));
        m = (m << 1) ^ m;
    }
    return v;
}

}  // namespace detail

inline constexpr std::array<SobolMatrix, 2> kSobolMatrices = {detail::sobol_matrix_dim0(),
                                                              detail::sobol_matrix_dim1()};

namespace detail {

// The generator matrix applied by its definition: xor of the columns the index's bits select.
constexpr uint32_t sobol_sample32_by_columns(uint32_t index, const SobolMatrix& v) {
    uint32_t x = 0;
    for (uint32_t k = 0; index != 0; index >>= 1, ++k) x ^= v[k] & (0u - (index & 1u));
    return x;
}

// Dimension 1 by bytes: entry [b][v] is the xor of the columns 8b .. 8b+7 that the bits of v
// select, so a point costs four lookups (4 KiB, cache resident) where the column loop runs
// up to 32 steps (a scrambled index has random high bits, so usually all 32).
constexpr std::array<std::array<uint32_t, 256>, 4> sobol_dim1_byte_tables() {
    std::array<std::array<uint32_t, 256>, 4> tables{};
    const SobolMatrix v = sobol_matrix_dim1();
    for (uint32_t b = 0; b < 4; ++b) {
        for (uint32_t byte = 0; byte < 256; ++byte) {
            uint32_t x = 0;
            for (uint32_t j = 0; j < 8; ++j)
                if (byte & (1u << j)) x ^= v[8 * b + j];
            tables[b][byte] = x;
        }
    }
    return tables;
}

}  // namespace detail

inline constexpr auto kSobolDim1ByteTables = detail::sobol_dim1_byte_tables();

// Sobol dimension `dim` (0 or 1) of point `index`, as a 32-bit fraction (value * 2^32).
// Dimension 0's columns V_k = 2^(32-k) send bit k-1 of the index to bit 32-k: a bit reversal.
constexpr uint32_t sobol_sample32(uint32_t index, uint32_t dim) {
    if (dim == 0) return reverse_bits32(index);
    const auto& t = kSobolDim1ByteTables;
    return t[0][index & 0xffu] ^ t[1][(index >> 8) & 0xffu] ^ t[2][(index >> 16) & 0xffu] ^ t[3][index >> 24];
}

// Owen-scrambled Sobol value of a (shuffled) index: nested_uniform_scramble(sobol_sample32(index,
// dim), key). For dimension 0 the scramble's own first bit reversal undoes the sequence's, so
// neither is computed.
constexpr uint32_t owen_scrambled_sobol32(uint32_t index, uint32_t dim, uint32_t key) {
    if (dim == 0) return reverse_bits32(vegdahl_permutation(index, key));
    return nested_uniform_scramble(sobol_sample32(index, 1), key);
}

// The fast forms equal the definition (tests/native check many more indices).
static_assert(sobol_sample32(0x9e3779b9u, 0) ==
              detail::sobol_sample32_by_columns(0x9e3779b9u, kSobolMatrices[0]));
static_assert(sobol_sample32(0x9e3779b9u, 1) ==
              detail::sobol_sample32_by_columns(0x9e3779b9u, kSobolMatrices[1]));
static_assert(sobol_sample32(0xffffffffu, 1) ==
              detail::sobol_sample32_by_columns(0xffffffffu, kSobolMatrices[1]));

static_assert(detail::sobol_matrix_dim1()[0] == 0x80000000u &&
              detail::sobol_matrix_dim1()[1] == 0xc0000000u &&
              detail::sobol_matrix_dim1()[2] == 0xa0000000u && detail::sobol_matrix_dim1()[3] == 0xf0000000u);

}  // namespace stratum
