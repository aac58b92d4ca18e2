// Cycles' Glossy BSDF: GGX microfacet reflection with Fresnel = 1, tinted by the node colour.
// Reference: Cycles 3.4 / 4.x `closure/bsdf_microfacet.h` (microfacet_ggx with constant Fresnel),
// Walter et al. 2007 (GGX), Heitz 2014 (height-correlated Smith G2), Heitz 2018 (VNDF sampling),
// Kulla & Conty 2017 / Turquin 2019 (multiple-scattering energy compensation).
//
// | parameter    | meaning                                                                  |
// |--------------|--------------------------------------------------------------------------|
// | base_color   | colour tint of the reflection (Cycles: the closure weight)               |
// | roughness    | alpha = roughness^2; alpha^2 <= 1e-7 is a perfect mirror (delta lobe),   |
// |              | Cycles' "sharp" threshold alpha_x alpha_y <= 1e-7                        |
// | distribution | Ggx: single scattering; MultiscatterGgx: f scaled by 1/E(cos_o) so the   |
// |              | lobe reflects all energy (Fresnel 1 gives F_ms = 1)                       |
//
// f cos_i = base D(h) G2(wo, wi) / (4 cos_o) * c(cos_o), c = 1 or 1/E(cos_o).
// pdf = VNDF: G1(wo) D(h) / (4 cos_o); sampled weight = base G2/G1 c.
// Colour passes: Glossy Color = base_color (3.x: the closure weight; 4.x: its bsdf_albedo, the
// weight times a constant Fresnel of 1, with no multi-bounce darkening for F = 1).
#pragma once

#include "bsdf/bsdf.h"

namespace stratum {

// Whether roughness makes the GGX lobe a Dirac (Cycles: alpha_x alpha_y <= 1e-7).
inline bool ggx_is_sharp(float roughness) {
    const float alpha = roughness * roughness;
    return alpha * alpha <= 1e-7f;
}

BsdfEval glossy_eval(const Material& m, Vec3 wo, Vec3 wi);
bool glossy_sample(const Material& m, Vec3 wo, Vec2 u, BsdfSample* out);

// STRATUM_MATERIAL_GLOSSY.
extern const ClosureModel kGlossyClosure;

}  // namespace stratum
