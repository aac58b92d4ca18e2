// Principled BSDF as Cycles 3.x (Blender 3.0-3.6) evaluates it, reflection part, default
// distribution "GGX" (single scattering). Reference: Cycles 3.4 `svm/closure.h`
// (svm_node_closure_principled), `closure/bsdf_principled_diffuse.h`, `closure/bsdf_microfacet.h`,
// `closure/bsdf_util.h` (interpolate_fresnel_color); Burley 2012 and 2015; Walter et al. 2007.
//
// | parameter  | meaning                                                                     |
// |------------|-----------------------------------------------------------------------------|
// | base_color | diffuse albedo scale; metal F0 (mixed by metallic)                           |
// | roughness  | Burley retro-reflection strength and GGX alpha = roughness^2                |
// | metallic   | diffuse weight (1 - metallic); cspec0 = mix(0.08 specular, base, metallic)   |
// | specular   | F0 = 0.08 specular, ior = 2 / (1 - sqrt(0.08 specular)) - 1 (Specular Tint 0)|
// | transmission | t' = transmission (1 - metallic): glass pair of weight t'; diffuse gets      |
// |            | (1 - metallic)(1 - transmission), the specular lobe 1 - t'                     |
// | ior        | relative IOR of the glass pair (inverted on back faces by the caller)          |
// | coat       | Clearcoat: GTR1 lobe, weight 0.25 coat, Fresnel at IOR 1.5                     |
// | coat_roughness | Clearcoat Roughness: GTR1 alpha = coat_roughness^2 (in [1e-3, 0.999])      |
//
// Transmission as Cycles 3.4 builds it (svm_node_closure_principled, distribution GGX or
// roughness <= 0.05): two closures weighted by the Fresnel F_N = F(cos_o, ior) of the shading
// normal, a GGX reflection with Fresnel 1 (untinted: Specular Tint 0) of weight t' F_N and a GGX
// refraction without Fresnel (bsdf_microfacet_ggx_refraction, Walter 2007 eq. 21 with G1 G1)
// tinted by base_color of weight t' (1 - F_N); Transmission Roughness 0 (refraction roughness =
// roughness). Below Cycles' sharp threshold both are Dirac lobes. Not energy conserving at
// roughness > 0 (each lobe loses its shadowing), as in Cycles.
// Clearcoat: 0.25 coat F(wi.h, 1.5) D_GTR1(h) G1(wo) G1(wi) / (4 cos_o), G1 of a fixed GGX
// alpha 0.25 (Cycles 3.4 bsdf_microfacet.h, Burley 2012 appendix); sampled from D_GTR1 cos(h).
// f = (1 - metallic) base f_burley + F(wi.h) D G1(wo) G1(wi) / (4 cos_o cos_i)
// f_burley = (1/pi) (1 + (Fd90 - 1) FL)(1 + (Fd90 - 1) FV), Fd90 = 0.5 + 2 roughness cos^2(theta_d),
// FL, FV = Schlick weights (1 - cos)^5 of wi, wo; cos(theta_d) = wi.h. The diffuse is not reduced
// by the specular (no energy conservation): with roughness 1 its albedo exceeds Lambert's, the
// source of Cycles 3.x Principled renders being brighter than a Diffuse BSDF.
// F = cspec0 (1 - FH) + FH, FH = (F_dielectric(wi.h, ior) - F0) / (1 - F0). The specular lobe
// exists only when specular > 0 or metallic > 0, as in Cycles.
// Colour passes, Cycles 3.4's closure weights (surface_shader_diffuse/glossy/transmission sum
// sc->weight by closure type): Diffuse Color = (1 - metallic)(1 - transmission) base_color;
// Glossy Color = (1 - t') for the specular closure (when it exists) + t' F_N for the glass
// reflection + 1 for the clearcoat closure (its weight is the node's; 0.25 coat is inside its
// Fresnel colour); Transmission Color = t' max(1 - F_N, 1e-4) base_color (Cycles keeps 1e-4).
#pragma once

#include "bsdf/bsdf.h"

namespace stratum {

BsdfEval principled_v1_eval(const Material& m, Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere);
bool principled_v1_sample(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                          HemisphereDistribution hemisphere);

// STRATUM_MATERIAL_PRINCIPLED_V1.
extern const ClosureModel kPrincipledV1Closure;

}  // namespace stratum
