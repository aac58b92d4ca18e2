// `path` (and `direct`): unidirectional path tracing, the textbook's ladder of estimators
// (§5: estimator 5.2; NEE 5.7–5.16; MIS §5.5 with Veach 1997 ch. 9's heuristics; Russian
// roulette 5.5–5.6; the control variate 5.17–5.18), over materials that are mixtures of
// closures (bsdf/closure_set.h).
//
// | parameter          | meaning                                                                 |
// |--------------------|-------------------------------------------------------------------------|
// | max_bounces        | Cycles' meaning: vertices 0..max_bounces scatter; 0 = direct light only |
// | diffuse_bounces,   | the same per kind, with clamp_direct and clamp_indirect: Cycles' Light  |
// | glossy_bounces,    | Paths (integrators/light_path_limits.h)                                 |
// | transmission_...   |                                                                         |
// | light_sampling     | bsdf: emission found by scattered rays only (5.2); nee: by light        |
// |                    | samples, a hit counts only after the camera or a delta scatter (5.16);  |
// |                    | mis: both, weighted                                                     |
// | mis_heuristic      | balance / power (β = 2) / max, for every emission a scattered ray hits  |
// |                    | (lamps, emissive triangles, environment) and every light sample         |
// | light_selection    | the light choice distribution of NEE (lights/light_set.h)               |
// | rr_mode,           | Russian roulette from bounce rr_min_depth on: off, survival             |
// | rr_min_depth       | min(1, max β), or min(1, max albedo estimate)                           |
// | control_variate    | L_a: each vertex adds β L_a ρ_L and subtracts β L_a f_L cos/p           |
// |                    | (÷ survival) for its Lambertian closures (ρ_L exact); 0 = off; not      |
// |                    | clamped                                                                 |
// | transparent_max_   | Transparent pass-throughs per path (and per shadow ray); not bounces    |
// | bounces            |                                                                         |
// | film_transparent   | background seen through camera/transparent rays gives alpha 0           |
// | hemisphere         | distribution diffuse lobes sample directions from (sampling/hemisphere.h) |
// | use_guiding, ...   | path guiding: directions from f · closures + (1 − f) · the tree learned |
// |                    | from the first training samples (integrators/guided_direction.h)        |
//
// Cycles conventions followed (Cycles 3.4 and 4.x `integrator/intersect_closest.h`,
// `shade_surface.h`, `shade_shadow.h`, `film/accumulate.h`):
// * Emission found by a scattered ray is weighted against light sampling with the power
//   heuristic; lights without geometry are reached only by light sampling (full weight);
//   emission reached after a delta scatter takes the full weight.
// * A sampled Transparent closure continues the ray straight on; it is not a bounce, keeps the
//   ray's visibility kind and its MIS pdf, and counts against transparent_max_bounces.
// * After the last bounce the ray still passes surfaces with Transparent closures (times their
//   summed weight) and collects the emission behind them, then ends (Cycles'
//   PATH_RAY_TERMINATE_AFTER_TRANSPARENT).
// * Shadow rays pass surfaces whose material has Transparent closures, times their summed
//   weight x colour, up to transparent_max_bounces surfaces; any other surface occludes.
// * Holdout (Holdout closures, or SurfaceHit::holdout for a holdout object) while the path has
//   only passed camera and transparent vertices: the holdout weight's share of the throughput
//   becomes transparency (alpha = 1 - transparency) when film_transparent, and the holdout
//   closure adds no light; a holdout object ends the path (black, whatever the film).
// * Light visibility: a light's DIFFUSE / GLOSSY / TRANSMISSION bits select which closures NEE
//   lights; with its SHADOW bit off no occlusion is tested (Cycles cast_shadow off).
// The control variate is unbiased whatever L_a (the added and subtracted terms have equal
// expectation); with BSDF sampling, albedo roulette and L_a equal to the radiance of a closed
// uniform enclosure every path returns exactly L_a (5.17; research/textbook.md §2.1 test B).
#pragma once

#include "integrators/integrator.h"
#include "integrators/shadow_catcher.h"
#include "integrators/shadow_linking.h"

namespace stratum {

class PathIntegrator final : public Integrator {
public:
    explicit PathIntegrator(const IntegratorSettings& settings) : settings_(settings) {}
    // The light tree, when this render chooses lights by it, is built here, before the first
    // sample: not by the first light sample while every other thread waits for it.
    // With guiding, the tree starts empty here (uniform guide) over a cube padded 1% around the
    // scene's bounding sphere.
    void prepare(const RenderScene& scene, const std::atomic<bool>&) override;
    void end_pass(uint32_t begin, uint32_t end) override;
    const GuidingReport* guiding_report() const override { return guide_ ? &guiding_report_ : nullptr; }
    RadianceSample estimate(const RenderScene& scene, const Sampler& sampler, const PixelSample& pixel,
                            const CameraRay& ray, PassValues& passes, uint64_t& rays) const override;
    std::vector<std::string> notices(const Scene& scene) const override;
    bool splits_shadow_catchers() const override { return true; }
    bool writes_light_groups() const override { return true; }

private:
    // One path of the camera sample: the main path, or the catcher-only copy of one that split at
    // a shadow catcher (integrators/shadow_catcher.h).
    RadianceSample trace(const RenderScene& scene, const Sampler& sampler, const PixelSample& pixel,
                         const CameraRay& ray, PassValues& passes, uint64_t& rays,
                         ShadowCatcherPath& catcher) const;
    // MIS weight of emission a scattered ray hits (scatter_pdf 0 after a camera or delta
    // vertex) against the light sample that could have drawn it (light_pdf 0: none could).
    float hit_weight(float scatter_pdf, float light_pdf) const;
    // Shadow linking's dedicated pass for the ray a vertex scattered (integrators/
    // shadow_linking.h): the emission it adds per unit throughput (clamped by the caller).
    Rgb shadow_linked_emission(const RenderScene& scene, const ScatteredRay& ray, uint64_t& rays,
                               uint32_t* lightgroup) const;
    // Whether hit_weight reads light_pdf's value: not after a camera or delta vertex, nor under
    // BSDF sampling alone. Evaluating the light pdf (for a triangle, its spherical view) is
    // skipped otherwise.
    bool light_pdf_matters(float scatter_pdf) const {
        return scatter_pdf > 0.0f && settings_.light_sampling != LightSampling::Bsdf;
    }

    IntegratorSettings settings_;
    // Read-only within a pass (its counters take the records, order-independently).
    std::unique_ptr<GuidingTree> guide_;
    GuidingReport guiding_report_;
};

}  // namespace stratum
