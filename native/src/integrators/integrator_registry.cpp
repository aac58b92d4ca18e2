#include <array>

#include "integrators/ao_integrator.h"
#include "integrators/integrator.h"
#include "integrators/light_tracer.h"
#include "integrators/path_integrator.h"
#include "integrators/radiosity_integrator.h"

namespace stratum {

namespace {

template <typename T>
std::unique_ptr<Integrator> make(const IntegratorSettings& settings) {
    return std::make_unique<T>(settings);
}

// Direct lighting is the path tracer stopped after its first vertex (max_bounces 0 in Cycles'
// meaning): emission seen by the camera plus one scattering toward the lights, by the chosen
// light_sampling strategy.
std::unique_ptr<Integrator> make_direct(const IntegratorSettings& settings) {
    IntegratorSettings direct = settings;
    direct.max_bounces = 0;
    direct.use_guiding = false;  // `path` only: one vertex learns nothing it could use
    return std::make_unique<PathIntegrator>(direct);
}

const std::array kIntegrators = {
    IntegratorEntry{{"path", "Path Tracing",
                     "Path tracing: BSDF sampling, next-event estimation or both by MIS (light_sampling), "
                     "Russian roulette (rr_mode), optional control variate"},
                    &make<PathIntegrator>},
    IntegratorEntry{
        {"light", "Light Tracing",
         "Light tracing: particles from the lights, scattered by the BSDFs and connected to the camera "
         "(textbook ch. 6), splatted through the pixel filter; the camera sees emission directly"},
        &make<LightTracer>},
    IntegratorEntry{{"direct", "Direct Lighting",
                     "Direct lighting only: emission seen by the camera and one scattering toward the lights "
                     "(the path tracer with max_bounces 0), by the light_sampling strategy"},
                    &make_direct},
    IntegratorEntry{
        {"ao", "Ambient Occlusion",
         "Openness 1 - AO of the first hit (seed 000 eq. 20): 1 = unoccluded (white), 0 = occluded within "
         "ao_distance; one ray per sample from the hemisphere setting's distribution; background 1"},
        &make<AoIntegrator>},
    IntegratorEntry{
        {"radiosity", "Radiosity",
         "Radiosity for diffuse scenes (textbook §3): patches, form factors by ray casting, solved once "
         "(radiosity_solver), seen through a final gather; other closures count by their diffuse albedo"},
        &make<RadiosityIntegrator>},
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
