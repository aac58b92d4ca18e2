// Cycles' Emission closure: light leaves the surface, none is scattered.
//
// | parameter | meaning                                                                     |
// |-----------|-----------------------------------------------------------------------------|
// | emission  | emitted radiance (every model may carry one; ClosureSet sums w_i emission_i) |
//
// Reference: Cycles `closure/emissive.h` (emissive_simple_eval: radiance = strength × colour,
// both faces). Its sample weight is 0, so a shading point never chooses it to scatter.
// Colour passes: none (it is no BSDF).
#pragma once

#include "bsdf/bsdf.h"

namespace stratum {

inline constexpr ClosureModel kEmissionClosure{};

}  // namespace stratum
