// Blender point light (Cycles conventions; see docs/cycles_models.md).
//
// | parameter | meaning |
// |-----------|---------|
// | power P   | Blender "Power" in W times colour; radiant intensity I = P / (4π) |
// | radius r  | "Radius": a sphere of radiance I / (π r²), so its irradiance at distance d is I/d² |
//
// r = 0 is the textbook delta point light (textbook 5.11). A sphere is sampled by the uniform
// cone of directions it subtends (pbrt-v4 §12.2.2), solid-angle pdf 1 / (2π(1 − cos θmax)).
#pragma once

#include "core/math.h"
#include "lights/light_sample.h"

namespace stratum {

class PointLight {
public:
    PointLight(Vec3 position, Rgb power, float radius);
    bool sample(Vec3 p, Vec2 u, LightSample* out) const;
    // Emitted power in W, used to choose among lights.
    float power() const { return power_.average(); }

private:
    Vec3 position_;
    Rgb power_;
    Rgb intensity_;  // W/sr
    float radius_;
};

}  // namespace stratum
