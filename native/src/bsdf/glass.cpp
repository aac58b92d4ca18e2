#include "bsdf/glass.h"

#include "bsdf/glass_albedo.h"
#include "bsdf/glossy.h"
#include "bsdf/microfacet_ggx.h"
#include "sampling/warps.h"

namespace stratum {

namespace {

// Visible-normal density of h seen from wo (Heitz 2018, eq. 3).
float visible_normal_density(Vec3 wo, Vec3 h, float alpha) {
    const float cos_oh = dot(wo, h);
    if (cos_oh <= 0.0f) return 0.0f;
    return ggx_g1(wo, alpha) * cos_oh * ggx_d(h, alpha) / wo.z;
}

// The caustics switches drop the reflection or the refraction (Cycles 5.0 zeroes that tint;
// 3.4 skips that closure of the pair): the closure goes when both are dropped.
float glass_sample_weight(const Material& m) {
    return m.no_glossy_reflection && m.no_glossy_refraction ? 0.0f : tint_sample_weight(m);
}

}  // namespace

ClosureColors glass_colors(const Material& m, Vec3 wo) {
    const float fresnel = fresnel_dielectric(wo.z, m.ior);
    return {Rgb(), m.base_color * fresnel, m.base_color * (1.0f - fresnel)};
}

bool refract_direction(Vec3 wo, Vec3 h, float eta, Vec3* wi) {
    const float c = dot(wo, h);
    const float sin2_t = (1.0f - c * c) / (eta * eta);
    if (sin2_t >= 1.0f) return false;
    const float cos_t = std::sqrt(1.0f - sin2_t);
    *wi = normalize(-wo / eta + h * (c / eta - cos_t));
    return true;
}

DielectricEval dielectric_ggx_eval(Vec3 wo, Vec3 wi, float alpha, float eta) {
    DielectricEval e{0.0f, 0.0f, 0.0f, 0.0f};
    if (wo.z <= 0.0f || wi.z == 0.0f) return e;
    if (wi.z > 0.0f) {
        const Vec3 h = normalize(wo + wi);
        const float cos_oh = dot(wo, h);
        if (cos_oh <= 0.0f) return e;
        const float f = fresnel_dielectric(cos_oh, eta);
        e.reflect_value = f * ggx_d(h, alpha) * ggx_g2_height_correlated(wo, wi, alpha) / (4.0f * wo.z);
        e.reflect_pdf = f * visible_normal_density(wo, h, alpha) / (4.0f * cos_oh);
        return e;
    }
    Vec3 h = wo + wi * eta;
    const float len = length(h);
    if (len <= 0.0f) return e;
    h = h / len;
    if (h.z < 0.0f) h = -h;
    const float cos_oh = dot(wo, h), cos_ih = dot(wi, h);
    // wo must see the microfacet from above and wi leave it from below.
    if (cos_oh <= 0.0f || cos_ih >= 0.0f) return e;
    const float f = fresnel_dielectric(cos_oh, eta);
    if (f >= 1.0f) return e;
    const float denom = sqr(cos_oh + eta * cos_ih);
    const float jacobian = eta * eta * std::abs(cos_ih) / denom;  // Walter 2007, eq. 17
    const Vec3 wi_up(wi.x, wi.y, -wi.z);
    // G2 is symmetric in the hemisphere of wi (Lambda depends on |cos|).
    e.transmit_value =
        (1.0f - f) * ggx_d(h, alpha) * ggx_g2_height_correlated(wo, wi_up, alpha) * cos_oh * jacobian / wo.z;
    e.transmit_pdf = (1.0f - f) * visible_normal_density(wo, h, alpha) * jacobian;
    return e;
}

bool dielectric_ggx_sample(Vec3 wo, float alpha, float eta, float u_event, Vec2 u, Vec3* wi,
                           bool* transmitted) {
    if (wo.z <= 0.0f) return false;
    const Vec3 h = sample_ggx_visible_normal(wo, alpha, u);
    const float cos_oh = dot(wo, h);
    if (cos_oh <= 0.0f) return false;
    const float f = fresnel_dielectric(cos_oh, eta);
    if (u_event < f) {
        *wi = h * (2.0f * cos_oh) - wo;
        *transmitted = false;
        return wi->z > 0.0f;
    }
    if (!refract_direction(wo, h, eta, wi)) return false;
    *transmitted = true;
    return wi->z < 0.0f;
}

float glass_energy_scale(MicrofacetDistribution distribution, float cos_o, float roughness, float eta) {
    if (distribution != MicrofacetDistribution::MultiscatterGgx) return 1.0f;
    return 1.0f / std::max(ggx_glass_albedo(cos_o, roughness, eta), 1e-3f);
}

BsdfEval glass_eval(const Material& m, Vec3 wo, Vec3 wi) {
    const float roughness = blurred_roughness(m.roughness, m);
    if (ggx_is_sharp(roughness) || wo.z <= 0.0f) return {Rgb(), 0.0f};
    const DielectricEval e = dielectric_ggx_eval(wo, wi, ggx_alpha_from_roughness(roughness), m.ior);
    // Compensated for the host roughness (Cycles sets it up before Filter Glossy blurs alpha).
    const float scale = glass_energy_scale(m.distribution, wo.z, m.roughness, m.ior);
    const float reflected = m.no_glossy_reflection ? 0.0f : e.reflect_value;
    const float transmitted = m.no_glossy_refraction ? 0.0f : e.transmit_value;
    return {m.base_color * ((reflected + transmitted) * scale), e.reflect_pdf + e.transmit_pdf};
}

bool glass_sample(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out) {
    if (wo.z <= 0.0f) return false;
    const float roughness = blurred_roughness(m.roughness, m);
    if (ggx_is_sharp(roughness)) {
        const float f = fresnel_dielectric(wo.z, m.ior);
        // A dropped side (caustics switches) carries nothing: the path ends there.
        if (u_lobe < f) {
            if (m.no_glossy_reflection) return false;
            *out = {Vec3(-wo.x, -wo.y, wo.z), m.base_color, 1.0f, true, ScatterKind::Glossy};
            return true;
        }
        Vec3 wi;
        if (m.no_glossy_refraction || !refract_direction(wo, Vec3(0.0f, 0.0f, 1.0f), m.ior, &wi))
            return false;
        *out = {wi, m.base_color, 1.0f, true, ScatterKind::Transmission};
        return true;
    }
    const float alpha = ggx_alpha_from_roughness(roughness);
    Vec3 wi;
    bool transmitted = false;
    if (!dielectric_ggx_sample(wo, alpha, m.ior, u_lobe, u, &wi, &transmitted)) return false;
    const BsdfEval e = glass_eval(m, wo, wi);
    if (e.pdf <= 0.0f) return false;
    *out = {wi, e.value / e.pdf, e.pdf, false, transmitted ? ScatterKind::Transmission : ScatterKind::Glossy};
    return true;
}

const ClosureModel kGlassClosure{
    .eval = [](const Material& m, Vec3 wo, Vec3 wi,
               HemisphereDistribution /*hemisphere*/) { return glass_eval(m, wo, wi); },
    .sample = [](const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                 HemisphereDistribution /*hemisphere*/) { return glass_sample(m, wo, u_lobe, u, out); },
    .is_delta = [](const Material& m) { return ggx_is_sharp(blurred_roughness(m.roughness, m)); },
    .has_transmission = &answer_true,
    .sample_weight = &glass_sample_weight,
    .albedo_estimate = &tint_albedo_estimate,
    .colors = &glass_colors,
    .kinds_above = scatter_kind_bit(ScatterKind::Glossy),
    .kinds_below = scatter_kind_bit(ScatterKind::Transmission),
};

}  // namespace stratum
