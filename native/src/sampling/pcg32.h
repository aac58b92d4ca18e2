// PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
// Algorithms for Random Number Generation", XSH-RR 64/32 variant). Pure sequence math.
#pragma once

#include <cstdint>

namespace stratum {

class Pcg32 {
public:
    // Stream selection follows the reference pcg32_srandom_r: any (state, stream) pair is valid.
    constexpr Pcg32(uint64_t initial_state, uint64_t stream) : inc_((stream << 1u) | 1u) {
        next_u32();
        state_ += initial_state;
        next_u32();
    }
    constexpr uint32_t next_u32() {
        const uint64_t old = state_;
        state_ = old * 6364136223846793005ull + inc_;
        const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        const auto rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
    }

private:
    uint64_t state_ = 0;
    uint64_t inc_;
};

}  // namespace stratum
