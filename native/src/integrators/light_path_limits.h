// Cycles' Light Paths limits (Render Properties > Light Paths > Max Bounces and Clamping), as its
// path state and film apply them (kernel/integrator/path_state.h path_state_next,
// kernel/film/light_passes.h film_clamp_light; the same in 3.4 and 5.0).
//
// | setting              | what it limits                                                        |
// |----------------------|-----------------------------------------------------------------------|
// | max_bounces          | scatterings of any kind but transparent pass-throughs                 |
// | diffuse_bounces      | diffuse reflections                                                   |
// | glossy_bounces       | glossy and mirror reflections                                         |
// | transmission_bounces | refractions, rough or smooth (Cycles also counts diffuse transmission |
// |                      | here: Stratum has no Translucent closure yet)                         |
// | clamp_direct         | each direct contribution: next-event estimation at the first vertex,  |
// |                      | emission, lamps and background met after at most one scattering       |
// | clamp_indirect       | each other contribution                                               |
//
// A vertex whose arriving counts are all within their limits is shaded in full (light sampling
// and scattering); the scattering that takes a count past its limit still collects the emission
// (and transparent pass-throughs) at the next hit, Cycles' PATH_RAY_TERMINATE_AFTER_TRANSPARENT,
// so that its light-sampling twin stays MIS-balanced. A limit of 0 is direct light only for that
// kind. A clamp c > 0 scales a contribution L whose |L_r| + |L_g| + |L_b| exceeds 3c down to that
// sum (the mean of the channels to c, the colour kept); 0 leaves it. Clamping is biased by design.
#pragma once

#include <cmath>
#include <cstdint>

#include "bsdf/bsdf.h"
#include "core/math.h"

namespace stratum {

struct LightPathLimits {
    uint32_t diffuse = 1024, glossy = 1024, transmission = 1024;
    float clamp_direct = 0.0f, clamp_indirect = 0.0f;
    // Filter Glossy and the caustics switches (integrators/light_path_closures.h): off.
    float filter_glossy = 0.0f;
    bool caustics_reflective = true, caustics_refractive = true;
};

// The scatterings a path has made, by kind (transparent pass-throughs are not counted here).
class BounceCounts {
public:
    // Counts a scattering of `kind`; a transparent pass-through is not one.
    void scatter(ScatterKind kind) {
        if (kind == ScatterKind::Transparent) return;
        ++total_;
        switch (kind) {
            case ScatterKind::Diffuse:
                ++diffuse_;
                break;
            case ScatterKind::Glossy:
                ++glossy_;
                break;
            case ScatterKind::Transmission:
                ++transmission_;
                break;
            case ScatterKind::Transparent:
                break;
        }
    }
    uint32_t total() const { return total_; }
    uint32_t diffuse() const { return diffuse_; }
    uint32_t glossy() const { return glossy_; }
    uint32_t transmission() const { return transmission_; }
    // The kinds (scatter_kind_bit) of which one more scattering keeps the count within its limit.
    uint32_t kinds_within(const LightPathLimits& limits) const {
        uint32_t kinds = 0;
        if (diffuse_ < limits.diffuse) kinds |= scatter_kind_bit(ScatterKind::Diffuse);
        if (glossy_ < limits.glossy) kinds |= scatter_kind_bit(ScatterKind::Glossy);
        if (transmission_ < limits.transmission) kinds |= scatter_kind_bit(ScatterKind::Transmission);
        return kinds;
    }
    // Whether some count is past its limit: the next hit only emits and passes light through.
    bool exhausted(uint32_t max_bounces, const LightPathLimits& limits) const {
        return total_ > max_bounces || diffuse_ > limits.diffuse || glossy_ > limits.glossy ||
               transmission_ > limits.transmission;
    }

private:
    uint32_t total_ = 0, diffuse_ = 0, glossy_ = 0, transmission_ = 0;
};

// film_clamp_light's scaling of one contribution by a clamp `limit` (0 = off).
inline Rgb clamp_contribution(Rgb c, float limit) {
    if (!(limit > 0.0f)) return c;
    const float sum = std::fabs(c.r) + std::fabs(c.g) + std::fabs(c.b);
    const float most = 3.0f * limit;
    return sum > most ? c * (most / sum) : c;
}

// The clamp of light met at a hit (emission, a lamp, the background) after `scatterings`
// scatterings: direct up to one.
inline float emission_clamp(const LightPathLimits& limits, uint32_t scatterings) {
    return scatterings <= 1 ? limits.clamp_direct : limits.clamp_indirect;
}

// The clamp of a light sample taken at a vertex after `scatterings` scatterings: direct at the
// first vertex.
inline float light_sample_clamp(const LightPathLimits& limits, uint32_t scatterings) {
    return scatterings == 0 ? limits.clamp_direct : limits.clamp_indirect;
}

}  // namespace stratum
