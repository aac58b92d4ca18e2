// Principled BSDF in the manner of Cycles 4.x (Blender 4.0-5.0), reflection part, default
// distribution "Multiscatter GGX", Diffuse Roughness 0, tints white, no coat/sheen/transmission.
// Reference: Cycles 4.x `svm/closure.h` (Principled: metal, then dielectric specular layer whose
// albedo attenuates the diffuse below), `closure/bsdf_microfacet.h`; Heitz 2014 (height-correlated
// Smith), Kulla & Conty 2017 (multiple-scattering energy compensation), Hoffman 2023 (F82 tint).
//
// | parameter  | meaning                                                                  |
// |------------|--------------------------------------------------------------------------|
// | base_color | Lambert albedo under the specular layer; metal F0                        |
// | roughness  | GGX alpha = roughness^2 for both microfacet lobes                        |
// | metallic   | mix: metallic f_metal + (1 - metallic) (f_spec + f_diffuse)              |
// | specular   | Specular IOR Level: F0 = F0(ior) 2 level, ior re-derived (0.5 = unchanged) |
// | ior        | dielectric IOR of the specular layer (default 1.5) and of the glass lobe |
// | transmission | weight of a glass lobe (glass.h) replacing spec + diffuse: reflection     |
// |            | untinted, refraction tinted by base_color; single-scatter GGX             |
// | coat       | Coat Weight: dielectric GGX layer (single scatter) on top of everything   |
// | coat_roughness, coat_ior | its roughness and IOR                                     |
// | coat_tint  | absorption of what passes the coat: tint^(1/cos_t), cos_t refracted into it |
//
// Layering as Cycles 4.x/5.0 svm_node_closure_principled: coat first (weight coat; the layers
// below are scaled by (1 - coat F_v,coat(cos_o)) and mix(1, coat_tint^(1/cos_t), coat)), then
// metal (metallic), then transmission ((1 - metallic) transmission: glass), then the specular
// layer over the diffuse ((1 - metallic)(1 - transmission)). The glass lobe has no
// multiple-scattering compensation here (Cycles 4.x compensates Multiscatter GGX glass).
//
// f_spec  = F(wi.h, eta) D G2 / (4 cos_o cos_i) * c(cos_o),   A_spec(cos_o) = E_F c its albedo
// f_diff  = (1 - A_layer(cos_o)) base / pi    (Cycles' layering by its albedo *estimate*)
// f_metal = F_schlick(wi.h, base) D G2 / (4 cos_o cos_i) * c_metal(cos_o)   (F82 tint = white)
// Multiscatter GGX: c = 1 + F_ms (1 - E(cos_o)) / E(cos_o), F_ms = F_avg E_avg / (1 - F_avg (1 -
//   E_avg)), the energy lost by single scattering returned with the average multi-bounce Fresnel;
//   A_layer = F_v E c.
// GGX: c = c_metal = 1 and A_layer = F_v, larger than A_spec = E_F by about 1/E: not energy
//   conserving, exactly as Cycles (which assumes a lossless lobe in its estimate).
// F_v = ggx_visible_fresnel_dielectric: the visible-normal mean Fresnel Cycles tabulates
// (microfacet_ggx.h). E, E_avg, E_F, F_v, F_avg come from tables this code computes once.
// The layering factors depend on wo only, so, like Cycles, this model is not reciprocal.
// Colour passes, Cycles 4.x's bsdf_albedo of each closure summed by type, from the same layering:
// Diffuse Color = b (1 - metallic)(1 - transmission)(1 - A_layer) base; Glossy Color =
// b [(1 - metallic)(1 - transmission) A_layer + metallic F_schlick(cos_o, base) + (1 - metallic)
// transmission F(cos_o, ior)] + coat F_v,coat; Transmission Color = b (1 - metallic) transmission
// (1 - F(cos_o, ior)) base, b the coat's base_scale. Cycles reads the metal's and rough glass
// reflection's estimates from GGX tables (mix(F0, 1, s)); here the smooth-surface Fresnel of wo.
// Which distribution a material uses is the node's `distribution` (Blender 4.x/5.0 default
// Multiscatter GGX; files saved by 3.x keep GGX).
#pragma once

#include "bsdf/bsdf.h"

namespace stratum {

// The microfacet distribution is m.distribution (Blender 4.x/5.0 default Multiscatter GGX).
BsdfEval principled_v2_eval(const Material& m, Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere);
bool principled_v2_sample(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                          HemisphereDistribution hemisphere);

// STRATUM_MATERIAL_PRINCIPLED_V2.
extern const ClosureModel kPrincipledV2Closure;

}  // namespace stratum
