#include "sampling/lcg_sampler.h"

#include "sampling/hash.h"
#include "sampling/sequences/minstd.h"

namespace stratum {

namespace {
constexpr uint32_t kLcgTag = 0x4c434731u;  // keeps these hashes apart from other samplers' keys
}

uint32_t LcgSampler::initial_state(const PixelSample& s, uint32_t dimension) const {
    return minstd::state_from_bits(hash_words(kLcgTag, s.x, s.y, s.index, dimension, seed_));
}

float LcgSampler::get_1d(const PixelSample& s, uint32_t dimension) const {
    return minstd::to_unit_float(minstd::next(initial_state(s, dimension)));
}

Vec2 LcgSampler::get_2d(const PixelSample& s, uint32_t dimension) const {
    return {get_1d(s, dimension), get_1d(s, dimension + 1)};
}

}  // namespace stratum
