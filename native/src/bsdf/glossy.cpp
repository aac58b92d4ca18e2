#include "bsdf/glossy.h"

#include "bsdf/microfacet_ggx.h"
#include "sampling/warps.h"

namespace stratum {

namespace {

float energy_scale(const Material& m, float roughness, float cos_o) {
    if (m.distribution != MicrofacetDistribution::MultiscatterGgx) return 1.0f;
    // With Fresnel 1 the multi-bounce Fresnel F_ms is 1: the missing (1 - E)/E all returns.
    return 1.0f / std::max(ggx_albedo_unit_fresnel(cos_o, roughness), 1e-4f);
}

// The lobe is the closure's only one: a caustics switch drops the closure (sample weight 0).
float glossy_sample_weight(const Material& m) {
    return m.no_glossy_reflection ? 0.0f : tint_sample_weight(m);
}

}  // namespace

BsdfEval glossy_eval(const Material& m, Vec3 wo, Vec3 wi) {
    const float roughness = blurred_roughness(m.roughness, m);
    if (wo.z <= 0.0f || wi.z <= 0.0f || ggx_is_sharp(roughness)) return {Rgb(), 0.0f};
    const float alpha = ggx_alpha_from_roughness(roughness);
    const Vec3 h = normalize(wo + wi);
    const float f = ggx_d(h, alpha) * ggx_g2_height_correlated(wo, wi, alpha) / (4.0f * wo.z);
    // The energy compensation is the host roughness's: Cycles 4.x+ computes it when the closure is
    // set up, before Filter Glossy blurs the lobe (bsdf_blur changes alpha only).
    return {m.base_color * (f * energy_scale(m, m.roughness, wo.z)), ggx_reflection_pdf(wo, wi, alpha)};
}

bool glossy_sample(const Material& m, Vec3 wo, Vec2 u, BsdfSample* out) {
    if (wo.z <= 0.0f) return false;
    const float roughness = blurred_roughness(m.roughness, m);
    if (ggx_is_sharp(roughness)) {
        *out = {Vec3(-wo.x, -wo.y, wo.z), m.base_color, 1.0f, true, ScatterKind::Glossy};
        return true;
    }
    const float alpha = ggx_alpha_from_roughness(roughness);
    Vec3 wi;
    if (!ggx_sample_reflection(wo, alpha, u, &wi)) return false;
    const BsdfEval e = glossy_eval(m, wo, wi);
    if (e.pdf <= 0.0f) return false;
    *out = {wi, e.value / e.pdf, e.pdf, false, ScatterKind::Glossy};
    return true;
}

const ClosureModel kGlossyClosure{
    .eval = [](const Material& m, Vec3 wo, Vec3 wi,
               HemisphereDistribution /*hemisphere*/) { return glossy_eval(m, wo, wi); },
    .sample = [](const Material& m, Vec3 wo, float /*u_lobe*/, Vec2 u, BsdfSample* out,
                 HemisphereDistribution /*hemisphere*/) { return glossy_sample(m, wo, u, out); },
    .is_delta = [](const Material& m) { return ggx_is_sharp(blurred_roughness(m.roughness, m)); },
    .has_transmission = &answer_false,
    .sample_weight = &glossy_sample_weight,
    .albedo_estimate = &tint_albedo_estimate,
    .colors = &tint_glossy_colors,
    .kinds_above = scatter_kind_bit(ScatterKind::Glossy),
    .kinds_below = scatter_kind_bit(ScatterKind::Glossy),
};

}  // namespace stratum
