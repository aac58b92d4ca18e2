// Lambertian reflection.
//
// | parameter  | meaning                            |
// |------------|------------------------------------|
// | base_color | albedo rho; f = rho / pi           |
//
// Colour passes: Diffuse Color = base_color (Cycles' diffuse closure weight, 3.x and 4.x).
//
// Reference: Cycles `bsdf_diffuse.h` (Diffuse BSDF with roughness 0), textbook 4.60-4.61 for
// the cosine-weighted sampling, which makes weight = rho exactly.
#pragma once

#include "bsdf/bsdf.h"

namespace stratum {

BsdfEval lambert_eval(const Material& m, Vec3 wo, Vec3 wi, HemisphereDistribution hemisphere);
bool lambert_sample(const Material& m, Vec3 wo, Vec2 u, BsdfSample* out, HemisphereDistribution hemisphere);

// STRATUM_MATERIAL_DIFFUSE.
extern const ClosureModel kLambertClosure;

}  // namespace stratum
