#include "bsdf/principled_v2.h"

#include "bsdf/glass.h"
#include "bsdf/microfacet_ggx.h"
#include "sampling/warps.h"

namespace stratum {

namespace {

struct LobesV2 {
    float metallic;
    // roughness: the host's, which the layer albedos and energy compensation read (Cycles sets
    // them up before Filter Glossy blurs); alpha: the lobes' own, blurred.
    float roughness, alpha;
    bool has_specular;      // dielectric layer present (eta != 1)
    float eta;              // relative IOR of the dielectric layer
    float specular_scale;   // multiple-scattering compensation c(cos_o) of the dielectric lobe
    float specular_albedo;  // A_spec(cos_o): what the dielectric lobe reflects
    float layer_albedo;     // what the diffuse below loses: 1 - layer_albedo reaches it
    Rgb metal_f0, metal_scale;
    float transmission;  // weight of the dielectric glass lobe inside the non-metal part
    float glass_eta;     // its relative IOR (inverted on back faces by the caller)
    float coat;          // coat weight; 0 = no coat
    float coat_alpha, coat_eta;
    float coat_albedo;  // Cycles' albedo estimate of the coat lobe, F_v of the coat
    Rgb base_scale;     // what the coat lets through to every layer below, for this wo
    float probability_metal, probability_specular, probability_glass, probability_coat;  // diffuse: rest
    // The caustics switches (Cycles 5.0): without reflection the coat, metal and dielectric
    // specular layers are skipped (and attenuate nothing below), the glass reflects nothing;
    // without refraction the glass transmits nothing.
    bool reflect, refract;
};

// Kulla & Conty 2017: with single-scattering albedo E(mu) and average E_avg, the missing energy
// (1 - E)/E, reflected again with the average multi-bounce Fresnel F_ms.
float multiscatter_scale(float e, float e_avg, float f_avg) {
    const float f_ms = f_avg * e_avg / (1.0f - f_avg * (1.0f - e_avg));
    return 1.0f + f_ms * (1.0f - e) / e;
}

float specular_eta(const Material& m) {
    const float ior = std::max(m.ior, 1e-5f);
    const float level = std::max(m.specular, 0.0f);
    // Cycles 4.x: F0 scaled by 2 level, IOR recomputed from it; reflection from outside sees
    // the same F0 for ior and 1/ior, so the relative eta is taken >= 1.
    const float eta = level == 0.5f ? ior : ior_from_f0(f0_from_ior(ior) * 2.0f * level);
    return std::max(eta, 1.0f / eta);
}

LobesV2 setup(const Material& m, Vec3 wo) {
    LobesV2 l;
    l.metallic = std::clamp(m.metallic, 0.0f, 1.0f);
    l.reflect = !m.no_glossy_reflection;
    l.refract = !m.no_glossy_refraction;
    l.roughness = std::clamp(m.roughness, 0.0f, 1.0f);
    l.alpha = ggx_alpha_from_roughness(blurred_roughness(l.roughness, m));
    l.eta = specular_eta(m);
    l.has_specular = l.eta > 1.0f && l.reflect;
    const bool multiscatter = m.distribution == MicrofacetDistribution::MultiscatterGgx;
    const float e = std::max(ggx_albedo_unit_fresnel(wo.z, l.roughness), 1e-4f);
    const float e_avg = ggx_average_albedo_unit_fresnel(l.roughness);
    l.specular_scale = 1.0f, l.specular_albedo = 0.0f, l.layer_albedo = 0.0f;
    if (l.has_specular) {
        // What reaches the diffuse below is 1 - layer_albedo, Cycles' estimate of the specular
        // albedo (svm/closure.h: closure_layering_weight(bsdf_albedo(spec), weight)): the
        // closure weight times the visible-normal Fresnel estimate F_v (microfacet_ggx.h).
        //   Multiscatter GGX: the weight carries the lobe's energy E + F_ms (1 - E) = E c
        //     (Cycles darkens the weight to that and scales eval by 1/E), so the estimate is
        //     F_v E c, close to the true albedo E_F c but larger at grazing views.
        //   GGX: no energy compensation and the weight stays 1, so the estimate is F_v alone,
        //     about 1/E times the true single-scattering albedo E_F: the diffuse also loses what
        //     the microfacets lose. Not energy conserving, like Cycles.
        const float visible_fresnel = ggx_visible_fresnel_dielectric(wo.z, l.roughness, l.eta);
        const float single_albedo = ggx_albedo_dielectric(wo.z, l.roughness, l.eta);
        if (multiscatter) {
            l.specular_scale = multiscatter_scale(e, e_avg, fresnel_dielectric_average(l.eta));
            l.specular_albedo = std::min(single_albedo * l.specular_scale, 1.0f);
            l.layer_albedo = std::min(visible_fresnel * e * l.specular_scale, 1.0f);
        } else {
            l.specular_albedo = std::min(single_albedo, 1.0f);
            l.layer_albedo = std::min(visible_fresnel, 1.0f);
        }
    }
    l.metal_f0 = Rgb(std::clamp(m.base_color.r, 0.0f, 1.0f), std::clamp(m.base_color.g, 0.0f, 1.0f),
                     std::clamp(m.base_color.b, 0.0f, 1.0f));
    l.metal_scale = Rgb(1.0f);
    if (multiscatter) {
        // Schlick's hemispherical average: F0 + (1 - F0)/21.
        const Rgb f_avg_metal = l.metal_f0 + (Rgb(1.0f) - l.metal_f0) * (1.0f / 21.0f);
        l.metal_scale =
            Rgb(multiscatter_scale(e, e_avg, f_avg_metal.r), multiscatter_scale(e, e_avg, f_avg_metal.g),
                multiscatter_scale(e, e_avg, f_avg_metal.b));
    }
    l.transmission = std::clamp(m.transmission, 0.0f, 1.0f);
    l.glass_eta = std::max(m.ior, 1e-5f);
    // Coat (Cycles 4.x svm_node_closure_principled): a dielectric GGX layer of weight `coat`
    // whose albedo estimate F_v removes that share from everything below, then Beer absorption
    // by coat_tint over the refracted path length 1/cos_t through a unit-thick coat.
    l.coat = std::clamp(m.coat, 0.0f, 1.0f);
    const float coat_roughness = std::clamp(m.coat_roughness, 0.0f, 1.0f);
    l.coat_alpha = ggx_alpha_from_roughness(blurred_roughness(coat_roughness, m));
    l.coat_eta = std::max(std::max(m.coat_ior, 1e-5f), 1.0f / std::max(m.coat_ior, 1e-5f));
    l.base_scale = Rgb(1.0f);
    l.coat_albedo = 0.0f;
    if (l.coat > 0.0f && l.coat_eta > 1.0f) {
        if (l.reflect) {
            l.coat_albedo = std::min(ggx_visible_fresnel_dielectric(wo.z, coat_roughness, l.coat_eta), 1.0f);
            l.base_scale = Rgb(1.0f - l.coat * l.coat_albedo);
        }
        const float cos_t = safe_sqrt(1.0f - (1.0f - wo.z * wo.z) / (l.coat_eta * l.coat_eta));
        const float depth = 1.0f / std::max(cos_t, 1e-4f);
        const Rgb tint(std::pow(std::clamp(m.coat_tint.r, 0.0f, 1.0f), depth),
                       std::pow(std::clamp(m.coat_tint.g, 0.0f, 1.0f), depth),
                       std::pow(std::clamp(m.coat_tint.b, 0.0f, 1.0f), depth));
        l.base_scale *= Rgb(1.0f - l.coat) + tint * l.coat;
    }
    // Lobe selection proportional to each lobe's albedo estimate for this wo.
    const float sw = schlick_weight(wo.z);
    const float below = l.base_scale.average();
    const float weight_metal =
        l.reflect ? below * l.metallic * (l.metal_f0 * (1.0f - sw) + Rgb(sw)).average() : 0.0f;
    const float opaque = (1.0f - l.metallic) * (1.0f - l.transmission) * below;
    const float weight_specular = opaque * l.specular_albedo;
    const float weight_diffuse = opaque * (1.0f - l.layer_albedo) * std::max(m.base_color.average(), 0.0f);
    // The glass lobe's Fresnel only where there is glass: its weight is 0 whatever it is.
    const float glass_fresnel = l.transmission > 0.0f ? fresnel_dielectric(wo.z, l.glass_eta) : 0.0f;
    const float weight_glass =
        below * (1.0f - l.metallic) * l.transmission *
        ((l.reflect ? glass_fresnel : 0.0f) +
         (l.refract ? (1.0f - glass_fresnel) * std::max(m.base_color.average(), 0.0f) : 0.0f));
    const float weight_coat = l.coat * l.coat_albedo;
    const float total = weight_metal + weight_specular + weight_diffuse + weight_glass + weight_coat;
    l.probability_metal = total > 0.0f ? weight_metal / total : 0.0f;
    l.probability_specular = total > 0.0f ? weight_specular / total : 0.0f;
    l.probability_glass = total > 0.0f ? weight_glass / total : 0.0f;
    l.probability_coat = total > 0.0f ? weight_coat / total : 0.0f;
    return l;
}

BsdfEval eval_lobes(const LobesV2& l, const Material& m, Vec3 wo, Vec3 wi,
                    HemisphereDistribution hemisphere) {
    BsdfEval e{Rgb(0.0f), 0.0f};
    if (l.probability_glass > 0.0f) {
        // The transmission lobe: glass whose reflection is untinted and refraction tinted by
        // base_color (Cycles 4.x: reflection tint = specular tint, transmission tint = base).
        const DielectricEval g = dielectric_ggx_eval(wo, wi, l.alpha, l.glass_eta);
        const float w = (1.0f - l.metallic) * l.transmission *
                        glass_energy_scale(m.distribution, wo.z, l.roughness, l.glass_eta);
        const float reflected = l.reflect ? g.reflect_value : 0.0f;
        const float transmitted = l.refract ? g.transmit_value : 0.0f;
        e.value += (Rgb(reflected) + m.base_color * transmitted) * l.base_scale * w;
        e.pdf += l.probability_glass * (g.reflect_pdf + g.transmit_pdf);
    }
    if (wi.z <= 0.0f) return e;
    const float probability_diffuse = std::max(
        1.0f - l.probability_metal - l.probability_specular - l.probability_glass - l.probability_coat, 0.0f);
    const float opaque = (1.0f - l.metallic) * (1.0f - l.transmission);
    e.diffuse = m.base_color * l.base_scale * (opaque * (1.0f - l.layer_albedo) * kInvPi * wi.z);
    e.value += e.diffuse;
    e.pdf += probability_diffuse * hemisphere_pdf(hemisphere, wi.z);
    const Vec3 h = normalize(wo + wi);
    const float cos_ih = dot(wi, h);
    if (l.probability_metal > 0.0f || l.probability_specular > 0.0f) {
        // D G2 / (4 cos_o) = f cos_i without Fresnel.
        const float microfacet =
            ggx_d(h, l.alpha) * ggx_g2_height_correlated(wo, wi, l.alpha) / (4.0f * wo.z);
        if (l.metallic > 0.0f && l.reflect) {
            const float sw = schlick_weight(cos_ih);
            e.value += (l.metal_f0 * (1.0f - sw) + Rgb(sw)) * l.metal_scale * l.base_scale *
                       (l.metallic * microfacet);
        }
        if (l.has_specular) {
            e.value +=
                l.base_scale * (opaque * fresnel_dielectric(cos_ih, l.eta) * l.specular_scale * microfacet);
        }
        e.pdf += (l.probability_metal + l.probability_specular) * ggx_reflection_pdf(wo, wi, l.alpha);
    }
    if (l.probability_coat > 0.0f) {
        const float coat =
            ggx_d(h, l.coat_alpha) * ggx_g2_height_correlated(wo, wi, l.coat_alpha) / (4.0f * wo.z);
        e.value += Rgb(l.coat * fresnel_dielectric(cos_ih, l.coat_eta) * coat);
        e.pdf += l.probability_coat * ggx_reflection_pdf(wo, wi, l.coat_alpha);
    }
    return e;
}

// Cycles 4.x's bsdf_albedo estimates of its closures, per type (see principled_v2.h).
ClosureColors colors(const Material& m, Vec3 wo) {
    const LobesV2 l = setup(m, wo);
    const float opaque = (1.0f - l.metallic) * (1.0f - l.transmission);
    const float glass = (1.0f - l.metallic) * l.transmission;
    // The glass lobe's Fresnel only where there is glass: its weight is 0 whatever it is.
    const float glass_fresnel = l.transmission > 0.0f ? fresnel_dielectric(wo.z, l.glass_eta) : 0.0f;
    const float sw = schlick_weight(wo.z);
    const Rgb metal = (l.metal_f0 * (1.0f - sw) + Rgb(sw)) * l.metallic;
    const Rgb glossy = l.base_scale * (metal + Rgb(opaque * l.layer_albedo + glass * glass_fresnel));
    return {m.base_color * l.base_scale * (opaque * (1.0f - l.layer_albedo)),
            glossy + Rgb(l.coat * l.coat_albedo),
            m.base_color * l.base_scale * (glass * (1.0f - glass_fresnel))};
}

}  // namespace

BsdfEval principled_v2_eval(const Material& m, Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere) {
    if (wo.z <= 0.0f || wi.z == 0.0f || (wi.z < 0.0f && m.transmission <= 0.0f)) return {Rgb(), 0.0f};
    return eval_lobes(setup(m, wo), m, wo, wi, hemisphere);
}

bool principled_v2_sample(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                          HemisphereDistribution hemisphere) {
    if (wo.z <= 0.0f) return false;
    const LobesV2 l = setup(m, wo);
    const float probability_microfacet = l.probability_metal + l.probability_specular;
    const float glass_end = probability_microfacet + l.probability_glass;
    const float coat_end = glass_end + l.probability_coat;
    Vec3 wi;
    ScatterKind kind = ScatterKind::Glossy;
    if (u_lobe < probability_microfacet) {
        // Metal and dielectric share D and G, so one VNDF draw serves both microfacet lobes.
        if (!ggx_sample_reflection(wo, l.alpha, u, &wi)) return false;
    } else if (u_lobe < glass_end) {
        // The glass lobe's own reflect/refract choice reuses u_lobe rescaled to [0, 1).
        const float u_event =
            std::min((u_lobe - probability_microfacet) / l.probability_glass, kOneMinusEpsilon);
        bool transmitted = false;
        if (!dielectric_ggx_sample(wo, l.alpha, l.glass_eta, u_event, u, &wi, &transmitted)) return false;
        if (transmitted) kind = ScatterKind::Transmission;
    } else if (u_lobe < coat_end) {
        if (!ggx_sample_reflection(wo, l.coat_alpha, u, &wi)) return false;
    } else {
        wi = sample_hemisphere(hemisphere, u);
        if (wi.z <= 0.0f) return false;
        kind = ScatterKind::Diffuse;
    }
    const BsdfEval e = eval_lobes(l, m, wo, wi, hemisphere);
    if (e.pdf <= 0.0f) return false;
    *out = {wi, e.value / e.pdf, e.pdf, false, kind};
    return true;
}

const ClosureModel kPrincipledV2Closure{
    .eval = &principled_v2_eval,
    .sample = &principled_v2_sample,
    .is_delta = &answer_false,
    .has_transmission = &principled_has_transmission,
    .sample_weight = &principled_sample_weight,
    .albedo_estimate = &principled_albedo_estimate,
    .colors = &colors,
    .kinds_above = kPrincipledKindsAbove,
    .kinds_below = scatter_kind_bit(ScatterKind::Transmission),
    .denoising_albedo_from_colors = true,
};

}  // namespace stratum
