#include "lights/sun_light.h"

#include "sampling/warps.h"

namespace stratum {

SunLight::SunLight(Vec3 toward_sun, Rgb irradiance, float angle)
    : frame_(Frame::from_normal(toward_sun)), irradiance_(irradiance), cos_max_(1.0f), pdf_(1.0f) {
    const float half = 0.5f * angle;
    if (half > 0.0f) {
        const float s = std::sin(half);
        cos_max_ = std::cos(half);
        radiance_ = irradiance / (kPi * s * s);
        pdf_ = 1.0f / (2.0f * kPi * (s * s / (1.0f + cos_max_)));
    }
}

bool SunLight::sample(Vec2 u, LightSample* out) const {
    if (cos_max_ >= 1.0f) {
        *out = {frame_.n, kInfinity, irradiance_, 1.0f, false};
        return true;
    }
    *out = {frame_.to_world(sample_uniform_cone(u, cos_max_)), kInfinity, radiance_, pdf_, false};
    return true;
}

}  // namespace stratum
