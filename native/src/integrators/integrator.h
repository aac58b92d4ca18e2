// The integrator interface and registry: an integrator estimates the radiance arriving along
// one camera ray, drawing every random number from the sampler at the named dimensions.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string_view>

#include "sampling/hemisphere.h"
#include "sampling/sampler.h"
#include "sampling/sampler_registry.h"
#include "scene/camera.h"
#include "scene/render_scene.h"

namespace stratum {

struct IntegratorSettings {
    // Cycles' max_bounces: vertices 0..max_bounces are shaded (light sampling and scattering);
    // the ray scattered at the last one still collects the emission it hits.
    uint32_t max_bounces = 12;
    // `ao`: the distribution AO directions are drawn from, and the distance within which an
    // obstacle occludes (scene units, > 0; infinity = unlimited).
    HemisphereDistribution hemisphere = HemisphereDistribution::Cosine;
    float ao_distance = 1.0f;
    // Cycles' transparent_max_bounces (default 8 in 3.4 and 5.0): pass-throughs of Transparent
    // closures (and transparent-shadow surfaces) allowed per path; they are not bounces.
    uint32_t transparent_max_bounces = 8;
    // Cycles' Film > Transparent: background seen directly (also through transparent closures)
    // gives alpha 0 instead of its radiance, and holdouts turn into alpha.
    bool film_transparent = false;
};

// One camera ray's estimate: the radiance, and the alpha the film stores (1 = covered; a
// holdout or, with a transparent film, the background gives 0).
struct RadianceSample {
    Rgb radiance;
    float alpha = 1.0f;
};

class Integrator {
public:
    virtual ~Integrator() = default;
    // `rays` is incremented by the number of rays traced.
    virtual RadianceSample radiance(const RenderScene& scene, const Sampler& sampler,
                                    const PixelSample& pixel, const CameraRay& ray, uint64_t& rays) const = 0;
};

struct IntegratorEntry {
    RegistryEntry info;
    std::unique_ptr<Integrator> (*create)(const IntegratorSettings&);
};

std::span<const IntegratorEntry> integrator_registry();
const IntegratorEntry* find_integrator(std::string_view name);

}  // namespace stratum
