// What every light model returns to next-event estimation.
#pragma once

#include <limits>

#include "core/math.h"

namespace stratum {

struct LightSample {
    Vec3 wi;          // unit direction from the shading point toward the light
    float distance;   // to the sampled point; infinity for the sun
    Rgb radiance;     // radiance arriving along -wi (delta lights: irradiance-like intensity term)
    float pdf;        // solid-angle pdf of wi; for delta lights 1 (and `delta` is set)
    bool delta;       // sampled with a Dirac distribution: no MIS with BSDF sampling
};

inline constexpr float kInfinity = std::numeric_limits<float>::infinity();

}  // namespace stratum
