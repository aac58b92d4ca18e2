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
//
// f = (1 - metallic) base f_burley + F(wi.h) D G1(wo) G1(wi) / (4 cos_o cos_i)
// f_burley = (1/pi) (1 + (Fd90 - 1) FL)(1 + (Fd90 - 1) FV), Fd90 = 0.5 + 2 roughness cos^2(theta_d),
// FL, FV = Schlick weights (1 - cos)^5 of wi, wo; cos(theta_d) = wi.h. The diffuse is not reduced
// by the specular (no energy conservation): with roughness 1 its albedo exceeds Lambert's, the
// source of Cycles 3.x Principled renders being brighter than a Diffuse BSDF.
// F = cspec0 (1 - FH) + FH, FH = (F_dielectric(wi.h, ior) - F0) / (1 - F0). The specular lobe
// exists only when specular > 0 or metallic > 0, as in Cycles.
#pragma once

#include "bsdf/bsdf.h"

namespace stratum {

BsdfEval principled_v1_eval(const Material& m, Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere);
bool principled_v1_sample(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                          HemisphereDistribution hemisphere);

}  // namespace stratum
