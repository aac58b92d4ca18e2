// A triangle of a mesh whose material emits (Cycles "mesh light"): two-sided, constant
// radiance L_e = emission colour × strength.
//
// | parameter | meaning |
// |-----------|---------|
// | p0, p1, p2| world-space vertices |
// | radiance  | emitted radiance, both faces |
//
// Next-event estimation takes a point on the triangle in one of two ways (TriangleSampling):
// * solid_angle (the default; pbrt-v4's triangle sampling, as Cycles for near triangles): a
//   direction in the solid angle Ω the triangle subtends at the shading point
//   (sampling/spherical_triangle.h), with the square's sample first warped by the bilinear
//   density of cos θ at the three vertex directions (floored at kMinCosineWeight), so that the
//   density is ≈ cos θ / ∫cos θ dω: pdf = bilinear_pdf(u) / Ω. NEE's weight f L cos θ / pdf is
//   then bounded and nearly constant, where area sampling's cos θ cos θ_l A / r² explodes next
//   to the emitter (a ceiling 2 cm above a two-sided lamp: up to A/0.02²). Without the cosine
//   warp the weight would vary with cos θ, which is worse than area sampling where cos θ and
//   cos θ_l / r² cancel (inside a sphere cos θ cos θ_l / r² = 1/(2R)² everywhere). With no
//   normal (n = 0) the direction is uniform in Ω. Area sampling is used instead where the
//   triangle is far: when p's distance to the triangle's plane is at least
//   kSphericalDistanceRatio × its longest edge (Cycles' test, kernel/light/triangle.h), where
//   area sampling's weight varies little and costs a tenth (Cornell box, 64 spp: MSE against a
//   1024-spp reference +0.4%; docs/performance.md), and below kMinSphericalSolidAngle
//   (pbrt-v4's cut-off; a sliver seen from nearby). Both tests depend on p and the triangle
//   only, so the MIS pdf (pdf()) takes the branch sample() took. Area sampling is also used
//   when p lies in the triangle's plane to within float precision of the coordinates
//   (kCoplanarTolerance × their magnitude): the triangle p itself lies on, or a coplanar
//   neighbour. There the solid angle is decided by rounding (anything from 0 to 2π for a point
//   on the triangle, and on which side), and a sample of weight Ω/p_choice toward the triangle
//   under the surface would be a firefly; area sampling's weight cos θ_l ≈ 0 is right.
// * area: a point uniform in area (textbook 4.38, folded square), converted to solid angle:
//   pdf = r² / (A |cos θ_light|), the textbook's NEE (5.9).
// The pdf of the mode in use is also the MIS pdf for a BSDF ray that hits the triangle; it
// depends only on the shading point, its normal and the triangle, so both strategies agree on
// it.
#pragma once

#include <optional>

#include "core/math.h"
#include "lights/light.h"
#include "lights/light_selection.h"
#include "sampling/spherical_triangle.h"
#include "sampling/warps.h"

namespace stratum {

class EmissiveTriangle final : public Light {
public:
    EmissiveTriangle(Vec3 p0, Vec3 p1, Vec3 p2, Rgb radiance);
    bool is_delta() const override { return false; }
    // Rays find it in the BVH, not among the lamps.
    bool is_hittable_lamp() const override { return false; }
    // Emitted flux of both faces, π A L_e each (used to choose among lights).
    double power(float /*scene_radius*/) const override {
        return 2.0 * kPi * static_cast<double>(area_) * mean(radiance_);
    }
    // A light sample for the shading point p with normal n (unit, or 0 when it has none), the
    // point taken as `mode` says.
    bool sample(Vec3 p, Vec3 n, Vec2 u, TriangleSampling mode, LightSample* out) const override;
    // Solid-angle pdf of reaching `hit` on this triangle from (p, n) by sample() in `mode`.
    float pdf(Vec3 p, Vec3 n, Vec3 hit, TriangleSampling mode = TriangleSampling::SolidAngle) const;
    // The box of the vertices; the normal, two-sided, each face emitting over its hemisphere.
    std::optional<LightBounds> bounds() const override;
    // A light-tracing particle (textbook 6.3): point uniform in area (p_A = 1/A), a face chosen
    // with probability ½ by u_direction.x (rescaled and reused), direction cosine-distributed
    // about that face's normal (p_ω = cos/π): weight L cos/(½ p_A p_ω) = 2π A L_e.
    // False for a degenerate triangle.
    bool sample_emission(Vec2 u_position, Vec2 u_direction, Vec3 center, float radius,
                         EmissionSample* out) const override;

    // Steradians, the plane distance over the longest edge from which the triangle is far, and
    // the cosine weight's floor (a vertex below the horizon still gets some samples: the
    // support stays the whole spherical triangle); see the header comment.
    static constexpr double kMinSphericalSolidAngle = 3e-4;
    static constexpr float kSphericalDistanceRatio = 1.0f;
    static constexpr float kMinCosineWeight = 0.01f;
    // Barycentric interpolation puts a hit point within a few ulps (≈ 2e-7 × the coordinates'
    // magnitude) of its triangle's plane; 50 times that.
    static constexpr float kCoplanarTolerance = 1e-5f;

private:
    bool sample_area(Vec3 p, Vec2 u, LightSample* out) const;
    float pdf_area(Vec3 p, Vec3 hit) const;
    // The triangle as seen from p when solid-angle sampling applies to p, else nullopt.
    std::optional<SphericalTriangle> spherical_view(Vec3 p) const;
    // The bilinear weights of the cosine warp: |cos θ| toward the vertices (the spherical
    // triangle's own unit directions) at the corners the spherical map sends to them
    // (SphericalTriangle::sample); all 1 without a normal.
    BilinearWeights cosine_weights(const SphericalTriangle& spherical, Vec3 n) const;

    Vec3 p0_, e1_, e2_, normal_;
    float area_;
    // kCoplanarTolerance × the largest vertex coordinate's magnitude (fixed per triangle).
    float coplanar_distance_;
    // (kSphericalDistanceRatio × the longest edge)²: solid-angle sampling below that squared
    // plane distance.
    float spherical_distance2_;
    Rgb radiance_;
};

}  // namespace stratum
