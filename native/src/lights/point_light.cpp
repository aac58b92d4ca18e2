#include "lights/point_light.h"

#include "sampling/warps.h"

namespace stratum {

PointLight::PointLight(Vec3 position, Rgb power, float radius)
    : position_(position), power_(power), intensity_(power * kInv4Pi), radius_(radius) {}

bool PointLight::sample(Vec3 p, Vec2 u, LightSample* out) const {
    const Vec3 to_center = position_ - p;
    const float d2 = dot(to_center, to_center);
    const float d = std::sqrt(d2);
    if (!(d > 0.0f)) return false;
    const Vec3 axis = to_center / d;
    if (radius_ <= 0.0f) {
        *out = {axis, d, intensity_ / d2, 1.0f, false};
        return true;
    }
    if (d <= radius_) return false;  // inside the emitter: it emits outward only
    const float sin2_max = sqr(radius_) / d2;
    // 1 − cos θmax computed as sin²/(1 + cos) to avoid cancellation for small, far spheres.
    const float cos_max = safe_sqrt(1.0f - sin2_max);
    const float one_minus_cos = sin2_max / (1.0f + cos_max);
    const Vec3 local = sample_uniform_cone(u, cos_max);
    const Vec3 wi = Frame::from_normal(axis).to_world(local);
    // Distance to the near side of the sphere along wi.
    const float b = dot(wi, to_center);
    const float t = b - safe_sqrt(b * b - (d2 - sqr(radius_)));
    const Rgb radiance = intensity_ / (kPi * sqr(radius_));
    *out = {wi, t, radiance, 1.0f / (2.0f * kPi * one_minus_cos), false};
    return true;
}

}  // namespace stratum
