// Path guiding at one path vertex (textbook §5, 5.19–5.20): the scattered direction is drawn
// from the one-sample mixture of the closures' own sampling and the guiding tree's p′,
// and the estimator carries the exact mixed density, so it stays unbiased; and the training
// records of one camera path (the radiance it carried back into each vertex).
//
// | quantity     | definition |
// |--------------|------------|
// | f            | guiding_bsdf_fraction: the probability of drawing from the closures |
// | p_mix(ω)     | f · p_bsdf(ω) + (1 − f) · p_guide(ω), p_guide = p′(s, t) / 4π (guiding/guiding_tree.h) |
// | weight       | value(ω) / p_mix(ω) for a non-delta direction; a delta direction (mirror, smooth
// glass, transparency), which only the closures draw, with probability f: its weight / f |
// | MIS          | p_mix replaces p_bsdf against next-event estimation, on both sides (Veach 1997 §9.2) |
// | record       | (x_v, ω_v, luminance of L_i): the radiance the path brought back along ω_v, i.e. what
// later vertices add, divided by the throughput at v; the emission that the ray from v hits counts
// whole (L_i along ω_v), deeper emission MIS-weighted as in the estimate |
//
// Guiding applies where the closures have a non-delta part (closures.has_non_delta()); a vertex
// of delta closures only samples them alone. A vertex whose guided direction the closures do not
// scatter into (below an opaque surface) ends the path: its contribution is 0, as the estimator
// of that direction says. Luminance uses Rec. 709 weights (Cycles' default scene-linear space).
#pragma once

#include <array>
#include <cstdint>

#include "bsdf/closure_set.h"
#include "core/math.h"
#include "guiding/guiding_tree.h"

namespace stratum {

// What the renderer reports of the guiding tree (RenderProgress, stratum_renderer_progress).
struct GuidingReport {
    uint64_t nodes = 0, regions = 0;
    uint64_t bytes = 0;            // the most the tree held (nodes and, while learning, its pass counters)
    uint32_t training_passes = 0;  // passes of camera samples the tree has learned from
    uint64_t records = 0;          // records learned from, all passes
};

// The guide at one shading point: the tree's region there and the mixture's BSDF share.
struct GuidedVertex {
    const GuidingTree* tree = nullptr;  // null: no guiding at this vertex
    uint32_t region = 0;
    float bsdf_fraction = 1.0f;
    Frame frame;

    bool active() const { return tree != nullptr; }
    // p_mix of world direction wi whose closure pdf is bsdf_pdf.
    float mixed_pdf(float bsdf_pdf, Vec3 wi_world) const {
        return bsdf_fraction * bsdf_pdf + (1.0f - bsdf_fraction) * tree->pdf(region, wi_world);
    }
};

// Draws a scattered direction (local frame, like ClosureSet::sample) from the mixture:
// u_choice picks the strategy; u_lobe and u go to the closures, or u to the guide. False when
// nothing is drawn (the closures draw nothing, or the guided direction carries no value).
bool sample_guided(const ClosureSet& closures, Vec3 wo, const GuidedVertex& guide, float u_choice,
                   float u_lobe, Vec2 u, BsdfSample* out, HemisphereDistribution hemisphere);

// The training records of one camera path: at most kMaxRecords vertices (the first ones, where
// the guide matters most), handed to the tree when the path ends.
class PathRecords {
public:
    static constexpr uint32_t kMaxRecords = 16;
    explicit PathRecords(GuidingTree* tree) : tree_(tree) {}
    bool active() const { return tree_ != nullptr; }
    // Radiance the estimate adds (weighted as in the estimate) reaching every recorded vertex.
    void add(Rgb weighted) {
        if (active()) add_found(weighted, weighted);
    }
    // Emission hit by the ray leaving the last vertex: that vertex's record takes it `whole`.
    void add_found(Rgb weighted, Rgb whole);
    // A non-delta scatter at `position` into world direction `direction`, with the throughput
    // after it (scatter weight and roulette included).
    void push(Vec3 position, Vec3 direction, Rgb throughput_after);
    // A scatter that is not recorded (delta): emission found next is not along a recorded direction.
    void skip() { last_is_recorded_ = false; }
    // Hands the records to the tree.
    void flush() const;

private:
    struct Entry {
        Vec3 position, direction;
        Rgb inverse_throughput, radiance;
    };
    GuidingTree* tree_;
    std::array<Entry, kMaxRecords> entries_;
    uint32_t count_ = 0;
    bool last_is_recorded_ = false;
};

}  // namespace stratum
