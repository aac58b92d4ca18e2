// The one list of samplers: name (stable, used in settings), label, description, factory.
// The add-on's menu and `stratum samplers` are generated from it.
#pragma once

#include <memory>
#include <span>
#include <string_view>

#include "core/registry.h"
#include "sampling/sampler.h"

namespace stratum {

struct SamplerEntry {
    RegistryEntry info;
    std::unique_ptr<Sampler> (*create)(const SamplerSettings&);
};

std::span<const SamplerEntry> sampler_registry();
// nullptr when no sampler has this name.
const SamplerEntry* find_sampler(std::string_view name);

}  // namespace stratum
