#include "sampling/stratified_sampler.h"

#include <cmath>

#include "sampling/hash.h"
#include "sampling/lhs_sampler.h"

namespace stratum {

namespace {
constexpr uint32_t kPermutationTag = 0x53545231u, kJitterTag = 0x53545232u;
}

float jittered_in_stratum(uint32_t cell, uint32_t n, uint32_t bits) {
    const double jitter = static_cast<double>(bits >> 8) * 0x1p-24;  // [0, 1 − 2^-24]
    const double lo = static_cast<double>(cell), hi = lo + 1.0, dn = static_cast<double>(n);
    auto f = static_cast<float>((lo + jitter) / dn);
    // Nudge by one float at a time until f·n lies in [cell, cell + 1) (exact in double for
    // n < 2^29: a 24-bit by 29-bit product).
    while (static_cast<double>(f) * dn < lo) f = std::nextafter(f, 2.0f);
    while (static_cast<double>(f) * dn >= hi) f = std::nextafter(f, -1.0f);
    return std::min(f, kOneMinusEpsilon);
}

StratifiedSampler::StratifiedSampler(const SamplerSettings& settings)
    : spp_(settings.samples > 0 ? settings.samples : 1), seed_(settings.seed), grid_(strata_grid(spp_)) {}

uint32_t StratifiedSampler::cell(const PixelSample& s, uint32_t dimension) const {
    const uint32_t pair = dimension & ~1u, block = s.index / spp_;
    return permute_index(s.index % spp_, grid_.nx * grid_.ny,
                         hash_words(kPermutationTag, s.x, s.y, pair, block, seed_));
}

Vec2 StratifiedSampler::get_2d(const PixelSample& s, uint32_t dimension) const {
    dimension &= ~1u;
    if (pair_holds_1d_quantities(dimension))
        return {latin_hypercube_value(s, dimension, spp_, seed_),
                latin_hypercube_value(s, dimension + 1, spp_, seed_)};
    const uint32_t c = cell(s, dimension);
    const uint64_t jitter = hash_words(kJitterTag, s.x, s.y, s.index, dimension, seed_);
    return {jittered_in_stratum(c % grid_.nx, grid_.nx, static_cast<uint32_t>(jitter)),
            jittered_in_stratum(c / grid_.nx, grid_.ny, static_cast<uint32_t>(jitter >> 32))};
}

float StratifiedSampler::get_1d(const PixelSample& s, uint32_t dimension) const {
    const Vec2 v = get_2d(s, dimension & ~1u);
    return (dimension & 1u) ? v.y : v.x;
}

}  // namespace stratum
