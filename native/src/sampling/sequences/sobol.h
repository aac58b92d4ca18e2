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

// Sobol dimension `dim` (0 or 1) of point `index`, as a 32-bit fraction (value * 2^32).
constexpr uint32_t sobol_sample32(uint32_t index, uint32_t dim) {
    const SobolMatrix& v = kSobolMatrices[dim];
    uint32_t x = 0;
    // Branch-free: scrambled indices have random bits, and a branch per bit mispredicts.
    for (uint32_t k = 0; index != 0; index >>= 1, ++k) x ^= v[k] & (0u - (index & 1u));
    return x;
}

static_assert(detail::sobol_matrix_dim1()[0] == 0x80000000u &&
              detail::sobol_matrix_dim1()[1] == 0xc0000000u &&
              detail::sobol_matrix_dim1()[2] == 0xa0000000u && detail::sobol_matrix_dim1()[3] == 0xf0000000u);

}  // namespace stratum
