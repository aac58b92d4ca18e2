// BSDF interface used by the integrators: one evaluation and one sampling entry point for every
// surface model, which looks up the model's entry (ClosureModel) by Material::model in the
// registry of bsdf.cpp. Directions below the shading horizon (wi.z < 0) are transmission; only
// Glass, Transparent and the Principled models with transmission produce them.
// The models, one line each with what they are, form that registry; each model's file opens
// with its parameters and reference.
//
// Material parameters: roughness is the artist roughness (alpha = roughness^2); `specular` is
// Cycles 3.x "Specular" for V1 and 4.x "Specular IOR Level" for V2 (0.5 keeps `ior` unchanged);
// `ior` is used by V2 only (V1 derives its IOR from `specular`, as Cycles 3.x does).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "bsdf/bump_shadowing.h"
#include "core/math.h"
#include "core/model_table.h"
#include "sampling/hemisphere.h"
#include "scene/material.h"

namespace stratum {

// What kind of scattering produced a direction: it selects the ray visibility bit of the next
// ray, the light visibility bit NEE honours, and whether the vertex counts as a bounce.
enum class ScatterKind : uint8_t { Diffuse, Glossy, Transmission, Transparent };
inline constexpr uint32_t scatter_kind_bit(ScatterKind k) { return 1u << static_cast<uint32_t>(k); }

// value = f(wo, wi) |cos theta_i|; pdf = solid-angle density with which bsdf_sample produces wi;
// diffuse = the part of value from diffuse lobes (Lambert, Burley), which bump shadowing scales.
struct BsdfEval {
    Rgb value;
    float pdf;
    Rgb diffuse{};
};

// weight = value / pdf for the sampled wi (the path throughput factor). A delta lobe (smooth
// glass, mirror, transparent) reports delta = true and pdf = 1 by convention: its direction can
// be found by no other strategy, so emission it reaches takes the full MIS weight.
struct BsdfSample {
    Vec3 wi;
    Rgb weight;
    float pdf;
    bool delta = false;
    ScatterKind kind = ScatterKind::Diffuse;
};

// What a closure that scatters nothing answers: ClosureModel's defaults, so that emission,
// holdout and a value without a model state only what they add.
inline BsdfEval no_scattering_eval(const Material&, Vec3, Vec3, HemisphereDistribution) {
    return {Rgb(), 0.0f};
}
inline bool no_scattering_sample(const Material&, Vec3, float, Vec2, BsdfSample*, HemisphereDistribution) {
    return false;
}
inline bool answer_false(const Material&) { return false; }
inline bool answer_true(const Material&) { return true; }
inline float no_sample_weight(const Material&) { return 0.0f; }
inline Rgb no_albedo(const Material&) { return Rgb(0.0f); }

// What a closure adds, per unit of its weight, to Cycles' Diffuse, Glossy and Transmission Color
// passes (kernel/film/data_passes.h: surface_shader_diffuse/glossy/transmission): Cycles 3.x sums
// the weights of its closures of each type, 4.x their bsdf_albedo estimates; each model reports
// those of the Cycles generation it imitates, for the view direction wo (local frame).
struct ClosureColors {
    Rgb diffuse, glossy, transmission;
};
inline ClosureColors no_colors(const Material&, Vec3) { return {}; }

// What a closure model answers for itself: each model's file defines its entry, and one line of
// the registry in bsdf.cpp files it under its StratumMaterialModel value. Every question costs one
// lookup and at most one indirect call, where a switch over the models cost one indirect jump.
// What a model leaves out answers as a closure that scatters nothing.
struct ClosureModel {
    // f(wo, wi) |cos θ_i| and the pdf of sample() (bsdf_eval below).
    BsdfEval (*eval)(const Material& m, Vec3 wo, Vec3 wi,
                     HemisphereDistribution hemisphere) = &no_scattering_eval;
    // A direction (bsdf_sample below).
    bool (*sample)(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                   HemisphereDistribution hemisphere) = &no_scattering_sample;
    // A Dirac distribution only (bsdf_is_delta below).
    bool (*is_delta)(const Material& m) = &answer_false;
    // Can send light through the surface (bsdf_has_transmission below).
    bool (*has_transmission)(const Material& m) = &answer_false;
    // The closure's share of the choice among the closures of a shading point, per unit of its
    // weight, and the colour albedo Russian roulette survives by (bsdf/closure_set.h's table).
    float (*sample_weight)(const Material& m) = &no_sample_weight;
    Rgb (*albedo_estimate)(const Material& m) = &no_albedo;
    // Its Diffuse/Glossy/Transmission Color pass values seen from wo (ClosureColors above).
    ClosureColors (*colors)(const Material& m, Vec3 wo) = &no_colors;
    // ScatterKind bits a direction above (wi.z >= 0) and below the shading horizon counts as
    // (ClosureSet::eval's `kinds`).
    uint32_t kinds_above = 0, kinds_below = 0;
    // What ClosureSet sums besides scattering: its weight is the holdout (Cycles
    // shader_holdout_apply); weight × base_color passes shadow rays (transparent shadows); f is
    // exactly base_color/π, so its albedo is the control variate's known integral (textbook 5.17).
    bool holdout = false, transparent = false, lambertian = false;
    // Its Denoising Albedo is the sum of its colours (Cycles 4.x: film_write_denoising_features_
    // surface sums bsdf_albedo, what Principled v2's colours are) rather than albedo_estimate
    // (Cycles 3.x scales closure weights by their Fresnel colour, which albedo_estimate
    // approximates; one-lobe models answer the same either way).
    bool denoising_albedo_from_colors = false;
};

// Closure models are numbered 0 .. kMaxClosureModels − 1.
inline constexpr int32_t kMaxClosureModels = 32;
using ClosureModels = ModelTable<ClosureModel, kMaxClosureModels>;

// Every registered closure model, in value order (what stratum_model_* list).
const ClosureModels& closure_models();
// The entry of `model`; a value no model is registered under scatters nothing.
const ClosureModel& closure_model(int32_t model);
// The entry registered under `model`, or null (how the C ABI tells a model it knows).
const ClosureModel* find_closure_model(int32_t model);
// Registers `entry` (kept by address: a static) under a value that has none, with `name` (a
// static string): how a test adds a closure model of its own. Call it before any material of
// that model is validated or shaded, and not while another thread reads the registry. False when
// the value is out of range or taken.
bool register_closure_model(int32_t model, const char* name, const ClosureModel& entry);

// A microfacet lobe's roughness at a shading point (alpha = roughness^2): Filter Glossy raises
// alpha to Material::min_alpha (Cycles bsdf_blur: alpha = max(alpha, r)); the host's otherwise.
inline float blurred_roughness(float roughness, const Material& m) {
    return m.min_alpha > 0.0f ? std::max(roughness, std::sqrt(m.min_alpha)) : roughness;
}

// Answers several models share.
// A single lobe tinted by base_color: average(base_color) and base_color.
inline float tint_sample_weight(const Material& m) { return m.base_color.average(); }
inline Rgb tint_albedo_estimate(const Material& m) { return m.base_color; }
// A single lobe of one Cycles closure type whose weight is the colour (Diffuse, Glossy nodes).
inline ClosureColors tint_diffuse_colors(const Material& m, Vec3) { return {m.base_color, Rgb(), Rgb()}; }
inline ClosureColors tint_glossy_colors(const Material& m, Vec3) { return {Rgb(), m.base_color, Rgb()}; }
// The Principled models: the specular layer reflects whatever the base colour (sample weight 1,
// albedo estimate base_color + 0.04 of a dielectric layer); transmission when there is some.
inline float principled_sample_weight(const Material&) { return 1.0f; }
inline Rgb principled_albedo_estimate(const Material& m) { return m.base_color + Rgb(0.04f); }
inline bool principled_has_transmission(const Material& m) { return m.transmission > 0.0f; }
inline constexpr uint32_t kPrincipledKindsAbove =
    scatter_kind_bit(ScatterKind::Diffuse) | scatter_kind_bit(ScatterKind::Glossy);

// Whether a closure of this model is a Dirac distribution only (it never contributes to NEE).
bool bsdf_is_delta(const Material& m);
// Whether the closure can send light through the surface (NEE must then test lights below it).
bool bsdf_has_transmission(const Material& m);

// wo, wi in the local shading frame (z = shading normal), both pointing away from the surface;
// wo points toward the viewer (wo.z > 0). wi.z < 0 is transmission (0 for opaque models).
// Transmissive models read `ior` as the relative IOR of the side below the horizon over the
// side of wo (the caller inverts it on back faces, as Cycles does with SD_BACKFACING).
// Delta lobes are not part of bsdf_eval (their value is a Dirac; eval gives 0 there).
// `hemisphere` is the distribution diffuse lobes sample directions from (a render setting);
// the pdf reported is always the exact density of that choice, so every choice is unbiased.
BsdfEval bsdf_eval(const Material& m, Vec3 wo, Vec3 wi,
                   HemisphereDistribution hemisphere = HemisphereDistribution::Cosine);
// u_lobe picks the lobe, u warps inside it. Returns false when no direction is produced (absorbed).
bool bsdf_sample(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                 HemisphereDistribution hemisphere = HemisphereDistribution::Cosine);

}  // namespace stratum
