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
#include "lights/light_sample.h"

namespace stratum {

class SunLight {
public:
    // toward_sun: unit direction from the scene to the sun.
    SunLight(Vec3 toward_sun, Rgb irradiance, float angle);
    bool sample(Vec2 u, LightSample* out) const;
    Rgb irradiance() const { return irradiance_; }
    // Angle 0: a single direction, which no scattered ray finds.
    bool is_delta() const { return cos_max_ >= 1.0f; }

private:
    Frame frame_;
    Rgb irradiance_;
    Rgb radiance_;
    float cos_max_;
    float pdf_;
};

}  // namespace stratum
