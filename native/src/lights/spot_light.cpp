#include "lights/spot_light.h"

#include "sampling/warps.h"

namespace stratum {

SpotLight::SpotLight(const Transform& light_to_world, Rgb power, float radius, float spot_size,
                     float spot_blend, bool cosine_falloff)
    : position_(light_to_world.translation()),
      axis_(normalize(light_to_world.vector(Vec3(0, 0, -1)))),
      power_(power),
      intensity_(power * kInv4Pi),
      radius_(radius),
      cos_half_(std::cos(0.5f * spot_size)),
      smooth_((1.0f - std::cos(0.5f * spot_size)) * spot_blend),
      cosine_falloff_(cosine_falloff) {}

float SpotLight::attenuation(float cos_theta) const {
    if (!(cos_theta > cos_half_)) return 0.0f;
    const float t = cos_theta - cos_half_;
    float s = 1.0f;
    if (smooth_ > 0.0f && t < smooth_) {
        const float x = t / smooth_;
        s = x * x * (3.0f - 2.0f * x);
    }
    return cosine_falloff_ ? s * cos_theta : s;
}

bool SpotLight::sample(Vec3 p, Vec2 u, LightSample* out) const {
    const Vec3 to_center = position_ - p;
    const float d2 = dot(to_center, to_center);
    const float d = std::sqrt(d2);
    if (!(d > 0.0f)) return false;
    const Vec3 axis = to_center / d;
    if (radius_ <= 0.0f) {
        const float a = attenuation(-dot(axis, axis_));
        if (!(a > 0.0f)) return false;
        *out = {axis, d, intensity_ * (a / d2), 1.0f, false};
        return true;
    }
    if (d <= radius_) return false;  // inside the emitter: it emits outward only
    const float sin2_max = sqr(radius_) / d2;
    const float cos_max = safe_sqrt(1.0f - sin2_max);
    const float one_minus_cos = sin2_max / (1.0f + cos_max);
    const Vec3 wi = Frame::from_normal(axis).to_world(sample_uniform_cone(u, cos_max));
    const float a = attenuation(-dot(wi, axis_));
    if (!(a > 0.0f)) return false;
    const float b = dot(wi, to_center);
    const float t = b - safe_sqrt(b * b - (d2 - sqr(radius_)));
    const Rgb radiance = intensity_ * (a / (kPi * sqr(radius_)));
    *out = {wi, t, radiance, 1.0f / (2.0f * kPi * one_minus_cos), false};
    return true;
}

}  // namespace stratum
