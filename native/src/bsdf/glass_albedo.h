// Directional albedo of the single-scattering rough dielectric (glass.h) with unit tint,
// E_glass(cos_o, roughness, eta) = E_h[ F G2(wo, wi_r)/G1(wo) + (1 - F) G2(wo, wi_t)/G1(wo) ]
// over the visible normals h of wo (reflected wi_r above, refracted wi_t below the surface;
// F = F_dielectric(wo.h, eta)), and the Multiscatter GGX energy scale 1/E_glass that Cycles 4.x/5.0
// applies to its glass (Kulla & Conty 2017 albedo scaling; measured: Blender 5.0.1 Glass BSDF,
// Multiscatter GGX, roughness 0.5, IOR 1.45, 45 degrees: albedo 0.9994, GGX 0.9792).
//
// | axis      | grid                                                    |
// |-----------|---------------------------------------------------------|
// | cos_o     | 32 points on [0, 1] (the first at 1e-3)                 |
// | roughness | 32 points on [0, 1], alpha = roughness^2 (>= 1e-3)      |
// | eta       | 33 points of x = (eta - 1)/(eta + 1) on [-0.5, 0.5], i.e. eta in [1/3, 3]; |
// |           | outside that range the nearest entry                     |
// Each entry: 16 x 16 stratified VNDF midpoints (the integrand is bounded by 1). Built by this
// code at first use (thread-safe static), trilinear lookup.
#pragma once

namespace stratum {

float ggx_glass_albedo(float cos_o, float roughness, float eta);

}  // namespace stratum
