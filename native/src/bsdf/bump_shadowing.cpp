#include "bsdf/bump_shadowing.h"

#include <algorithm>
#include <cmath>

namespace stratum {

namespace {

// Chiang et al. 2019 eq. 4 with Cycles' choice of Ns for the geometric normal: g compares the
// cosine the smooth surface sees with the one the perturbed normal claims.
float chiang_term(Vec3 ns, Vec3 wi, bool smoothed) {
    const float cos_ni = wi.z;
    if (cos_ni < 0.0f) ns = -ns;
    const float denominator = cos_ni * ns.z;
    const float g = denominator != 0.0f ? dot(ns, wi) / denominator : 0.0f;
    if (g >= 1.0f) return 1.0f;
    if (g < 0.0f) return 0.0f;
    if (!smoothed) return 1.0f;
    const float g2 = g * g;
    return -g2 * g + g2 + g;
}

// Conty Estevez et al. 2019: the bumps are read as GGX microfacets whose roughness makes the
// average normal deviation tan^2 = 8 alpha^2 (sec. 3); their shadowing G1 at the smooth cosine.
float conty_smoothing(float cos_nsi, float cos_nsn) {
    const float cos_i = std::abs(cos_nsi), cos_d = std::abs(cos_nsn);
    if (cos_d >= 1.0f || cos_i >= 1.0f) return 1.0f;
    if (cos_i < 1e-6f) return 0.0f;
    const float alpha2 = std::clamp(0.125f * (1.0f / (cos_d * cos_d) - 1.0f), 0.0f, 1.0f);
    const float cos2 = cos_i * cos_i;
    const float tan2 = (1.0f - cos2) / cos2;
    const float lambda = 0.5f * (std::sqrt(1.0f + alpha2 * tan2) - 1.0f);  // GGX Smith Lambda
    return 1.0f / (1.0f + lambda);
}

}  // namespace

BumpShadowingFactors bump_shadowing(BumpShadowing model, Vec3 smooth_normal, Vec3 wi, bool sampled) {
    switch (model) {
        case BumpShadowing::None:
            break;
        case BumpShadowing::Chiang:
        case BumpShadowing::ChiangUnsmoothed:
            return {1.0f, chiang_term(smooth_normal, wi, model == BumpShadowing::Chiang)};
        case BumpShadowing::Conty:
        case BumpShadowing::ContyUnsmoothed: {
            // wi and N on different sides of the smooth surface, yet wi on N's reflection side
            // (or the same side, yet on N's transmission side): light through opaque geometry.
            const float cos_nsi = dot(smooth_normal, wi), cos_nsn = smooth_normal.z;
            const bool leaks = cos_nsi * cos_nsn * wi.z < 0.0f;
            BumpShadowingFactors f;
            f.all = leaks && !sampled ? 0.0f : 1.0f;
            f.diffuse =
                leaks ? 0.0f : (model == BumpShadowing::Conty ? conty_smoothing(cos_nsi, cos_nsn) : 1.0f);
            return f;
        }
    }
    return {};
}

}  // namespace stratum
