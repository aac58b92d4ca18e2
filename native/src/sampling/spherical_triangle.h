// Uniform sampling of the solid angle a triangle subtends at a point.
//
// | quantity        | formula                                                   | reference |
// |-----------------|-----------------------------------------------------------|------------------------------|
// | solid angle Ω   | tan(Ω/2) = |a·(b×c)| / (1 + a·b + b·c + c·a), a, b, c unit | Van Oosterom & Strackee
// 1983 | | sample          | sub-triangle (a, b, ĉ) of area u₁Ω, then cos along b→ĉ    | Arvo 1995,
// "Stratified       | |                 | uniform in [b·ĉ, 1] with u₂; density 1/Ω                  |
// Sampling of Spherical        | |                 | | Triangles", SIGGRAPH         |
//
// Why: area sampling (textbook 5.9, pdf r²/(A cos θ_l)) has an unbounded weight cos cos A / r²
// for points close to an emitter; sampling the solid angle makes NEE's weight f L cos Ω, which
// is bounded. Everything is computed in double: Arvo's formula takes differences of nearly
// equal cosines, which float resolves only for triangles much larger than those it serves.
#pragma once

#include "core/math.h"

namespace stratum {

class SphericalTriangle {
public:
    // The triangle (v0, v1, v2) seen from `p`, either orientation.
    SphericalTriangle(Vec3 p, Vec3 v0, Vec3 v1, Vec3 v2);
    // Ω in steradians; 0 when p lies in the triangle's plane or the triangle is degenerate.
    double solid_angle() const { return solid_angle_; }
    // A unit direction from p, uniformly distributed (density 1/Ω) over the spherical triangle;
    // u in [0,1)². Only for solid_angle() > 0. The corners of the square map to the vertices:
    // (0,0) and (1,0) to v1, (0,1) to v0, (1,1) to v2.
    Vec3 sample(Vec2 u) const;
    // The u that sample() maps to the unit direction w (inside the spherical triangle), clamped
    // to [0,1]²: the sub-triangle (v0, v1, ĉ) cut by the great circle through v1 and w has area
    // u₁Ω, and u₂ = (1 − w·v1) / (1 − ĉ·v1).
    Vec2 invert(Vec3 w) const;

    // A direction in double precision (the arithmetic of the .cpp).
    struct Dir {
        double x, y, z;
    };

private:
    Dir a_{}, b_{}, c_{};  // unit directions to the vertices
    double alpha_ = 0.0;   // the spherical angle at a
    double solid_angle_ = 0.0;
};

}  // namespace stratum
