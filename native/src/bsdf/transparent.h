// Cycles' Transparent BSDF: light passes straight through, unrefracted, tinted.
//
// | parameter  | meaning                                                          |
// |------------|------------------------------------------------------------------|
// | base_color | tint T of what passes: f = T δ(wi + wo), sampled weight exactly T |
//
// Reference: Cycles `closure/bsdf_transparent.h` (bsdf_transparent_sample: wi = −wo, a Dirac,
// pdf 1 by convention). Shadow rays pass it too: ClosureSet sums w_i T_i as the shading point's
// transparency (integrators/transparent_shadow.h).
// Colour passes: none (Cycles' transparent closure is none of diffuse, glossy, transmission); the
// surfaces behind it enter them through the path's throughput, tinted by T.
#pragma once

#include "bsdf/bsdf.h"

namespace stratum {

inline bool transparent_sample(const Material& m, Vec3 wo, float /*u_lobe*/, Vec2 /*u*/, BsdfSample* out,
                               HemisphereDistribution /*hemisphere*/) {
    *out = {-wo, m.base_color, 1.0f, true, ScatterKind::Transparent};
    return true;
}

// A Dirac: bsdf_eval gives no value for any given pair of directions.
inline constexpr ClosureModel kTransparentClosure{
    .eval = &no_scattering_eval,
    .sample = &transparent_sample,
    .is_delta = &answer_true,
    .has_transmission = &answer_true,
    .sample_weight = &tint_sample_weight,
    .albedo_estimate = &tint_albedo_estimate,
    .kinds_above = scatter_kind_bit(ScatterKind::Transparent),
    .kinds_below = scatter_kind_bit(ScatterKind::Transparent),
    .transparent = true,
};

}  // namespace stratum
