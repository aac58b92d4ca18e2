#include "sampling/bluenoise_sampler.h"

#include "sampling/hash.h"
#include "sampling/sequences/void_and_cluster.h"

namespace stratum {

namespace {
constexpr uint32_t kLookupTag = 0x424e5331u;
constexpr uint32_t kMask = BlueNoiseSampler::kSize - 1;
static_assert((BlueNoiseSampler::kSize & kMask) == 0, "the lookup wraps with a mask");
}  // namespace

const std::vector<uint32_t>& BlueNoiseSampler::ranks() {
    static const std::vector<uint32_t> texture =
        void_and_cluster::rank_texture(kSize, kSigma, kInitialFraction, kTextureSeed);
    return texture;
}

uint32_t BlueNoiseSampler::texel(const PixelSample& s, uint32_t dimension) const {
    // 28 bits: shift (sx, sy) and odd strides (kx, ky), 7 bits each, per (dimension, block).
    const uint64_t h = hash_words(kLookupTag, dimension, s.index / kSize, seed_);
    const uint64_t i = s.index;
    const uint64_t column = s.x + (h & kMask) + i * (((h >> 14) & kMask) | 1u);
    const uint64_t row = s.y + ((h >> 7) & kMask) + i * (((h >> 21) & kMask) | 1u);
    return static_cast<uint32_t>((row & kMask) * kSize + (column & kMask));
}

}  // namespace stratum
