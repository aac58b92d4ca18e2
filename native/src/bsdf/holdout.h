// Cycles' Holdout closure: what it covers is black with alpha 0 (a hole in the image).
//
// | parameter      | meaning                                                          |
// |----------------|------------------------------------------------------------------|
// | (closure weight) | the holdout amount: ClosureSet sums the weights of holdouts    |
//
// Reference: Cycles `integrator/surface_shader.h` (surface_shader_apply_holdout,
// shader_holdout_apply in 3.x): the integrator turns the summed weight into transparency of
// the path's throughput. Nothing is scattered (sample weight 0). Colour passes: none.
#pragma once

#include "bsdf/bsdf.h"

namespace stratum {

inline constexpr ClosureModel kHoldoutClosure{.holdout = true};

}  // namespace stratum
