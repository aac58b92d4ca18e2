// `ao`: ambient occlusion of the first surface a camera ray hits (seed 000, eq. 20).
//
// | parameter   | meaning |
// |-------------|---------|
// | hemisphere  | distribution of the occlusion rays (sampling/hemisphere.h): uniform_angles, uniform, cosine
// (default) | | ao_distance | an obstacle closer than this along the ray occludes (scene units, > 0; infinity
// = unlimited; default 1) | | output      | the AO factor in [0,1] as grey: 1 = fully open (white), 0 = fully
// occluded | | background  | camera rays that miss: 1 (nothing occludes the open sky) |
//
// Seed 000 defines the occluded fraction, with V(ω) = 1 when a ray in direction ω hits an
// obstacle within ao_distance:
//     O = (1/π) ∫∫ V cos θ sin θ dθ dφ = (1/π) ∫_{H²} V(ω) cos θ dω ∈ [0,1].
// Like most renderers we display the openness A = 1 − O (white = unoccluded). One direction per
// pixel sample, ω ~ p (the chosen distribution, exact solid-angle pdf), gives the unbiased
//     A ≈ 1 − (1/π) V(ω) cos θ / p(ω).
// Estimating O and subtracting (rather than averaging (1 − V) cos θ / (π p)) makes an
// unoccluded point exactly 1 with every distribution; with `cosine`, cos θ/(π p) = 1 and each
// sample is exactly 0 or 1. With the other two a single sample may leave [0,1] (uniform:
// 1 − 2 cos θ V; uniform_angles: 1 − π sin θ cos θ V); their mean is still A.
//
// The hemisphere is around the shading normal turned to the viewer's side; a direction below
// the geometric surface counts as occluded (the surface itself blocks it). The direction's 2D
// sample is bounce_dimension(0, kDimBsdfDirection) of the named layout.
#pragma once

#include "integrators/integrator.h"

namespace stratum {

class AoIntegrator final : public Integrator {
public:
    explicit AoIntegrator(const IntegratorSettings& settings) : settings_(settings) {}
    RadianceSample estimate(const RenderScene& scene, const Sampler& sampler, const PixelSample& pixel,
                            const CameraRay& ray, PassValues& passes, uint64_t& rays) const override;

private:
    IntegratorSettings settings_;
};

}  // namespace stratum
