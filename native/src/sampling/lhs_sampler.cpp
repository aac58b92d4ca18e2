#include "sampling/lhs_sampler.h"

#include "sampling/hash.h"
#include "sampling/stratified_sampler.h"

namespace stratum {

namespace {
constexpr uint32_t kPermutationTag = 0x4c485331u, kJitterTag = 0x4c485332u;
}

uint32_t latin_hypercube_stratum(const PixelSample& s, uint32_t dimension, uint32_t spp, uint32_t seed) {
    const uint32_t block = s.index / spp;
    return permute_index(s.index % spp, spp, hash_words(kPermutationTag, s.x, s.y, dimension, block, seed));
}

float latin_hypercube_value(const PixelSample& s, uint32_t dimension, uint32_t spp, uint32_t seed) {
    const auto jitter = static_cast<uint32_t>(hash_words(kJitterTag, s.x, s.y, s.index, dimension, seed));
    return jittered_in_stratum(latin_hypercube_stratum(s, dimension, spp, seed), spp, jitter);
}

}  // namespace stratum
