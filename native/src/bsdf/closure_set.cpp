#include "bsdf/closure_set.h"

namespace stratum {

ClosureSet::ClosureSet(const SceneMaterial& material) {
    count_ = static_cast<uint32_t>(std::min<size_t>(material.closures.size(), kMaxClosures));
    for (uint32_t i = 0; i < count_; ++i) closures_[i] = material.closures[i];
    finalize();
}

void ClosureSet::finalize() {
    sample_weight_sum_ = 0.0f;
    emission_ = holdout_ = transparency_ = lambertian_albedo_ = albedo_estimate_ = Rgb(0.0f);
    has_transmission_ = has_non_delta_ = false;
    scatterers_ = 0;
    for (uint32_t i = 0; i < count_; ++i) {
        const WeightedClosure& c = closures_[i];
        const ClosureModel& model = closure_model(c.params.model);
        emission_ += c.weight * c.params.emission;
        if (model.holdout) holdout_ += c.weight;
        if (model.transparent) transparency_ += c.weight * c.params.base_color;
        sample_weight_[i] = std::abs(c.weight.average()) * model.sample_weight(c.params);
        sample_weight_sum_ += sample_weight_[i];
        if (sample_weight_[i] > 0.0f) {
            ++scatterers_;
            if (model.lambertian) lambertian_albedo_ += c.weight * c.params.base_color;
            albedo_estimate_ += c.weight * model.albedo_estimate(c.params);
            has_transmission_ = has_transmission_ || model.has_transmission(c.params);
            has_non_delta_ = has_non_delta_ || !model.is_delta(c.params);
        }
    }
}

Rgb ClosureSet::denoising_albedo(Vec3 wo) const {
    Rgb sum(0.0f);
    for (uint32_t i = 0; i < count_; ++i) {
        const Material& m = closures_[i].params;
        const ClosureModel& model = closure_model(m.model);
        if (model.denoising_albedo_from_colors) {
            const ClosureColors c = model.colors(m, wo);
            sum += closures_[i].weight * (c.diffuse + c.glossy + c.transmission);
        } else {
            sum += closures_[i].weight * model.albedo_estimate(m);
        }
    }
    return sum;
}

ClosureColors ClosureSet::colors(Vec3 wo) const {
    ClosureColors sum;
    for (uint32_t i = 0; i < count_; ++i) {
        const Material& m = closures_[i].params;
        const ClosureColors c = closure_model(m.model).colors(m, wo);
        sum.diffuse += closures_[i].weight * c.diffuse;
        sum.glossy += closures_[i].weight * c.glossy;
        sum.transmission += closures_[i].weight * c.transmission;
    }
    return sum;
}

Rgb ClosureSet::lambertian_value(Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere) const {
    Rgb sum(0.0f);
    for (uint32_t i = 0; i < count_; ++i) {
        const Material& m = closures_[i].params;
        const ClosureModel& model = closure_model(m.model);
        if (sample_weight_[i] <= 0.0f || !model.lambertian) continue;
        sum += closures_[i].weight * model.eval(m, wo, wi, hemisphere).value;
    }
    return sum;
}

void ClosureSet::apply(const ClosureFilter& filter) {
    for (uint32_t i = 0; i < count_; ++i) {
        Material& m = closures_[i].params;
        m.min_alpha = filter.min_alpha;
        m.no_glossy_reflection = filter.drop_reflection;
        m.no_glossy_refraction = filter.drop_refraction;
    }
}

void ClosureSet::set_smooth_normal(Vec3 smooth_normal_local) {
    perturbed_ = true;
    smooth_normal_ = smooth_normal_local;
}

BsdfEval ClosureSet::eval(Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere, uint32_t kinds) const {
    return eval_with(wo, wi, hemisphere, kinds, count_);
}

BsdfEval ClosureSet::eval_with(Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere, uint32_t kinds,
                               uint32_t sampled) const {
    BsdfEval sum{Rgb(0.0f), 0.0f};
    if (!(sample_weight_sum_ > 0.0f)) return sum;
    for (uint32_t i = 0; i < count_; ++i) {
        if (sample_weight_[i] <= 0.0f) continue;
        const Material& m = closures_[i].params;
        const ClosureModel& model = closure_model(m.model);
        BsdfEval e = model.eval(m, wo, wi, hemisphere);
        if (perturbed_ && m.bump_shadowing != BumpShadowing::None) {
            const BumpShadowingFactors f = bump_shadowing(m.bump_shadowing, smooth_normal_, wi, i == sampled);
            e.value = (e.value + e.diffuse * (f.diffuse - 1.0f)) * f.all;
        }
        const uint32_t closure_kinds = wi.z < 0.0f ? model.kinds_below : model.kinds_above;
        if (closure_kinds & kinds) sum.value += closures_[i].weight * e.value;
        sum.pdf += sample_weight_[i] / sample_weight_sum_ * e.pdf;
    }
    return sum;
}

bool ClosureSet::sample(Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                        HemisphereDistribution hemisphere) const {
    if (!(sample_weight_sum_ > 0.0f)) return false;
    // Choose closure i by u_lobe over the cumulative sample weights, then rescale u_lobe to the
    // position inside the chosen interval so the closure's own lobe choice gets a fresh uniform.
    const float target = u_lobe * sample_weight_sum_;
    float start = 0.0f;
    uint32_t chosen = count_;
    for (uint32_t i = 0; i < count_; ++i) {
        if (sample_weight_[i] <= 0.0f) continue;
        chosen = i;
        if (target < start + sample_weight_[i]) break;
        start += sample_weight_[i];
    }
    if (chosen == count_) return false;
    const float width = sample_weight_[chosen];
    const float u_inner = std::clamp((target - start) / width, 0.0f, kOneMinusEpsilon);
    BsdfSample s;
    if (!bsdf_sample(closures_[chosen].params, wo, u_inner, u, &s, hemisphere)) return false;
    const float probability = width / sample_weight_sum_;
    if (s.delta) {
        s.weight = closures_[chosen].weight * s.weight / probability;
        s.pdf = probability;
        *out = s;
        return true;
    }
    // The only closure eval_with would sum, without bump shadowing to apply: the mixture is that
    // closure alone, and its sample already carries value/pdf of its whole lobe mixture
    // (bsdf_sample's contract), which evaluating it again would only recompute.
    if (scatterers_ == 1 && !(perturbed_ && closures_[chosen].params.bump_shadowing != BumpShadowing::None)) {
        if (!(s.pdf > 0.0f)) return false;
        s.weight = closures_[chosen].weight * s.weight;
        *out = s;
        return true;
    }
    const BsdfEval e = eval_with(wo, s.wi, hemisphere, kAllKinds, chosen);
    if (!(e.pdf > 0.0f)) return false;
    *out = {s.wi, e.value / e.pdf, e.pdf, false, s.kind};
    return true;
}

}  // namespace stratum
