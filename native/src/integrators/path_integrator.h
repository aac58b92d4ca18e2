// `path`: unidirectional path tracing with next-event estimation, multiple importance sampling
// and Russian roulette (textbook §5: estimator 5.2 with NEE 5.7–5.16 and MIS §5.5; Veach 1997
// ch. 9 power heuristic β = 2).
//
// | parameter   | meaning |
// |-------------|---------|
// | max_bounces | Cycles' meaning: vertices 0..max_bounces scatter; 0 = direct lighting only |
// | hemisphere  | distribution diffuse lobes sample directions from (sampling/hemisphere.h) |
//
// Emission found by a scattered ray is weighted against light sampling with the power
// heuristic; lights without geometry (point, sun, area lights, which Cycles also keeps out of
// camera rays) are reached only by light sampling and take the full weight. Russian roulette from the 4th
// vertex on, survival = min(1, max throughput).
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
