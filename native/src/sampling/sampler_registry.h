// The one list of samplers: name (stable, used in settings), label, description, factory.
// The add-on's menu and `stratum samplers` are generated from it.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string_view>

#include "core/registry.h"
#include "sampling/sampler.h"

namespace stratum {

// How a pixel's samples relate to each other, for what the film and adaptive sampling may assume
// of its first n samples.
enum class SampleStructure : uint8_t {
    Independent,  // independent draws: the sample variance s²/n is the error of their mean
    Progressive,  // every power-of-two prefix is a well-spread set of its own (nets, sequences)
    WholeCount,   // laid out for the whole sample count (a grid, strata, a lattice of that size)
};

struct SamplerEntry {
    RegistryEntry info;
    std::unique_ptr<Sampler> (*create)(const SamplerSettings&);
    SampleStructure structure;
    // Neighbouring pixels' samples are spread jointly (blue-noise error): adaptive sampling
    // stops aligned blocks of pixels together so the joint structure holds within them.
    bool screen_space = false;
};

std::span<const SamplerEntry> sampler_registry();
// nullptr when no sampler has this name.
const SamplerEntry* find_sampler(std::string_view name);

}  // namespace stratum
