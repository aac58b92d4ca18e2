#include "bsdf/lambert.h"

#include "sampling/warps.h"

namespace stratum {

BsdfEval lambert_eval(const Material& m, Vec3 wo, Vec3 wi) {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return {Rgb(), 0.0f};
    return {m.base_color * (wi.z * kInvPi), cosine_hemisphere_pdf(wi.z)};
}

bool lambert_sample(const Material& m, Vec3 wo, Vec2 u, BsdfSample* out) {
    if (wo.z <= 0.0f) return false;
    const Vec3 wi = sample_cosine_hemisphere(u);
    if (wi.z <= 0.0f) return false;
    // f cos / pdf = (rho/pi) cos / (cos/pi) = rho.
    *out = {wi, m.base_color, cosine_hemisphere_pdf(wi.z)};
    return true;
}

}  // namespace stratum
