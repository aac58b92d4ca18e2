// `path`: unidirectional path tracing with next-event estimation, multiple importance sampling
// and Russian roulette (textbook §5: estimator 5.2 with NEE 5.7–5.16 and MIS §5.5; Veach 1997
// ch. 9 power heuristic β = 2), over materials that are mixtures of closures (bsdf/closure_set.h).
//
// | parameter               | meaning |
// |-------------------------|---------|
// | max_bounces             | Cycles' meaning: vertices 0..max_bounces scatter; 0 = direct lighting only |
// | transparent_max_bounces | Transparent pass-throughs per path (and per shadow ray); not bounces |
// | film_transparent        | background seen through camera/transparent rays gives alpha 0 |
// | hemisphere              | distribution diffuse lobes sample directions from (sampling/hemisphere.h) |
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
// Russian roulette from the 4th bounce on, survival = min(1, max throughput).
#pragma once

#include "integrators/integrator.h"

namespace stratum {

class PathIntegrator final : public Integrator {
public:
    explicit PathIntegrator(const IntegratorSettings& settings) : settings_(settings) {}
    RadianceSample radiance(const RenderScene& scene, const Sampler& sampler, const PixelSample& pixel,
                            const CameraRay& ray, uint64_t& rays) const override;

private:
    IntegratorSettings settings_;
};

}  // namespace stratum
