#include <array>

#include "integrators/ao_integrator.h"
#include "integrators/integrator.h"
#include "integrators/path_integrator.h"

namespace stratum {

namespace {

template <typename T>
std::unique_ptr<Integrator> make(const IntegratorSettings& settings) {
    return std::make_unique<T>(settings);
}

const std::array kIntegrators = {
    IntegratorEntry{{"path", "Path Tracing",
                     "Path tracing with next-event estimation, MIS (power heuristic) and Russian roulette"},
                    &make<PathIntegrator>},
    IntegratorEntry{
        {"ao", "Ambient Occlusion",
         "Openness 1 - AO of the first hit (seed 000 eq. 20): 1 = unoccluded (white), 0 = occluded within "
         "ao_distance; one ray per sample from the hemisphere setting's distribution; background 1"},
        &make<AoIntegrator>},
};

}  // namespace

std::span<const IntegratorEntry> integrator_registry() { return kIntegrators; }

const IntegratorEntry* find_integrator(std::string_view name) {
    for (const IntegratorEntry& e : kIntegrators) {
        if (name == e.info.name) return &e;
    }
    return nullptr;
}

}  // namespace stratum
