// Blender sun light: a distant disk of directions (Cycles "distant" light).
//
// | parameter   | meaning |
// |-------------|---------|
// | strength E  | "Strength": irradiance in W/m² on a surface facing the sun, times colour |
// | angle α     | "Angle": angular diameter; the sun fills a cone of half-angle α/2 |
//
// Directions are sampled uniformly in the cone (pdf 1 / (2π(1 − cos(α/2)))); the radiance
// E / (π sin²(α/2)) makes the irradiance of the full cone at normal incidence equal E.
// α = 0 is the textbook parallel source (textbook 5.13), a delta direction.
#pragma once

#include "core/math.h"
#include "lights/light.h"

namespace stratum {

class SunLight final : public Light {
public:
    // toward_sun: unit direction from the scene to the sun.
    SunLight(Vec3 toward_sun, Rgb irradiance, float angle);
    // Angle 0: a single direction, which no scattered ray finds.
    bool is_delta() const override { return cos_max_ >= 1.0f; }
    bool is_hittable_lamp() const override { return false; }
    // The flux through the scene's cross-section, π R² E.
    double power(float scene_radius) const override {
        return mean(irradiance_) * kPi * scene_radius * scene_radius;
    }
    bool sample(Vec3 p, Vec3 n, Vec2 u, TriangleSampling triangle_sampling, LightSample* out) const override;
    // A light-tracing particle (textbook 6.5): a parallel beam over a disk that covers the
    // scene's bounding sphere (center, radius R) seen from any direction of the sun's cone: the
    // disk is tangent to the sphere on the sun's side, radius R(1 + sin α/2)/cos α/2 (the
    // sphere's oblique shadow on that plane), point uniform on it (p_A = 1/A). The direction
    // toward the sun is uniform in the cone (p_ω as sample()), weight L cos/(p_A p_ω); angle 0
    // gives E·A. False when the cone is too wide for a covering disk (α/2 > 84°).
    bool sample_emission(Vec2 u_position, Vec2 u_direction, Vec3 center, float radius,
                         EmissionSample* out) const override;

private:
    Frame frame_;
    Rgb irradiance_;
    Rgb radiance_;
    float cos_max_;
    float pdf_;
};

// STRATUM_LIGHT_SUN: direction = the transform's +Z, irradiance = color × strength, angle.
extern const LightModel kSunLightModel;

}  // namespace stratum
