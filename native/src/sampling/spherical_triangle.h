// Uniform sampling of the solid angle a triangle subtends at a point.
//
// | quantity      | formula (a, b, c unit directions to the vertices)           | reference          |
// |---------------|-------------------------------------------------------------|--------------------|
// | solid angle Ω | tan(Ω/2) = |a·(b×c)| / (1 + a·b + b·c + c·a)               | Van Oosterom &     |
// |               |                                                             | Strackee 1983      |
// | sample        | ĉ on arc a→c with area(a, b, ĉ) = Â = u₁Ω, then cos to b    | Arvo 1995,         |
// |               | uniform in [b·ĉ, 1] with u₂; density 1/Ω                    | "Stratified        |
// | 1 − a·ĉ       | (1 − cos Â)(1 + cos c) / ((1 − cos Â) + sin α (1 − cos c)   | Sampling of        |
// |               | sin(α − Â)), c = arc ab, α the angle at a (derived in .cpp) | Spherical Tri."    |
//
// Why: area sampling (textbook 5.9, pdf r²/(A cos θ_l)) has an unbounded weight cos cos A / r²
// for points close to an emitter; sampling the solid angle makes NEE's weight f L cos Ω, which
// is bounded.
// Precision: Arvo's construction takes differences of nearly equal cosines (1 − cos of arcs of a
// few hundredths of a radian), which float resolves only to ~3e-4 rad. So the arithmetic is in
// double, every such difference is taken from a difference of vectors (1 − a·b = |a − b|²/2), and
// ĉ comes from 1 − a·ĉ in the closed form above rather than from a·ĉ; the two angles (atan2 for
// Ω, sin/cos of Â/2) are float functions: their relative error (~1e-7) is all Ω and the samples
// need, and they cost a fraction of the double ones (profiles of the Cornell box showed
// __ieee754_atan2 and __sincos at ~5%). The angle α is never taken: sin α and cos α are ratios
// of the cross products of the arcs at a, whose common denominator the .cpp multiplies out.
#pragma once

#include "core/math.h"

namespace stratum {

class SphericalTriangle {
public:
    // The triangle (v0, v1, v2) seen from `p`, either orientation.
    SphericalTriangle(Vec3 p, Vec3 v0, Vec3 v1, Vec3 v2);
    // Ω in steradians; 0 when p lies in the triangle's plane or the triangle is degenerate.
    double solid_angle() const { return solid_angle_; }
    // The unit direction from p toward vertex v0, v1 or v2 (vertex 0, 1, 2); for
    // solid_angle() > 0.
    Vec3 direction(int vertex) const {
        const Dir& d = vertex == 0 ? a_ : vertex == 1 ? b_ : c_;
        return {float(d.x), float(d.y), float(d.z)};
    }
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
    double solid_angle_ = 0.0;
};

}  // namespace stratum
