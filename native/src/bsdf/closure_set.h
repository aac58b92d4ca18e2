// The closures of one shading point: Sum_i w_i f_i, Blender's Mix / Add Shader trees flattened as
// Cycles flattens them (Cycles 3.4 / 4.x `kernel/closure/bsdf.h`, `integrator/surface_shader.h`:
// one-sample MIS over closures, each chosen with probability p_i proportional to its sample weight).
//
// | quantity         | definition                                                                |
// |------------------|---------------------------------------------------------------------------|
// | eval value       | Sum_i w_i f_i(wo, wi) cos_i over the non-delta closures                  |
// | eval pdf         | Sum_i p_i pdf_i(wo, wi); p_i = s_i / Sum_j s_j                           |
// | sample weight s_i| average(w_i) x albedo estimate of closure i (average(base_color) for the  |
// |                  | single-lobe models, 1 for Principled); 0 for Emission and Holdout         |
// | emission         | Sum_i w_i emission_i                                                      |
// | holdout          | Sum of the weights of holdout closures (Cycles shader_holdout_apply)     |
// | transparency     | Sum_i w_i base_color_i over transparent closures (transparent shadows)   |
// | lambertian albedo| Sum_i w_i base_color_i over Lambertian closures (Diffuse): their exact    |
// |                  | directional albedo, the control variate's known integral (textbook 5.17) |
// | albedo estimate  | Sum_i w_i a_i, a_i = base_color (single-lobe models), base_color + 0.04  |
// |                  | dielectric specular (Principled), clamped to 1: Russian roulette by      |
// |                  | albedo (textbook 5.5); any positive survival keeps it unbiased           |
// | colors(wo)       | Sum_i w_i c_i(wo), c_i the closure's Diffuse/Glossy/Transmission Color   |
// |                  | pass values (ClosureModel::colors); computed on request, depends on wo   |
//
// Sampling picks closure i with u_lobe, rescales u_lobe to [0,1) for the closure's own lobe
// choice, and samples it. A non-delta pick reports the full mixture value and pdf (so weight =
// value/pdf is one-sample MIS over closures). A delta pick reports weight w_i f_i/(p_i pdf_i) and
// delta = true: no other closure can produce that exact direction.
// Where the shading normal was perturbed, each closure's value is scaled by its bump shadowing
// term (bsdf/bump_shadowing.h) against the smooth normal given by set_smooth_normal; pdfs are
// unchanged, as Cycles scales eval only.
// Each closure's a_i, s_i / average(w_i), kinds and role (holdout, transparent, Lambertian) are
// its model's answers (ClosureModel, bsdf/bsdf.h), looked up once per closure and question.
// Capacity is fixed (kMaxClosures) with in-place storage, so a texturing step can rewrite the
// parameters of each closure before evaluation; call finalize() after any such change.
#pragma once

#include <array>
#include <cstdint>

#include "bsdf/bsdf.h"
#include "scene/scene.h"

namespace stratum {

inline constexpr uint32_t kMaxClosures = 8;

// What a path changes of a shading point's closures (integrators/light_path_closures.h): Filter
// Glossy's least microfacet alpha (0 = none) and the glossy lobes the caustics switches drop.
struct ClosureFilter {
    float min_alpha = 0.0f;
    bool drop_reflection = false, drop_refraction = false;
    bool active() const { return min_alpha > 0.0f || drop_reflection || drop_refraction; }
};

class ClosureSet {
public:
    // Copies the first kMaxClosures closures (the API rejects more).
    explicit ClosureSet(const SceneMaterial& material);

    WeightedClosure* closures() { return closures_.data(); }
    uint32_t count() const { return count_; }
    // Recomputes the sample weights and the summed quantities from the closures' parameters.
    void finalize();
    // The smooth shading normal in the local frame of the closures' normal (z); call only where
    // the two differ: bump shadowing applies then.
    void set_smooth_normal(Vec3 smooth_normal_local);
    // Applies `filter` to every closure (Material::min_alpha, no_glossy_*); call finalize() after.
    void apply(const ClosureFilter& filter);

    Rgb emission() const { return emission_; }
    Rgb holdout() const { return holdout_; }
    Rgb transparency() const { return transparency_; }
    Rgb lambertian_albedo() const { return lambertian_albedo_; }
    Rgb albedo_estimate() const { return albedo_estimate_; }
    // What the Denoising Albedo pass takes of these closures seen from wo (local frame):
    // Σ weight × (the colours' sum or albedo_estimate, as each model says:
    // ClosureModel::denoising_albedo_from_colors).
    Rgb denoising_albedo(Vec3 wo) const;
    bool has_transmission() const { return has_transmission_; }
    // Whether any closure has a non-delta part that next-event estimation can evaluate.
    bool has_non_delta() const { return has_non_delta_; }
    // Whether any closure scatters light at all.
    bool scatters() const { return sample_weight_sum_ > 0.0f; }

    // `kinds` selects the closures whose value is summed (bit k = ScatterKind k; a Glass closure
    // counts as Glossy for wi above the surface and Transmission below; Principled as both
    // Diffuse and Glossy). The pdf is always the full sampling density.
    BsdfEval eval(Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere, uint32_t kinds = kAllKinds) const;
    bool sample(Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out, HemisphereDistribution hemisphere) const;
    // Sum_i w_i c_i(wo) of the closures' colour pass values (wo in the local frame).
    ClosureColors colors(Vec3 wo) const;
    // Sum_i w_i f_i(wo, wi) cos_i over the Lambertian Diffuse closures only.
    Rgb lambertian_value(Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere) const;

    static constexpr uint32_t kAllKinds = 0xf;

private:
    // `sampled`: the closure that produced wi in sample() (count_ when none did).
    BsdfEval eval_with(Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere, uint32_t kinds,
                       uint32_t sampled) const;

    std::array<WeightedClosure, kMaxClosures> closures_{};
    std::array<float, kMaxClosures> sample_weight_{};
    uint32_t count_ = 0;
    uint32_t scatterers_ = 0;  // closures with a positive sample weight
    float sample_weight_sum_ = 0.0f;
    Rgb emission_, holdout_, transparency_, lambertian_albedo_, albedo_estimate_;
    bool has_transmission_ = false, has_non_delta_ = false;
    bool perturbed_ = false;
    Vec3 smooth_normal_{0.0f, 0.0f, 1.0f};
};

}  // namespace stratum
