// A triangle of a mesh whose material emits (Cycles "mesh light"): two-sided, constant
// radiance L_e = emission colour × strength.
//
// | parameter | meaning |
// |-----------|---------|
// | p0, p1, p2| world-space vertices |
// | radiance  | emitted radiance, both faces |
//
// Points are sampled uniformly in area (textbook 4.38, folded square), converted to solid
// angle: pdf = r² / (A |cos θ_light|); the same expression is the MIS pdf for a BSDF ray that
// hits the triangle.
#pragma once

#include "core/math.h"
#include "lights/emission_sample.h"
#include "lights/light_sample.h"

namespace stratum {

class EmissiveTriangle {
public:
    EmissiveTriangle(Vec3 p0, Vec3 p1, Vec3 p2, Rgb radiance);
    bool sample(Vec3 p, Vec2 u, LightSample* out) const;
    // Solid-angle pdf of reaching `hit` on this triangle from `p` by sample().
    float pdf(Vec3 p, Vec3 hit) const;
    // Emitted flux of both faces, π A L_e each (used to choose among lights).
    float power() const { return 2.0f * kPi * area_ * radiance_.average(); }
    // A light-tracing particle (textbook 6.3): point uniform in area (p_A = 1/A), a face chosen
    // with probability ½ by u_direction.x (rescaled and reused), direction cosine-distributed
    // about that face's normal (p_ω = cos/π): weight L cos/(½ p_A p_ω) = 2π A L_e.
    // False for a degenerate triangle.
    bool sample_emission(Vec2 u_position, Vec2 u_direction, EmissionSample* out) const;

private:
    Vec3 p0_, e1_, e2_, normal_;
    float area_;
    Rgb radiance_;
};

}  // namespace stratum
