#include "sampling/fibonacci_sampler.h"

#include <cmath>

#include "sampling/hash.h"
#include "sampling/stratified_sampler.h"

namespace stratum {

namespace {

constexpr double kInvGoldenRatio = 0.61803398874989484820;  // 1/φ = φ − 1
constexpr uint32_t kOrderTag = 0x46494231u, kShiftTag = 0x46494232u;

double frac(double v) { return v - std::floor(v); }

// 53 random bits → [0,1).
double unit_double(uint64_t bits) { return static_cast<double>(bits >> 11) * 0x1p-53; }

// Wraps a shifted coordinate to [0,1) and rounds it to a float < 1.
float wrap_to_float(double v) { return std::min(static_cast<float>(frac(v)), kOneMinusEpsilon); }

}  // namespace

LatticePoint fibonacci_lattice_point(uint32_t j, uint32_t n) {
    return {frac((static_cast<double>(j) + 1.0) * kInvGoldenRatio),
            (static_cast<double>(j) + 0.5) / static_cast<double>(n)};
}

uint64_t FibonacciSampler::key(const PixelSample& s, uint32_t dimension, uint32_t tag) const {
    const uint32_t block = s.index / spp_;
    return per_pixel_ ? hash_words(tag, s.x, s.y, dimension, block, seed_)
                      : hash_words(tag, dimension, block, seed_);
}

LatticePoint FibonacciSampler::shift(const PixelSample& s, uint32_t dimension) const {
    const uint64_t k = key(s, dimension & ~1u, kShiftTag);
    return {unit_double(k), unit_double(mix_bits(k))};
}

Vec2 FibonacciSampler::get_2d(const PixelSample& s, uint32_t dimension) const {
    dimension &= ~1u;
    const uint32_t i = s.index % spp_;
    if (pair_holds_1d_quantities(dimension)) {
        float v[2];
        for (uint32_t k = 0; k < 2; ++k) {
            const uint64_t shift_bits = key(s, dimension + k, kShiftTag);
            const uint32_t j = permute_index(i, spp_, key(s, dimension + k, kOrderTag));
            v[k] = wrap_to_float((j + 0.5) / spp_ + unit_double(shift_bits));
        }
        return {v[0], v[1]};
    }
    const uint32_t j = permute_index(i, spp_, key(s, dimension, kOrderTag));
    const LatticePoint p = fibonacci_lattice_point(j, spp_), t = shift(s, dimension);
    return {wrap_to_float(p.x + t.x), wrap_to_float(p.y + t.y)};
}

float FibonacciSampler::get_1d(const PixelSample& s, uint32_t dimension) const {
    const Vec2 v = get_2d(s, dimension & ~1u);
    return (dimension & 1u) ? v.y : v.x;
}

}  // namespace stratum
