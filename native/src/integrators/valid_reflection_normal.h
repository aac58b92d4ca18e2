// The shading normal a closure is evaluated with, bent so that the mirror reflection of the
// view direction stays above the true (geometric) surface.
//
// | input | meaning                                                                        |
// |-------|--------------------------------------------------------------------------------|
// | ng    | unit geometric normal, on the viewer's side (dot(ng, wo) > 0)                  |
// | wo    | unit direction from the shading point toward the viewer                        |
// | ns    | unit shading normal (interpolated / normal-mapped); may point below the surface |
//
// Reference: Cycles 3.x `ensure_valid_reflection(Ng, I, N)` (kernel/closure/bsdf_util.h),
// applied by svm_node_closure_bsdf to the normal of every BSDF closure of a non-curve surface.
// On a smooth-shaded mesh the interpolated normal can face away from the viewer near
// silhouettes (dot(ns, wo) <= 0): without the bend every closure there is black and the path
// ends, and glossy reflections point into the surface. The bend keeps the rotation minimal:
// the new normal lies in the plane of ns and ng and makes dot(reflect(wo), ng) equal to
// t = min(0.9 dot(ng, wo), 0.01) (a reflection may always be as shallow as the incoming ray).
//
// Derivation (local frame: z = ng, x = the unit part of ns orthogonal to ng, so the new normal
// is (sqrt(1 - z^2), 0, z)): 2 dot(N', wo) z - wo.z = t, with dot(N', wo) = sqrt(1 - z^2) wo.x +
// z wo.z, gives z^2 = (c +- b) / (2a) with a = wo.x^2 + wo.z^2, b = sqrt(wo.x^2 (a - t^2)),
// c = wo.z t + a. A root is usable when 0 < z^2 <= 1; when both are, the one whose reflection is
// above the surface and shallower (closer to the original normal) is taken; when neither is,
// the geometric normal is. A normal whose reflection is already high enough is kept as it is,
// even one below the surface.
#pragma once

#include "core/math.h"

namespace stratum {

Vec3 ensure_valid_reflection(Vec3 ng, Vec3 wo, Vec3 ns);

}  // namespace stratum
