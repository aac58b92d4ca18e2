#include "sampling/hemisphere.h"

#include <array>

namespace stratum {

namespace {

const std::array kDistributions = {
    RegistryEntry{"uniform_angles", "Uniform in Angles",
                  "phi = 2 pi u, theta = pi v / 2: uniform in (phi, theta), crowds directions at the pole"},
    RegistryEntry{"uniform", "Uniform", "Uniform in solid angle over the hemisphere (pdf 1/(2 pi))"},
    RegistryEntry{"cosine", "Cosine-Weighted",
                  "Cosine-weighted (pdf cos(theta)/pi): the shape of the diffuse and AO integrands"},
};

}  // namespace

std::span<const RegistryEntry> hemisphere_registry() { return kDistributions; }

bool parse_hemisphere(std::string_view name, HemisphereDistribution* out) {
    constexpr HemisphereDistribution kValues[] = {HemisphereDistribution::UniformAngles,
                                                  HemisphereDistribution::Uniform,
                                                  HemisphereDistribution::Cosine};
    for (size_t i = 0; i < kDistributions.size(); ++i) {
        if (name == kDistributions[i].name) {
            *out = kValues[i];
            return true;
        }
    }
    return false;
}

}  // namespace stratum
