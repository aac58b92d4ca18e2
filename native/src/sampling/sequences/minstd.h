// The minimal standard LCG "minstd" (Park & Miller 1988; std::minstd_rand0):
// x_{k+1} = 16807 · x_k mod (2^31 − 1), states in [1, 2^31 − 2]. Pure sequence math.
//
// | quantity   | value                  |
// |------------|------------------------|
// | multiplier | 16807 = 7^5            |
// | modulus    | 2^31 − 1 (prime)       |
// | period     | 2^31 − 2               |
//
// std::minstd_rand0 seeded with 1 yields 16807, 282475249, 1622650073, ... and its 10000th
// output is 1043618065 (C++ standard [rand.predef]).
#pragma once

#include <cstdint>

namespace stratum::minstd {

inline constexpr uint32_t kMultiplier = 16807;
inline constexpr uint32_t kModulus = 2147483647u;  // 2^31 − 1

// One step of the recurrence.
constexpr uint32_t next(uint32_t state) {
    return static_cast<uint32_t>(static_cast<uint64_t>(state) * kMultiplier % kModulus);
}

// The state after `steps` steps, by modular exponentiation of the multiplier (a jump ahead):
// x_{k+n} = 16807^n · x_k mod m.
constexpr uint32_t advance(uint32_t state, uint64_t steps) {
    uint64_t factor = 1, base = kMultiplier;
    for (; steps != 0; steps >>= 1) {
        if (steps & 1u) factor = factor * base % kModulus;
        base = base * base % kModulus;
    }
    return static_cast<uint32_t>(factor * state % kModulus);
}

// A valid state from any 64 random bits: uniform over [1, m − 1] up to a bias of 2^-33.
// (std::minstd_rand0 maps seed s to s mod m, with 0 replaced by 1.)
constexpr uint32_t state_from_bits(uint64_t bits) { return static_cast<uint32_t>(1 + bits % (kModulus - 1)); }

// An output x in [1, m − 1] mapped to [0,1) as std::uniform_real_distribution<float>(0, 1)
// does with this engine: generate_canonical<float, 24> needs ceil(24 / log2 R) = 1 engine call,
// R = max − min + 1 = 2^31 − 2, and returns (x − min)/R = (x − 1)/(2^31 − 2). Computed in
// double, rounded to float, and clamped below 1, since the rounding can reach 1.0 (the clamp
// libstdc++ itself added for LWG 2524).
constexpr float to_unit_float(uint32_t x) {
    const double u = static_cast<double>(x - 1) / static_cast<double>(kModulus - 1);
    const auto f = static_cast<float>(u);
    return f < 0x1.fffffep-1f ? f : 0x1.fffffep-1f;
}

}  // namespace stratum::minstd
