// Fixed pseudo-random inputs shared by the micro-benchmarks: generated once before timing, so
// the loops measure the code under test, not a random number generator. Fixed seeds: every run
// measures the same work.
#pragma once

#include <cmath>
#include <cstddef>
#include <random>
#include <vector>

#include "core/math.h"

namespace stratum::bench {

// Inputs per benchmark loop (a power of two: the loops index them with a mask).
inline constexpr size_t kInputs = 4096;

inline std::vector<Vec2> uniform_pairs(uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, kOneMinusEpsilon);
    std::vector<Vec2> out(kInputs);
    for (Vec2& v : out) v = {u(rng), u(rng)};
    return out;
}

// Unit directions in the upper hemisphere (z > 0.05: no grazing degeneracies).
inline std::vector<Vec3> upper_directions(uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Vec3> out(kInputs);
    for (Vec3& v : out) {
        const float z = 0.05f + 0.95f * u(rng), phi = 2.0f * kPi * u(rng);
        const float r = std::sqrt(1.0f - z * z);
        v = {r * std::cos(phi), r * std::sin(phi), z};
    }
    return out;
}

}  // namespace stratum::bench
