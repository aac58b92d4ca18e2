// Blender spot light (Cycles conventions; see docs/cycles_models.md §4 "Spot light").
//
// | parameter      | meaning |
// |----------------|---------|
// | power P        | "Power" in W times colour; on the axis the intensity is P/(4π), as a point |
// |                | light's (the cone does not concentrate the power) |
// | radius r       | "Radius" (shadow_soft_size): a disk of radiance I/(π r²) facing the |
// |                | shading point, as the point light's |
// | spot_size      | "Spot Size": full cone angle in (0, π]; half angle θ_h = spot_size / 2 |
// | spot_blend b   | "Blend" in [0, 1]: the smoothstep falloff toward the edge |
// | cosine_falloff | Cycles 3.x also multiplies by cos θ (θ to the axis); 4.x/5.x does not |
//
// Intensity toward a direction at angle θ from the axis (the light's local −Z):
//     I(θ) = P/(4π) · S(cos θ) · (cos θ if cosine_falloff),
//     S(c) = smoothstep((c − cos θ_h) / ((1 − cos θ_h) b)),  smoothstep(x) = 3x² − 2x³ on [0, 1],
// 0 below, 1 above; b = 0 makes a hard edge (S = 1 inside the cone, 0 outside). With radius r
// the emitter is the point light's disk facing the shading point (radiance I/(π r²), sampled
// uniformly by area; Cycles 3.x and 4.1+ with Soft Falloff, kernel/light/spot.h) and the factor
// is evaluated for the direction from the sampled point of the disk toward the shading point,
// as Cycles does. Rays meet the disk as they meet the point light's (LightSet::lamp_radiance),
// times the factor for −dir. Non-uniform scale of the transform is ignored: the axis is the
// transformed −Z, normalized, and the cone stays circular.
#pragma once

#include "core/math.h"
#include "lights/light.h"
#include "lights/point_light.h"

namespace stratum {

class SpotLight final : public Light {
public:
    SpotLight(const Transform& light_to_world, Rgb power, float radius, float spot_size, float spot_blend,
              bool cosine_falloff);
    // As the point light: delta at radius 0, a facing disk rays meet otherwise.
    bool is_delta() const override { return radius_ <= 0.0f; }
    bool is_hittable_lamp() const override { return radius_ > 0.0f; }
    // sample_emission() below starts from the centre of a lamp with a radius.
    bool emits_from_its_centre() const override { return radius_ > 0.0f; }
    // Emitted power in W as Blender states it (the point light's), used to choose among lights.
    double power(float /*scene_radius*/) const override { return mean(power_); }
    bool sample(Vec3 p, Vec3 n, Vec2 u, TriangleSampling triangle_sampling, LightSample* out) const override;
    // As PointLight::intersect, with the angular factor of the direction −dir.
    bool intersect(Vec3 origin, Vec3 dir, float t_max, float* t, Rgb* radiance, float* pdf) const override;
    // The ball of radius r about the centre; cone about the axis: full intensity within θ_o
    // (where the blend's smoothstep reaches 1), none beyond θ_h = θ_o + θ_e.
    std::optional<LightBounds> bounds() const override;
    // The angular factor I(θ) / (P/(4π)) for cos θ = cos_theta (θ from the axis).
    float attenuation(float cos_theta) const;
    // Radiance of the facing disk of a lamp with a radius at angular factor a: I a / (π r²),
    // saturating (a 3e38 W lamp of radius 1 cm would overflow).
    Rgb disk_radiance(float a) const {
        return saturating_product(intensity_, a / (kPi * static_cast<double>(radius_) * radius_));
    }
    // A light-tracing particle (textbook 6.4): from the centre, direction uniform in the cone
    // of half angle θ_h (p_ω = 1/(2π(1 − cos θ_h))), weight I(θ)/p_ω. A radius is treated as
    // the point light's (soft_radius; see PointLight::sample_emission).
    bool sample_emission(Vec2 u_position, Vec2 u_direction, Vec3 center, float radius,
                         EmissionSample* out) const override;

private:
    Vec3 position_;
    Vec3 axis_;  // unit, direction of emission (local −Z)
    Rgb power_;
    Rgb intensity_;  // on the axis, W/sr
    float radius_;
    float cos_half_;  // cos θ_h
    float smooth_;    // (1 − cos θ_h) b: width of the blend band in cos θ
    bool cosine_falloff_;
};

// STRATUM_LIGHT_SPOT (Cycles 4.x/5.x) and STRATUM_LIGHT_SPOT_V1 (Cycles 3.x: cosine_falloff): transform,
// power = color × strength, radius, spot_size, spot_blend; both check spot_size in (0, π] and
// spot_blend in [0, 1].
extern const LightModel kSpotLightModel, kSpotV1LightModel;

}  // namespace stratum
