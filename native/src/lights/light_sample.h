// What every light model returns to next-event estimation.
#pragma once

#include <limits>

#include "core/math.h"
#include "scene/visibility.h"

namespace stratum {

struct LightSample {
    Vec3 wi;         // unit direction from the shading point toward the light
    float distance;  // to the sampled point; infinity for the sun
    Rgb radiance;    // radiance arriving along -wi; for delta lights the irradiance at normal incidence
    float pdf;       // solid-angle pdf of wi; 1 for delta lights (point of radius 0, sun of angle 0)
    // True when a BSDF-sampled ray can also find this light (emissive geometry), so the two
    // strategies are combined by MIS; lights without geometry are found by light sampling only
    // and take the full weight.
    bool found_by_bsdf_rays;
    // StratumVisibility bits of the light (DIFFUSE / GLOSSY / TRANSMISSION: which vertices it
    // lights; SHADOW: whether occluders block it).
    uint32_t visibility = kVisibleAll;
    uint32_t light = 0;  // the light's index in its LightSet (its links: LightSet::links)
    // The light group of the light (LightSet::set_lightgroup; 0 = none).
    uint32_t lightgroup = 0;
};

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

}  // namespace stratum
