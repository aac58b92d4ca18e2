#include "bsdf/principled_v1.h"

#include "bsdf/glass.h"
#include "bsdf/glossy.h"
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
    float specular_weight;  // 1 - final transmission
    // Transmission (Cycles 3.4: two closures weighted by the Fresnel of the shading normal).
    float glass_weight, glass_eta, glass_fresnel;  // final transmission, relative IOR, F(cos_o)
    // The pair's reflection and refraction weights, glass_weight F and glass_weight (1 - F), or 0
    // where a caustics switch drops that closure of the pair.
    float glass_reflect, glass_refract;
    bool glass_sharp;  // roughness below Cycles' sharp threshold
    float clearcoat;   // 0.25 Clearcoat; 0 = no clearcoat lobe
    float clearcoat_alpha;
    // Lobe selection, cumulative in this order: diffuse, specular, glass reflection, glass
    // refraction, clearcoat (the last takes the rest).
    float diffuse_probability, specular_probability, reflect_probability, refract_probability;
};

LobesV1 setup(const Material& m, Vec3 wo) {
    LobesV1 l;
    const float metallic = std::clamp(m.metallic, 0.0f, 1.0f);
    const float specular = std::max(m.specular, 0.0f);
    const float transmission = std::clamp(m.transmission, 0.0f, 1.0f);
    // Cycles 3.4: diffuse (1 - metallic)(1 - transmission), glass transmission (1 - metallic),
    // specular 1 - that glass weight.
    l.diffuse_color = m.base_color * ((1.0f - metallic) * (1.0f - transmission));
    l.glass_weight = transmission * (1.0f - metallic);
    if (l.glass_weight <= kClosureCutoff) l.glass_weight = 0.0f;
    l.specular_weight = 1.0f - l.glass_weight;
    // Cycles 3.4 skips the specular and clearcoat closures when reflective caustics are dropped.
    l.has_specular = (specular > kClosureCutoff || metallic > kClosureCutoff) && !m.no_glossy_reflection;
    l.alpha = ggx_alpha_from_roughness(blurred_roughness(m.roughness, m));
    l.ior = 2.0f / (1.0f - safe_sqrt(0.08f * specular)) - 1.0f;
    l.f0 = f0_from_ior(l.ior);  // equals 0.08 specular
    l.cspec0 = Rgb(0.08f * specular) * (1.0f - metallic) + m.base_color * metallic;
    l.glass_eta = std::max(m.ior, 1e-5f);
    // Fresnel terms of absent lobes are not computed: their weights are 0 whatever they are.
    l.glass_fresnel = l.glass_weight > 0.0f ? fresnel_dielectric(wo.z, l.glass_eta) : 0.0f;
    l.glass_reflect = m.no_glossy_reflection ? 0.0f : l.glass_weight * l.glass_fresnel;
    l.glass_refract = m.no_glossy_refraction ? 0.0f : l.glass_weight * (1.0f - l.glass_fresnel);
    l.glass_sharp = ggx_is_sharp(blurred_roughness(m.roughness, m));
    l.clearcoat = m.coat > kClosureCutoff && !m.no_glossy_reflection ? 0.25f * m.coat : 0.0f;
    // GTR1 needs alpha < 1 (ln alpha^2 in its normalisation).
    l.clearcoat_alpha =
        std::clamp(sqr(std::clamp(blurred_roughness(m.coat_roughness, m), 0.0f, 1.0f)), 1e-3f, 0.999f);
    // Cycles weights lobe selection by the closure weight times, for the specular, the average
    // Fresnel colour seen from wo at normal incidence on the microfacets (h = n).
    const float weight_diffuse = std::max(l.diffuse_color.average(), 0.0f);
    float weight_specular = 0.0f;
    if (l.has_specular) {
        const float fh = (fresnel_dielectric(wo.z, l.ior) - l.f0) / (1.0f - l.f0);
        weight_specular = l.specular_weight * (l.cspec0 * (1.0f - fh) + Rgb(fh)).average();
    }
    const float weight_reflect = l.glass_reflect;
    const float weight_refract = l.glass_refract * std::max(m.base_color.average(), 0.0f);
    const float weight_clearcoat = l.clearcoat > 0.0f ? l.clearcoat * fresnel_dielectric(wo.z, 1.5f) : 0.0f;
    const float total = weight_diffuse + weight_specular + weight_reflect + weight_refract + weight_clearcoat;
    const float inv = total > 0.0f ? 1.0f / total : 0.0f;
    l.diffuse_probability = weight_diffuse * inv;
    l.specular_probability = weight_specular * inv;
    l.reflect_probability = weight_reflect * inv;
    l.refract_probability = weight_refract * inv;
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

// Disney's clearcoat as Cycles 3.4 evaluates it: GTR1 distribution (Burley 2012, eq. 4),
// Smith G1 of a fixed GGX alpha 0.25 for both directions, Fresnel of IOR 1.5 (F0 = 0.04).
float gtr1_d(float cos_h, float alpha) {
    const float a2 = alpha * alpha;
    return (a2 - 1.0f) / (kPi * std::log(a2) * (1.0f + (a2 - 1.0f) * cos_h * cos_h));
}
float clearcoat_value(const LobesV1& l, Vec3 wo, Vec3 wi) {
    const Vec3 h = normalize(wo + wi);
    const float g = ggx_g2_separable(wo, wi, 0.25f);
    return l.clearcoat * fresnel_dielectric(dot(wi, h), 1.5f) * gtr1_d(h.z, l.clearcoat_alpha) * g /
           (4.0f * wo.z);
}
// Sampling density of the clearcoat: h drawn from D(h) cos(h) (Burley 2012, appendix B.2).
float clearcoat_pdf(const LobesV1& l, Vec3 wo, Vec3 wi) {
    const Vec3 h = normalize(wo + wi);
    const float cos_oh = dot(wo, h);
    if (h.z <= 0.0f || cos_oh <= 0.0f) return 0.0f;
    return gtr1_d(h.z, l.clearcoat_alpha) * h.z / (4.0f * cos_oh);
}
bool clearcoat_sample(const LobesV1& l, Vec3 wo, Vec2 u, Vec3* wi) {
    const float a2 = l.clearcoat_alpha * l.clearcoat_alpha;
    const float cos2 = (1.0f - std::pow(a2, 1.0f - u.x)) / (1.0f - a2);
    const float cos_h = safe_sqrt(cos2), sin_h = safe_sqrt(1.0f - cos2);
    const float phi = 2.0f * kPi * u.y;
    const Vec3 h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
    const float cos_oh = dot(wo, h);
    if (cos_oh <= 0.0f) return false;
    *wi = h * (2.0f * cos_oh) - wo;
    return wi->z > 0.0f;
}

// The refraction closure of Cycles 3.4's glass pair: GGX transmission without Fresnel (the pair's
// weights carry it), separable Smith G1 G1, Walter 2007 eq. 21; sampled by visible normals.
struct Refraction {
    float value, pdf;
};
Refraction refraction(const LobesV1& l, Vec3 wo, Vec3 wi) {
    Vec3 h = wo + wi * l.glass_eta;
    const float len = length(h);
    if (len <= 0.0f) return {0.0f, 0.0f};
    h = h / len;
    if (h.z < 0.0f) h = -h;
    const float cos_oh = dot(wo, h), cos_ih = dot(wi, h);
    if (cos_oh <= 0.0f || cos_ih >= 0.0f) return {0.0f, 0.0f};
    const float jacobian = l.glass_eta * l.glass_eta * std::abs(cos_ih) / sqr(cos_oh + l.glass_eta * cos_ih);
    const float d = ggx_d(h, l.alpha);
    const float g1o = ggx_g1(wo, l.alpha), g1i = ggx_g1(Vec3(wi.x, wi.y, -wi.z), l.alpha);
    return {d * g1o * g1i * cos_oh * jacobian / wo.z, g1o * cos_oh * d / wo.z * jacobian};
}

BsdfEval eval_lobes(const LobesV1& l, const Material& m, Vec3 wo, Vec3 wi,
                    HemisphereDistribution hemisphere) {
    BsdfEval e{Rgb(0.0f), 0.0f};
    if (wi.z < 0.0f) {
        if (l.glass_weight > 0.0f && !l.glass_sharp) {
            const Refraction r = refraction(l, wo, wi);
            e.value = m.base_color * (l.glass_refract * r.value);
            e.pdf = l.refract_probability * r.pdf;
        }
        return e;
    }
    e.value = l.diffuse_color * (burley_diffuse(wo, wi, std::clamp(m.roughness, 0.0f, 1.0f)) * wi.z);
    e.diffuse = e.value;
    e.pdf = l.diffuse_probability * hemisphere_pdf(hemisphere, wi.z);
    if (l.has_specular) {
        e.value += specular_value(l, wo, wi) * l.specular_weight;
        e.pdf += l.specular_probability * ggx_reflection_pdf(wo, wi, l.alpha);
    }
    if (l.glass_weight > 0.0f && !l.glass_sharp) {
        // The glass pair's reflection closure: GGX with Fresnel 1 (cspec0 white), weight F(cos_o).
        const Vec3 h = normalize(wo + wi);
        e.value +=
            Rgb(l.glass_reflect * ggx_d(h, l.alpha) * ggx_g2_separable(wo, wi, l.alpha) / (4.0f * wo.z));
        e.pdf += l.reflect_probability * ggx_reflection_pdf(wo, wi, l.alpha);
    }
    if (l.clearcoat > 0.0f) {
        e.value += Rgb(clearcoat_value(l, wo, wi));
        e.pdf += (1.0f - l.diffuse_probability - l.specular_probability - l.reflect_probability -
                  l.refract_probability) *
                 clearcoat_pdf(l, wo, wi);
    }
    return e;
}

// Cycles 3.4's closure weights, per type (see principled_v1.h).
ClosureColors colors(const Material& m, Vec3 wo) {
    const LobesV1 l = setup(m, wo);
    float glossy = l.has_specular && l.specular_weight > kClosureCutoff ? l.specular_weight : 0.0f;
    Rgb transmission(0.0f);
    if (l.glass_weight > 0.0f) {
        glossy += l.glass_weight * l.glass_fresnel;
        // Cycles keeps the refraction closure alive under total internal reflection (for MNEE).
        transmission = m.base_color * (l.glass_weight * std::max(1.0f - l.glass_fresnel, 1e-4f));
    }
    if (l.clearcoat > 0.0f) glossy += 1.0f;
    return {l.diffuse_color, Rgb(glossy), transmission};
}

}  // namespace

BsdfEval principled_v1_eval(const Material& m, Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere) {
    if (wo.z <= 0.0f || wi.z == 0.0f || (wi.z < 0.0f && m.transmission <= 0.0f)) return {Rgb(), 0.0f};
    return eval_lobes(setup(m, wo), m, wo, wi, hemisphere);
}

bool principled_v1_sample(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                          HemisphereDistribution hemisphere) {
    if (wo.z <= 0.0f) return false;
    const LobesV1 l = setup(m, wo);
    const float specular_end = l.diffuse_probability + l.specular_probability;
    const float reflect_end = specular_end + l.reflect_probability;
    const float refract_end = reflect_end + l.refract_probability;
    if (refract_end <= 0.0f && l.clearcoat <= 0.0f) return false;
    Vec3 wi;
    ScatterKind kind = ScatterKind::Glossy;
    if (u_lobe < l.diffuse_probability) {
        wi = sample_hemisphere(hemisphere, u);
        if (wi.z <= 0.0f) return false;
        kind = ScatterKind::Diffuse;
    } else if (u_lobe < specular_end) {
        if (!ggx_sample_reflection(wo, l.alpha, u, &wi)) return false;
    } else if (u_lobe < refract_end && l.glass_sharp) {
        // Smooth glass pair: Dirac lobes, weight = closure weight / selection probability.
        const bool reflect = u_lobe < reflect_end;
        const float probability = reflect ? l.reflect_probability : l.refract_probability;
        if (reflect) {
            *out = {Vec3(-wo.x, -wo.y, wo.z), Rgb(l.glass_reflect / probability), probability, true,
                    ScatterKind::Glossy};
            return true;
        }
        if (!refract_direction(wo, Vec3(0.0f, 0.0f, 1.0f), l.glass_eta, &wi)) return false;
        *out = {wi, m.base_color * (l.glass_refract / probability), probability, true,
                ScatterKind::Transmission};
        return true;
    } else if (u_lobe < reflect_end) {
        if (!ggx_sample_reflection(wo, l.alpha, u, &wi)) return false;
    } else if (u_lobe < refract_end) {
        const Vec3 h = sample_ggx_visible_normal(wo, l.alpha, u);
        if (dot(wo, h) <= 0.0f || !refract_direction(wo, h, l.glass_eta, &wi) || wi.z >= 0.0f) return false;
        kind = ScatterKind::Transmission;
    } else if (!clearcoat_sample(l, wo, u, &wi)) {
        return false;
    }
    // The weight uses the full mixture pdf (one-sample MIS over lobes), so it equals value/pdf
    // exactly as bsdf_eval reports them.
    const BsdfEval e = eval_lobes(l, m, wo, wi, hemisphere);
    if (e.pdf <= 0.0f) return false;
    *out = {wi, e.value / e.pdf, e.pdf, false, kind};
    return true;
}

const ClosureModel kPrincipledV1Closure{
    .eval = &principled_v1_eval,
    .sample = &principled_v1_sample,
    .is_delta = &answer_false,
    .has_transmission = &principled_has_transmission,
    .sample_weight = &principled_sample_weight,
    .albedo_estimate = &principled_albedo_estimate,
    .colors = &colors,
    .kinds_above = kPrincipledKindsAbove,
    .kinds_below = scatter_kind_bit(ScatterKind::Transmission),
};

}  // namespace stratum
