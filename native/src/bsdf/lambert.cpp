#include "bsdf/lambert.h"

#include "sampling/warps.h"

namespace stratum {

BsdfEval lambert_eval(const Material& m, Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere) {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return {Rgb(), 0.0f};
    const Rgb value = m.base_color * (wi.z * kInvPi);
    return {value, hemisphere_pdf(hemisphere, wi.z), value};
}

bool lambert_sample(const Material& m, Vec3 wo, Vec2 u, BsdfSample* out, HemisphereDistribution hemisphere) {
    if (wo.z <= 0.0f) return false;
    const Vec3 wi = sample_hemisphere(hemisphere, u);
    const float pdf = hemisphere_pdf(hemisphere, wi.z);
    if (wi.z <= 0.0f || !(pdf > 0.0f)) return false;
    // f cos / pdf: exactly rho for cosine sampling, rho cos/(pi pdf) otherwise.
    *out = {wi, m.base_color * (wi.z * kInvPi / pdf), pdf};
    return true;
}

const ClosureModel kLambertClosure{
    .eval = &lambert_eval,
    .sample = [](const Material& m, Vec3 wo, float /*u_lobe*/, Vec2 u, BsdfSample* out,
                 HemisphereDistribution hemisphere) { return lambert_sample(m, wo, u, out, hemisphere); },
    .is_delta = &answer_false,
    .has_transmission = &answer_false,
    .sample_weight = &tint_sample_weight,
    .albedo_estimate = &tint_albedo_estimate,
    .colors = &tint_diffuse_colors,
    // Diffuse whichever side wi is on (it has no value below).
    .kinds_above = scatter_kind_bit(ScatterKind::Diffuse),
    .kinds_below = scatter_kind_bit(ScatterKind::Diffuse),
    .lambertian = true,
};

}  // namespace stratum
