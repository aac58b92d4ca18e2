// Blender point light (Cycles conventions; see docs/cycles_models.md §4 "Point light").
//
// | parameter | meaning |
// |-----------|---------|
// | power P   | Blender "Power" in W times colour; radiant intensity I = P / (4π) |
// | radius r  | "Radius" (shadow_soft_size): a disk of radius r that always faces the shading point |
//
// r = 0 is the textbook delta point light (textbook 5.11): irradiance I/d² at normal incidence.
// r > 0 is Cycles' "oriented disk" point light (3.x: kernel/light/light.h; 4.1+ with Soft
// Falloff on, Blender's default: kernel/light/point.h, is_sphere false): a disk of radius r
// centred on the light, its normal toward the shading point p, emitting the uniform radiance
//     L = I / (π r²) = P / (4π² r²)
// toward p. Directly below at distance d its irradiance is L·π·r²/(d² + r²) = I/(d² + r²)
// (measured in Cycles 3.4 and 5.0.1, docs/features.md). It is sampled uniformly by area, solid
// angle pdf dist² / (π r² cos θ_l), θ_l between the ray and the disk normal; a ray (camera or
// scattered) meets the disk facing its own origin (Cycles' point_light_intersect), so
// LightSet::lamp_radiance finds it and NEE is MIS-weighted.
#pragma once

#include "core/math.h"
#include "lights/light.h"

namespace stratum {

// The disk of radius r at `center` facing `p`, shared by the point and spot lights.
struct FacingDiskSample {
    Vec3 wi;         // unit, from p toward the sampled point
    float distance;  // from p to the sampled point
    float pdf;       // solid angle
};
// Samples the disk uniformly by area with u; false if p is at the centre.
bool sample_facing_disk(Vec3 center, float radius, Vec3 p, Vec2 u, FacingDiskSample* out);
// Where the ray (origin, unit dir) meets the disk of radius r at `center` that faces the origin,
// before t_max: *t and the solid-angle pdf sample_facing_disk gives that direction.
bool intersect_facing_disk(Vec3 center, float radius, Vec3 origin, Vec3 dir, float t_max, float* t,
                           float* pdf);

class PointLight final : public Light {
public:
    PointLight(Vec3 position, Rgb power, float radius);
    // A zero radius is a delta light no ray finds; a radius gives the facing disk rays meet.
    bool is_delta() const override { return radius_ <= 0.0f; }
    bool is_hittable_lamp() const override { return radius_ > 0.0f; }
    // sample_emission() below starts from the centre of a lamp with a radius.
    bool emits_from_its_centre() const override { return radius_ > 0.0f; }
    // Emitted power in W, used to choose among lights.
    double power(float /*scene_radius*/) const override { return mean(power_); }
    bool sample(Vec3 p, Vec3 n, Vec2 u, TriangleSampling triangle_sampling, LightSample* out) const override;
    // The disk met by the ray (origin, unit dir) before t_max (radius > 0 only): distance,
    // radiance and sample()'s solid-angle pdf of dir.
    bool intersect(Vec3 origin, Vec3 dir, float t_max, float* t, Rgb* radiance, float* pdf) const override;
    // The ball of radius r about the centre (the facing disk's points), emitting every way.
    std::optional<LightBounds> bounds() const override {
        return omnidirectional_bounds(position_, radius_, 0.0);
    }
    // A light-tracing particle (textbook 6.4): from the centre, direction uniform on the sphere
    // (p_ω = 1/(4π)), weight I/p_ω = P. A radius r is Cycles' disk facing each receiver, which
    // no emitter in space reproduces: the particle leaves the centre and its first hit at
    // distance d takes d²/(d² + r²) (soft_radius), the facing disk's irradiance I/(d² + r²)
    // over the point's I/d² — exact for a receiver facing the lamp with nothing in the way;
    // tilted receivers differ by O(r²/d²) and shadows are those of the centre (hard).
    bool sample_emission(Vec2 u_position, Vec2 u_direction, Vec3 center, float radius,
                         EmissionSample* out) const override;

private:
    Vec3 position_;
    Rgb power_;
    Rgb intensity_;      // W/sr
    Rgb disk_radiance_;  // of the facing disk of a lamp with a radius: I / (π r²)
    float radius_;
};

// STRATUM_LIGHT_POINT: position from the transform, power = color × strength, radius.
extern const LightModel kPointLightModel;

}  // namespace stratum
