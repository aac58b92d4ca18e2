#include "sampling/sampler_registry.h"

#include <array>

#include "sampling/independent_sampler.h"

namespace stratum {

namespace {

template <typename T>
std::unique_ptr<Sampler> make(const SamplerSettings& settings) {
    return std::make_unique<T>(settings);
}

const std::array kSamplers = {
    SamplerEntry{{"random", "Random (PCG32)",
                  "Independent uniform samples: PCG32 keyed by a hash of pixel, sample, dimension and seed"},
                 &make<IndependentSampler>},
};

}  // namespace

std::span<const SamplerEntry> sampler_registry() { return kSamplers; }

const SamplerEntry* find_sampler(std::string_view name) {
    for (const SamplerEntry& e : kSamplers) {
        if (name == e.info.name) return &e;
    }
    return nullptr;
}

}  // namespace stratum
