// The shadowing term of a closure whose normal N differs from the smooth shading normal Ns
// (a normal map, or Ns bent by ensure_valid_reflection). A perturbed normal lights directions
// the smooth surface faces away from; these terms hide that terminator and the light leaking
// behind opaque surfaces, as Cycles does (kernel/closure/bsdf.h, bump_shadowing_term).
//
// | model            | term (reference)                                                       |
// |------------------|------------------------------------------------------------------------|
// | Chiang           | diffuse x G(g), g = (Ns'.wi) / ((N.wi)(Ns'.N)), Ns' = Ns turned to     |
// |                  | wi's side of N; G = 0 for g < 0, 1 for g >= 1, -g^3 + g^2 + g between  |
// |                  | (Chiang, Li, Burley 2019, "Taming the Shadow Terminator", eq. 4;       |
// |                  | Cycles 2.90-4.4)                                                       |
// | ChiangUnsmoothed | the 0 for g < 0 only (Cycles 4.2-4.4, Bump Map Correction off)         |
// | Conty            | every lobe 0 when (Ns.wi)(Ns.N)(N.wi) < 0; diffuse x GGX G1(|Ns.wi|)   |
// |                  | with alpha^2 = min(tan^2(N, Ns) / 8, 1) (Conty Estevez, Lecocq, Stein  |
// |                  | 2019, sec. 3; Cycles 4.5+)                                             |
// | ContyUnsmoothed  | the side test only (Cycles 4.5+, Bump Map Correction off)              |
#pragma once

#include <cstdint>

#include "core/math.h"
#include "scene/material.h"

namespace stratum {

// What one closure's value is multiplied by: `all` for every lobe, `diffuse` for its diffuse
// lobes on top. Conty's side test holds for every lobe when a direction is evaluated, but only
// for diffuse lobes when the closure samples wi itself (`sampled`), as Cycles' bsdf_sample.
struct BumpShadowingFactors {
    float all = 1.0f;
    float diffuse = 1.0f;
};

// smooth_normal: Ns in the closure's local frame (z = N), unit; wi: local, unit.
BumpShadowingFactors bump_shadowing(BumpShadowing model, Vec3 smooth_normal, Vec3 wi, bool sampled);

}  // namespace stratum
