#include "bsdf/principled_v1.h"

#include "bsdf/microfacet_ggx.h"
#include "sampling/warps.h"

namespace stratum {

namespace {

// Cycles treats weights below this as absent closures (CLOSURE_WEIGHT_CUTOFF).
constexpr float kClosureCutoff = 1e-5f;

struct LobesV1 {
    Rgb diffuse_color;  // (1 - metallic) base_color
    bool has_specular;
    float alpha, ior, f0;
    Rgb cspec0;
    float diffuse_probability;  // lobe selection; 1 - this for the specular lobe
};

LobesV1 setup(const Material& m, Vec3 wo) {
    LobesV1 l;
    const float metallic = std::clamp(m.metallic, 0.0f, 1.0f);
    const float specular = std::max(m.specular, 0.0f);
    l.diffuse_color = m.base_color * (1.0f - metallic);
    l.has_specular = specular > kClosureCutoff || metallic > kClosureCutoff;
    l.alpha = ggx_alpha_from_roughness(m.roughness);
    l.ior = 2.0f / (1.0f - safe_sqrt(0.08f * specular)) - 1.0f;
    l.f0 = f0_from_ior(l.ior);  // equals 0.08 specular
    l.cspec0 = Rgb(0.08f * specular) * (1.0f - metallic) + m.base_color * metallic;
    // Cycles weights lobe selection by the closure weight times, for the specular, the average
    // Fresnel colour seen from wo at normal incidence on the microfacets (h = n).
    const float diffuse_weight = std::max(l.diffuse_color.average(), 0.0f);
    float specular_weight = 0.0f;
    if (l.has_specular) {
        const float fh = (fresnel_dielectric(wo.z, l.ior) - l.f0) / (1.0f - l.f0);
        specular_weight = (l.cspec0 * (1.0f - fh) + Rgb(fh)).average();
    }
    const float total = diffuse_weight + specular_weight;
    l.diffuse_probability = total > 0.0f ? diffuse_weight / total : 0.0f;
    return l;
}

float burley_diffuse(Vec3 wo, Vec3 wi, float roughness) {
    // Burley 2012, "Physically Based Shading at Disney", §5.3; 2 cos^2(theta_d) = 1 + wo.wi.
    const float fl = schlick_weight(wi.z), fv = schlick_weight(wo.z);
    const float fd90 = 0.5f + roughness * (1.0f + dot(wo, wi));
    return kInvPi * (1.0f + (fd90 - 1.0f) * fl) * (1.0f + (fd90 - 1.0f) * fv);
}

Rgb specular_value(const LobesV1& l, Vec3 wo, Vec3 wi) {
    const Vec3 h = normalize(wo + wi);
    const float fh = (fresnel_dielectric(dot(wi, h), l.ior) - l.f0) / (1.0f - l.f0);
    const Rgb fresnel = l.cspec0 * (1.0f - fh) + Rgb(fh);
    // f cos_i = F D G1 G1 / (4 cos_o).
    return fresnel * (ggx_d(h, l.alpha) * ggx_g2_separable(wo, wi, l.alpha) / (4.0f * wo.z));
}

BsdfEval eval_lobes(const LobesV1& l, const Material& m, Vec3 wo, Vec3 wi,
                    HemisphereDistribution hemisphere) {
    BsdfEval e{l.diffuse_color * (burley_diffuse(wo, wi, std::clamp(m.roughness, 0.0f, 1.0f)) * wi.z),
               l.diffuse_probability * hemisphere_pdf(hemisphere, wi.z)};
    if (l.has_specular) {
        e.value += specular_value(l, wo, wi);
        e.pdf += (1.0f - l.diffuse_probability) * ggx_reflection_pdf(wo, wi, l.alpha);
    }
    return e;
}

}  // namespace

BsdfEval principled_v1_eval(const Material& m, Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere) {
    if (wo.z <= 0.0f || wi.z <= 0.0f) return {Rgb(), 0.0f};
    return eval_lobes(setup(m, wo), m, wo, wi, hemisphere);
}

bool principled_v1_sample(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                          HemisphereDistribution hemisphere) {
    if (wo.z <= 0.0f) return false;
    const LobesV1 l = setup(m, wo);
    if (l.diffuse_probability <= 0.0f && !l.has_specular) return false;
    Vec3 wi;
    if (u_lobe < l.diffuse_probability) {
        wi = sample_hemisphere(hemisphere, u);
        if (wi.z <= 0.0f) return false;
    } else if (!ggx_sample_reflection(wo, l.alpha, u, &wi)) {
        return false;
    }
    // The weight uses the full mixture pdf (one-sample MIS over lobes), so it equals value/pdf
    // exactly as bsdf_eval reports them.
    const BsdfEval e = eval_lobes(l, m, wo, wi, hemisphere);
    if (e.pdf <= 0.0f) return false;
    *out = {wi, e.value / e.pdf, e.pdf, false,
            u_lobe < l.diffuse_probability ? ScatterKind::Diffuse : ScatterKind::Glossy};
    return true;
}

}  // namespace stratum
