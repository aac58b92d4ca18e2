// Which placements of a mesh can be traced at all: Embree maps a ray into an instance's object
// space with the inverse of its transform, and aborts if a coordinate of the mapped ray exceeds
// FLT_LARGE (scene/scene_limits.h). A mesh scaled to (nearly) zero along an axis (a linked
// duplicate scaled (1, 0, 1), or by 1e-18) has an inverse that would; such a placement is
// skipped, with a notice, instead of handed to Embree.
//
// | quantity | meaning |
// |----------|---------|
// | n        | a bound on ‖A(t)⁻¹‖∞ (max row sum of |entries|) over the shutter, A(t) the linear part |
// | T        | a bound on |translation(t)|∞ over the shutter |
// | L        | the largest |coordinate| a ray origin of the scene may have (ray_origin_limit) |
// A placement is traceable iff n (L + T) <= kMaxObjectRayCoordinate: then every object-space
// origin A⁻¹(o − t) and direction A⁻¹d (|d| = 1) of a ray with |o|∞ <= L stays below it.
//
// A static placement's n is its inverse's norm, computed in double. A moving one is
// interpolated by Embree as A(t) = R(t) S(t) (rotation by slerp; S upper triangular, scales on
// its diagonal and skews above it, both linear in t: accel/embree_scene.h). With each scale
// keeping its sign over the shutter, |s_i(t)| >= m (the smallest end value) and |skew(t)| <= K,
// |s_i(t)| <= M (the largest end values), and the inverse of S = [[a, p, q], [0, b, r], [0, 0, c]]
// is [[1/a, −p/(ab), (pr − qb)/(abc)], [0, 1/b, −r/(bc)], [0, 0, 1/c]], so
// ‖S⁻¹‖∞ <= 1/m + K/m² + (K² + KM)/m³, and ‖A⁻¹‖∞ <= √3 ‖A⁻¹‖₂ = √3 ‖S⁻¹‖₂ <= 3 ‖S⁻¹‖∞.
// A scale that changes sign passes through zero: n is infinite.
#pragma once

#include "core/math.h"

namespace stratum {

// n of the table above for a placement moving from `start` to `end` (equal: static).
double inverse_norm_bound(const Transform& start, const Transform& end, bool moving);
// T of the table above.
double translation_bound(const Transform& start, const Transform& end);
// Whether a placement with those bounds is traceable in a scene whose ray origins stay within
// ray_origin_limit.
inline bool traceable(double inverse_norm, double translation, double ray_origin_limit) {
    return inverse_norm * (ray_origin_limit + translation) <= 1e18;
}

}  // namespace stratum
