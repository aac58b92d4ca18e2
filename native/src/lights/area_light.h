// Blender area light: a one-sided planar emitter (square, rectangle, disk or ellipse) facing
// its local −Z axis.
//
// | parameter        | meaning |
// |------------------|---------|
// | power P          | "Power" in W times colour |
// | size_x, size_y   | "Size" / "Size Y": side lengths, or diameters of disk and ellipse |
// | shape            | rectangle (square is equal sides) or ellipse (disk is equal diameters) |
//
// Radiance L = P / (π A), A the world-space area: a Lambertian emitter whose flux is P. This is
// Cycles 4.x/5.x; Cycles 3.x used P / (4 A) (docs/cycles_models.md), and the add-on scales the
// power of a 3.x scene by π/4 so both Blenders render what their Cycles renders.
// Points are sampled uniformly in area (textbook 4.37 for the rectangle, concentric polar map
// for the ellipse, 4.41), converted to solid angle: pdf = r² / (A |cos θ_light|).
#pragma once

#include "core/math.h"
#include "lights/light_sample.h"

namespace stratum {

class AreaLight {
public:
    // light_to_world maps the unit shape (x, y in [−½, ½]·size) into the world.
    AreaLight(const Transform& light_to_world, float size_x, float size_y, bool ellipse, Rgb power);
    bool sample(Vec3 p, Vec2 u, LightSample* out) const;
    float power() const { return power_.average(); }

private:
    Vec3 center_, axis_x_, axis_y_;  // half extents along the local axes, in world units
    Vec3 normal_;                    // emitting side
    bool ellipse_;
    float area_;
    Rgb power_;
    Rgb radiance_;
};

}  // namespace stratum
