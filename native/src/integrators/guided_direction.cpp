#include "integrators/guided_direction.h"

namespace stratum {

namespace {

float inverse_or_zero(float v) { return v > 0.0f ? 1.0f / v : 0.0f; }

float luminance(Rgb c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

}  // namespace

bool sample_guided(const ClosureSet& closures, Vec3 wo, const GuidedVertex& guide, float u_choice,
                   float u_lobe, Vec2 u, BsdfSample* out, HemisphereDistribution hemisphere) {
    const float f = guide.bsdf_fraction;
    if (u_choice < f) {
        if (!closures.sample(wo, u_lobe, u, out, hemisphere)) return false;
        // A delta direction is drawn by the closures only, with probability f × theirs.
        if (out->delta) {
            out->weight *= 1.0f / f;
            return true;
        }
        // The closures report value / pdf with their mixture pdf: value = weight × pdf.
        const Rgb value = out->weight * out->pdf;
        out->pdf = guide.mixed_pdf(out->pdf, guide.frame.to_world(out->wi));
        out->weight = value * (1.0f / out->pdf);
        return true;
    }
    float guide_pdf = 0.0f;
    const Vec3 wi_world = guide.tree->sample(guide.region, u, &guide_pdf);
    const Vec3 wi = guide.frame.to_local(wi_world);
    const BsdfEval e = closures.eval(wo, wi, hemisphere);
    const float pdf = f * e.pdf + (1.0f - f) * guide_pdf;
    if (e.value.is_black() || !(pdf > 0.0f)) return false;
    out->wi = wi;
    out->pdf = pdf;
    out->weight = e.value * (1.0f / pdf);
    out->delta = false;
    // The ray's kind (for the lights' and objects' visibility): transmission below the surface,
    // else the lobe family that carries most of the value.
    out->kind = wi.z < 0.0f                                       ? ScatterKind::Transmission
                : e.diffuse.average() >= 0.5f * e.value.average() ? ScatterKind::Diffuse
                                                                  : ScatterKind::Glossy;
    return true;
}

void PathRecords::add_found(Rgb weighted, Rgb whole) {
    if (!active()) return;
    for (uint32_t k = 0; k < count_; ++k) {
        const bool last = k + 1 == count_ && last_is_recorded_;
        entries_[k].radiance += (last ? whole : weighted) * entries_[k].inverse_throughput;
    }
}

void PathRecords::push(Vec3 position, Vec3 direction, Rgb throughput_after) {
    if (!active()) return;
    if (count_ == kMaxRecords) {
        last_is_recorded_ = false;
        return;
    }
    entries_[count_++] = Entry{position, direction,
                               Rgb(inverse_or_zero(throughput_after.r), inverse_or_zero(throughput_after.g),
                                   inverse_or_zero(throughput_after.b)),
                               Rgb(0.0f)};
    last_is_recorded_ = true;
}

void PathRecords::flush() const {
    if (!active()) return;
    for (uint32_t k = 0; k < count_; ++k)
        tree_->record(entries_[k].position, entries_[k].direction, luminance(entries_[k].radiance));
}

}  // namespace stratum
