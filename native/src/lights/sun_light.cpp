#include "lights/sun_light.h"

#include "sampling/warps.h"

namespace stratum {

SunLight::SunLight(Vec3 toward_sun, Rgb irradiance, float angle)
    : frame_(Frame::from_normal(toward_sun)), irradiance_(irradiance), cos_max_(1.0f), pdf_(1.0f) {
    const float half = 0.5f * angle;
    if (half > 0.0f) {
        const float s = std::sin(half);
        cos_max_ = std::cos(half);
        radiance_ = saturating_product(irradiance, 1.0 / (kPi * static_cast<double>(s) * s));
        pdf_ = 1.0f / (2.0f * kPi * (s * s / (1.0f + cos_max_)));
    }
}

bool SunLight::sample(Vec3 /*p*/, Vec3 /*n*/, Vec2 u, TriangleSampling /*triangle_sampling*/,
                      LightSample* out) const {
    if (cos_max_ >= 1.0f) {
        *out = {frame_.n, kInfinity, irradiance_, 1.0f, false};
        return true;
    }
    *out = {frame_.to_world(sample_uniform_cone(u, cos_max_)), kInfinity, radiance_, pdf_, false};
    return true;
}

bool SunLight::sample_emission(Vec2 u_position, Vec2 u_direction, Vec3 center, float radius,
                               EmissionSample* out) const {
    if (cos_max_ < 0.1f) return false;
    const float sin_max = safe_sqrt(1.0f - cos_max_ * cos_max_);
    const float disk_radius = radius * (1.0f + sin_max) / cos_max_;
    const float disk_area = kPi * disk_radius * disk_radius;
    const Vec2 d = sample_uniform_disk_concentric(u_position);
    out->position = center + frame_.n * radius + (frame_.s * d.x + frame_.t * d.y) * disk_radius;
    out->normal = frame_.n;
    out->soft_radius = 0.0f;
    if (cos_max_ >= 1.0f) {
        out->direction = -frame_.n;
        out->weight = irradiance_ * disk_area;
        return true;
    }
    const Vec3 local = sample_uniform_cone(u_direction, cos_max_);
    out->direction = -frame_.to_world(local);
    out->weight = radiance_ * (local.z * disk_area / pdf_);
    return true;
}

namespace {

std::unique_ptr<Light> make_sun_light(const LightParams& params) {
    return std::make_unique<SunLight>(normalize(params.light_to_world.vector(Vec3(0, 0, 1))),
                                      params.color * params.strength, params.angle);
}

}  // namespace

const LightModel kSunLightModel{&make_sun_light, nullptr};

}  // namespace stratum
