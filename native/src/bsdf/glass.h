// Cycles' Glass BSDF (4.x form): a rough dielectric interface, GGX reflection and refraction
// chosen by the exact Fresnel term of the microfacet, both tinted by the node colour.
// Reference: Walter et al. 2007, "Microfacet Models for Refraction through Rough Surfaces"
// (eqs. 20-22, 40); Heitz 2014 (height-correlated G2); Heitz 2018 (VNDF sampling); Cycles 4.x
// `closure/bsdf_microfacet.h` (bsdf_microfacet_ggx_glass_setup, Fresnel from wo.h).
//
// | parameter  | meaning                                                                       |
// |------------|-------------------------------------------------------------------------------|
// | base_color | tint of both reflection and refraction                                        |
// | roughness  | alpha = roughness^2; alpha^2 <= 1e-7: smooth (delta) glass                    |
// | ior        | relative IOR eta of the side below the shading horizon over wo's side (the    |
// |            | caller inverts it on back faces); eta < 1 gives total internal reflection     |
//
// h_r = normalize(wo + wi), h_t = -normalize(wo + eta wi) (turned to z > 0), F = F_dielectric(wo.h)
// reflect: f cos_i = F D G2 / (4 cos_o);  pdf = F D_v(h) / (4 wo.h)
// refract: f cos_i = (1 - F) D G2 eta^2 |wi.h| (wo.h) / (cos_o (wo.h + eta wi.h)^2);
//          pdf = (1 - F) D_v(h) eta^2 |wi.h| / (wo.h + eta wi.h)^2
// (D_v = G1(wo) (wo.h) D / cos_o the visible normals). The sampled weight is G2/G1 <= 1 for both
// events, so reflection + refraction never exceeds 1. No 1/eta^2 radiance scaling, as Cycles.
// Smooth glass: reflect with probability F(cos_o), refract otherwise, weight exactly base_color.
// distribution Multiscatter GGX (Blender 4.x/5.0's default for this node): f scaled by
// 1/E_glass(cos_o) (glass_albedo.h), so white rough glass keeps all energy, as Cycles 4.x/5.0.
// Cycles 3.4's Glass node (default Beckmann, or GGX) is two closures weighted by the Fresnel of
// the shading normal; its albedo differs little (3.4 GGX 0.988 against 0.980 here at roughness 0.5,
// IOR 1.45, 45 degrees) and is not modelled separately.
// Colour passes: Glossy Color = base F(cos_o, eta), Transmission Color = base (1 - F(cos_o, eta)),
// F the smooth dielectric Fresnel of the shading normal: Cycles 3.4's glass closure pair weights
// (which keep at least 1e-4 for the refraction) and Cycles 4.x's bsdf_albedo of its glass closure
// for smooth glass (4.x reads the rough reflectance mix(F0, 1, s) from its GGX tables instead).
#pragma once

#include "bsdf/bsdf.h"

namespace stratum {

// The two parts of a rough dielectric lobe with unit tint, for reuse by the Principled models.
struct DielectricEval {
    float reflect_value, transmit_value;  // f cos_i of each event (one of them is 0)
    float reflect_pdf, transmit_pdf;      // the densities glass sampling gives them
};
DielectricEval dielectric_ggx_eval(Vec3 wo, Vec3 wi, float alpha, float eta);
// Draws one event; `transmitted` tells which. Returns false when nothing is produced.
bool dielectric_ggx_sample(Vec3 wo, float alpha, float eta, float u_event, Vec2 u, Vec3* wi,
                           bool* transmitted);
// The refracted direction of wo about the normal h with relative IOR eta; false on total
// internal reflection.
bool refract_direction(Vec3 wo, Vec3 h, float eta, Vec3* wi);

// 1 for single-scatter GGX; 1/E_glass for Multiscatter GGX.
float glass_energy_scale(MicrofacetDistribution distribution, float cos_o, float roughness, float eta);

// The colour passes of a Glass closure (see above).
ClosureColors glass_colors(const Material& m, Vec3 wo);

BsdfEval glass_eval(const Material& m, Vec3 wo, Vec3 wi);
bool glass_sample(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out);

// STRATUM_MATERIAL_GLASS.
extern const ClosureModel kGlassClosure;

}  // namespace stratum
