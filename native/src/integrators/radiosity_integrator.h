// `radiosity`: the textbook's deterministic method for diffuse scenes (§3), shown through a
// final gather.
//
// | parameter            | meaning |
// |----------------------|---------|
// | radiosity_patch_size | patches' longest edge (radiosity/patch_set.h; 0 = scene diagonal / 32) |
// | radiosity_rays       | form-factor rays per patch (radiosity/form_factors.h) |
// | radiosity_solver     | shooting, gauss_seidel or jacobi (radiosity/radiosity_solvers.h) |
// | radiosity_tolerance  | the solve stops at ΔE ≤ tolerance × mean radiance (radiosity/radiosity_system.h) |
// | light_selection, light_tree_splits, triangle_sampling | the final gather's light sample (as `path`) |
// | film_transparent     | background seen by the camera gives alpha 0 |
//
// prepare() solves the scene once (radiosity/radiosity_solution.h): the solution depends on the
// scene only, so the next render of the same renderer keeps it while only the camera changes
// (adopt(): the viewport's start passes and orbits do not solve again). Each camera sample then takes, at the
// first surface x it meets (diffuse albedo κ(x) of its textured closures, Diffuse Color as seen from the
// camera):
//     L = L_e(x) + (κ(x)/π) [ L_l c / p_l  +  M_r(y) ]
// * L_l c / p_l: the path tracer's next-event estimation (LightSet::sample_cut: one light
//   sample, or one per cut node of a split light tree, each with a shadow ray): the direct
//   light of lamps, emissive triangles and the environment, estimated at x;
// * M_r(y): one cosine-distributed gather ray about the shading normal; at the patch y it hits,
//   its reflected exitance M − M_e (emission is the light sample's); escaping, π × the constant
//   background when there is no environment light (an environment is the light sample's). With
//   pdf c/π, π L(y) = M_r(y) estimates ∫ L_r c dω.
// Lamps met by the camera add their radiance, as in the path tracer.
//
// Why a final gather rather than radiosity interpolated at vertices: the patches' piecewise
// constant M is only seen after one reflection, where it is averaged over the gather's
// hemisphere, so patch-sized blotches and light leaks at patch boundaries do not show; direct
// light (the sharpest part: hard shadows of point lamps, texture detail of κ) is computed at x
// itself rather than at patch centres; and the image converges like any Monte Carlo render
// (unbiased for the discretised indirect light), which the comparison tools expect. The cost is
// two rays and a shadow ray per sample, against one for interpolation.
//
// Surfaces are diffuse here: a material with glossy, glass or transparent closures is rendered
// by its diffuse albedo alone, and the render says so once, naming the materials.
// Deterministic: the solve is (fixed ray sets, sums in a fixed order), and each sample draws
// its numbers from the sampler as every integrator does.
#pragma once

#include <memory>

#include "integrators/integrator.h"

namespace stratum {

class RadiosityIntegrator final : public Integrator {
public:
    explicit RadiosityIntegrator(const IntegratorSettings& settings) : settings_(settings) {}
    void prepare(const RenderScene& scene, const std::atomic<bool>& cancel) override;
    // The previous render's solution, when it was a radiosity render with the same settings
    // (the renderer vouches that the scene is the same): the solve depends on the scene only.
    bool adopt(const Integrator& previous) override;
    RadianceSample estimate(const RenderScene& scene, const Sampler& sampler, const PixelSample& pixel,
                            const CameraRay& ray, PassValues& passes, uint64_t& rays) const override;
    std::vector<std::string> notices(const Scene& scene) const override;
    const RadiosityReport* radiosity_report() const override {
        return solution_ ? &solution_->report() : nullptr;
    }

private:
    IntegratorSettings settings_;
    std::shared_ptr<const RadiositySolution> solution_;
};

}  // namespace stratum
