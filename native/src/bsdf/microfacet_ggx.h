// GGX (Trowbridge-Reitz) microfacet building blocks shared by the Principled models, plus the
// directional-albedo tables the energy-conserving (4.x-style) layering needs.
//
// | symbol       | formula                                                          | reference            |
// |--------------|------------------------------------------------------------------|----------------------|
// | alpha        | roughness^2 (clamped to kGgxMinAlpha)                            | Burley 2012          |
// | D(h)         | alpha^2 / (pi (cos^2(h) (alpha^2 - 1) + 1)^2)                    | Walter 2007, eq. 33  |
// | Lambda(w)    | (-1 + sqrt(1 + alpha^2 tan^2(w))) / 2                            | Heitz 2014, eq. 72   |
// | G1(w)        | 1 / (1 + Lambda(w))                                              | Heitz 2014           |
// | G2 separable | G1(wo) G1(wi)            (Cycles 3.x)                            | Walter 2007, eq. 23  |
// | G2 height    | 1 / (1 + Lambda(wo) + Lambda(wi))   (Cycles 4.x)                 | Heitz 2014, eq. 99   |
// | f_spec       | F D G2 / (4 |wo.z| |wi.z|)                                        | Walter 2007, eq. 20  |
// | pdf (VNDF)   | G1(wo) D(h) / (4 wo.z), wi = reflect(wo, h)                      | Heitz 2018, eq. 17   |
// | F dielectric | unpolarised exact Fresnel for relative IOR eta                   | Walter 2007, eq. 22  |
//
// The tables are computed by this code at first use (thread-safe static), never copied.
#pragma once

#include "core/math.h"

namespace stratum {

// Below this alpha the lobe is a near-mirror; clamping keeps D finite in float and lets the
// lobe stay a regular density that NEE and MIS can evaluate.
inline constexpr float kGgxMinAlpha = 1e-3f;

inline float ggx_alpha_from_roughness(float roughness) {
    return std::max(sqr(std::clamp(roughness, 0.0f, 1.0f)), kGgxMinAlpha);
}

inline float ggx_d(Vec3 h, float alpha) {
    if (h.z <= 0.0f) return 0.0f;
    const float a2 = alpha * alpha;
    const float t = h.z * h.z * (a2 - 1.0f) + 1.0f;
    return a2 / (kPi * t * t);
}
inline float ggx_lambda(Vec3 w, float alpha) {
    const float cos2 = w.z * w.z;
    if (cos2 <= 0.0f) return 1e30f;  // grazing: fully shadowed, G1 = 0
    const float tan2 = std::max(1.0f - cos2, 0.0f) / cos2;
    return 0.5f * (-1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
}
inline float ggx_g1(Vec3 w, float alpha) { return 1.0f / (1.0f + ggx_lambda(w, alpha)); }
inline float ggx_g2_separable(Vec3 wo, Vec3 wi, float alpha) { return ggx_g1(wo, alpha) * ggx_g1(wi, alpha); }
inline float ggx_g2_height_correlated(Vec3 wo, Vec3 wi, float alpha) {
    return 1.0f / (1.0f + ggx_lambda(wo, alpha) + ggx_lambda(wi, alpha));
}

// Solid-angle density of wi = reflect(wo, h) when h is drawn from the visible normals of wo.
inline float ggx_reflection_pdf(Vec3 wo, Vec3 wi, float alpha) {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return 0.0f;
    const Vec3 h = normalize(wo + wi);
    // Visible-normal density G1 max(0, wo.h) D / wo.z times the reflection Jacobian 1/(4 wo.h).
    return ggx_g1(wo, alpha) * ggx_d(h, alpha) / (4.0f * wo.z);
}
// Draws wi by VNDF sampling; returns false when the reflected direction falls below the horizon.
bool ggx_sample_reflection(Vec3 wo, float alpha, Vec2 u, Vec3* wi);

// Exact unpolarised Fresnel reflectance at a dielectric interface, relative IOR eta (> 0).
inline float fresnel_dielectric(float cos_i, float eta) {
    // Walter et al. 2007, eq. 22 (g^2 < 0 means total internal reflection).
    const float c = std::abs(cos_i);
    const float g2 = eta * eta - 1.0f + c * c;
    if (g2 <= 0.0f) return 1.0f;
    const float g = std::sqrt(g2);
    const float a = (g - c) / (g + c);
    const float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
    return 0.5f * a * a * (1.0f + b * b);
}
// Normal-incidence reflectance ((eta-1)/(eta+1))^2 and its inverse (clamped as Cycles does, F0 <= 0.99).
inline float f0_from_ior(float eta) { return sqr((eta - 1.0f) / (eta + 1.0f)); }
inline float ior_from_f0(float f0) {
    const float s = std::sqrt(std::clamp(f0, 0.0f, 0.99f));
    return (1.0f + s) / (1.0f - s);
}
// Schlick 1994: F0 + (1 - F0)(1 - cos)^5.
inline float schlick_weight(float cos_i) {
    const float m = std::clamp(1.0f - cos_i, 0.0f, 1.0f);
    return (m * m) * (m * m) * m;
}

// Directional albedo of the single-scattering GGX lobe (height-correlated G2) with F = 1:
// E(mu_o) = integral of D G2 / (4 mu_o) over wi. Its cosine-weighted average E_avg = 2 int E mu dmu.
float ggx_albedo_unit_fresnel(float cos_o, float roughness);
float ggx_average_albedo_unit_fresnel(float roughness);
// Same lobe with the exact dielectric Fresnel F(wi.h, eta), eta >= 1.
float ggx_albedo_dielectric(float cos_o, float roughness, float eta);
// Cycles 4.x/5.0's estimate of that lobe's albedo, by which its Principled BSDF attenuates the
// layers below (kernel `bsdf_microfacet_estimate_albedo`, table `ggx_gen_schlick_ior_s` made by
// `cycles_precompute`): F_v = F0 + (1 - F0) s_v, s_v = E_h[ 1{wi.z > 0} (F(wo.h) - F0)/(1 - F0) ]
// over the visible normals h of wo (VNDF), wi = reflect(wo, h). Unlike E_F / E it is not weighted
// by the shadowing G2/G1 of wi, and reflections below the horizon count as 0 but stay in the
// mean; grazing views get a larger estimate (roughness 0.5, eta 1.45, 10 degrees above the
// surface: F_v = 0.168 against E_F/E = 0.158, E_F = 0.135; measured in Cycles 5.0: 0.168).
float ggx_visible_fresnel_dielectric(float cos_o, float roughness, float eta);
// Hemispherical (cosine-weighted) average of the dielectric Fresnel: 2 int F(mu, eta) mu dmu.
float fresnel_dielectric_average(float eta);

}  // namespace stratum
