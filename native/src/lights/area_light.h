// Blender area light: a one-sided planar emitter (square, rectangle, disk or ellipse) facing
// its local −Z axis, optionally narrowed by Cycles' spread.
//
// | parameter        | meaning |
// |------------------|---------|
// | power P          | "Power" in W times colour |
// | size_x, size_y   | "Size" / "Size Y": side lengths, or diameters of disk and ellipse |
// | shape            | rectangle (square is equal sides) or ellipse (disk is equal diameters) |
// | spread s         | "Spread" (full angle, radians, (0, π]); π = plain Lambertian emitter |
//
// Radiance L = P / (π A), A the world-space area: a Lambertian emitter whose flux is P. This is
// Cycles 4.x/5.x; Cycles 3.x used P / (4 A) (docs/cycles_models.md), and the add-on scales the
// power of a 3.x scene by π/4 so both Blenders render what their Cycles renders.
//
// Spread (Cycles 3.4 and 4.x kernel/light/area.h area_light_spread_attenuation, scene/light.cpp;
// Blender D10594, a soft box's grid of slats): the radiance toward a direction at angle a from
// the normal is L · f(a),
//     f(a) = max((tan h − tan a) · N, 0),   h = s/2,   N = 1 / (tan h − h)
// (N = 3/h³ for h <= 0.05, Cycles 4.x's Taylor form; 3.4 uses the exact form, equal there to
// float precision). N normalises the flux: 2π N ∫₀ʰ (tan h − tan a) cos a sin a da = π, so the
// light's power P, its selection weight and the sampling are unchanged by the spread.
// Points are sampled uniformly in area (textbook 4.37 for the rectangle, concentric polar map
// for the ellipse, 4.41), converted to solid angle: pdf = r² / (A |cos θ_light|); f only
// multiplies the radiance of each sample (f > 0 only where cos θ_light > 0, inside the support
// of the pdf, so the estimator stays unbiased).
#pragma once

#include "core/math.h"
#include "lights/light.h"

namespace stratum {

// f(a) above for cos_a = cos a; tan_half = tan h, normalize = N. Returns 1 for spread π
// (tan_half = infinity).
float area_light_spread_attenuation(float cos_a, float tan_half, float normalize);

class AreaLight final : public Light {
public:
    // light_to_world maps the unit shape (x, y in [−½, ½]·size) into the world.
    AreaLight(const Transform& light_to_world, float size_x, float size_y, bool ellipse, Rgb power,
              float spread = kPi);
    bool is_delta() const override { return false; }
    // Rays scattered by BSDFs meet the lamp too (LightSet::lamp_radiance), so NEE is MIS-weighted.
    bool is_hittable_lamp() const override { return true; }
    double power(float /*scene_radius*/) const override { return mean(power_); }
    bool sample(Vec3 p, Vec3 n, Vec2 u, TriangleSampling triangle_sampling, LightSample* out) const override;
    // The ray origin + t·dir (dir unit) meets the emitting face at t in (0, t_max): writes t,
    // the radiance toward the ray's origin (spread included) and the solid-angle pdf with which
    // sample() at the origin produces this direction. False for the back side or a miss.
    bool intersect(Vec3 origin, Vec3 dir, float t_max, float* t, Rgb* radiance, float* pdf) const override;
    // The box of the shape's corners (an ellipse's bounding rectangle); one normal (θ_o = 0),
    // emitting within the spread's half angle h of it (π/2 without spread): f(a) = 0 for a ≥ h.
    std::optional<LightBounds> bounds() const override;
    // A light-tracing particle (textbook 6.3): point uniform in area (p_A = 1/A), direction
    // cosine-distributed about the normal within the spread's cone of half angle h (a uniform
    // point of the disk of radius sin h lifted to the sphere: p_ω = cos/(π sin²h), h = π/2
    // without spread), weight L f(a) cos/(p_A p_ω) = L f(a) π sin²h A (= P without spread).
    bool sample_emission(Vec2 u_position, Vec2 u_direction, Vec3 center, float radius,
                         EmissionSample* out) const override;

private:
    Vec3 point(Vec2 u) const;
    Vec3 center_, axis_x_, axis_y_;  // half extents along the local axes, in world units
    Vec3 normal_;                    // emitting side
    bool ellipse_;
    float area_;
    Rgb power_;
    Rgb radiance_;
    float tan_half_spread_;   // infinity when spread = π
    float normalize_spread_;  // N
    float sin_half_spread_;   // sin h (1 without spread)
};

// STRATUM_LIGHT_AREA_RECTANGLE and STRATUM_LIGHT_AREA_ELLIPSE: transform, size_x, size_y, power =
// color × strength, spread; both check size_x, size_y in (0, kMaxCoordinate] and spread in
// [0, π], 0 read as π (callers written before spread existed pass 0).
extern const LightModel kRectangleAreaLightModel, kEllipseAreaLightModel;

}  // namespace stratum
