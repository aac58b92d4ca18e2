// Cycles' Filter Glossy and caustics switches (Render Properties > Light Paths > Caustics): what
// a path changes of the closures at the next shading point, from what it did so far.
// Cycles 3.4 / 5.0: integrator/surface_shader.h surface_shader_prepare_closures (the blur),
// svm/closure.h (caustics tricks, at closure allocation); the same rules in both.
//
// | quantity           | definition                                                                |
// |--------------------|---------------------------------------------------------------------------|
// | min_ray_pdf        | the least solid-angle pdf of the path's non-transparent scatterings so far |
// |                    | (the closures' mixture pdf of the sampled direction, unguided; delta      |
// |                    | samples do not count; infinity at the camera)                              |
// | blur r             | 0.5 sqrt(1 - min_ray_pdf / filter_glossy) when min_ray_pdf < filter_glossy,|
// |                    | else none (filter_glossy 0 = off): every microfacet lobe's alpha >= r      |
// | after diffuse      | the last non-transparent scattering was diffuse (Cycles' PATH_RAY_DIFFUSE)|
// | dropped reflection | after diffuse, without caustics_reflective: glossy reflection lobes       |
// | dropped refraction | after diffuse, without caustics_refractive: glossy refraction lobes       |
//
// Both are biased by design (they remove or widen light paths); the defaults, filter_glossy 0 and
// both caustics on, change nothing.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "bsdf/closure_set.h"
#include "integrators/light_path_limits.h"

namespace stratum {

// Filter Glossy's least alpha after a path whose least scattering pdf is `min_ray_pdf`; 0 = none.
inline float filter_glossy_alpha(float filter_glossy, float min_ray_pdf) {
    if (!(filter_glossy > 0.0f)) return 0.0f;
    const float blur_pdf = min_ray_pdf / filter_glossy;
    return blur_pdf < 1.0f ? 0.5f * std::sqrt(1.0f - blur_pdf) : 0.0f;
}

// What a path carries for the closures of its next hits.
class PathClosureState {
public:
    // After a scattering of `kind` whose direction had pdf `pdf` (`delta`: a Dirac lobe's).
    // Transparent pass-throughs change nothing.
    void scatter(ScatterKind kind, float pdf, bool delta) {
        if (kind == ScatterKind::Transparent) return;
        after_diffuse_ = kind == ScatterKind::Diffuse;
        if (!delta) min_ray_pdf_ = std::min(min_ray_pdf_, pdf);
    }
    float min_ray_pdf() const { return min_ray_pdf_; }
    bool after_diffuse() const { return after_diffuse_; }

    // The filter the next hit's closures get (ClosureFilter, bsdf/closure_set.h).
    ClosureFilter filter(const LightPathLimits& limits) const {
        return {filter_glossy_alpha(limits.filter_glossy, min_ray_pdf_),
                after_diffuse_ && !limits.caustics_reflective, after_diffuse_ && !limits.caustics_refractive};
    }

private:
    float min_ray_pdf_ = std::numeric_limits<float>::infinity();
    bool after_diffuse_ = false;
};

}  // namespace stratum
