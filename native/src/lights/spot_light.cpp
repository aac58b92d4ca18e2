#include "lights/spot_light.h"

#include <algorithm>
#include <cmath>

#include "lights/light_param_checks.h"
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

bool SpotLight::sample(Vec3 p, Vec3 /*n*/, Vec2 u, TriangleSampling /*triangle_sampling*/,
                       LightSample* out) const {
    if (radius_ <= 0.0f) {
        const Vec3 to_center = position_ - p;
        const float d2 = dot(to_center, to_center);
        const float d = std::sqrt(d2);
        if (!(d > 0.0f)) return false;
        const Vec3 wi = to_center / d;
        const float a = attenuation(-dot(wi, axis_));
        if (!(a > 0.0f)) return false;
        *out = {wi, d, intensity_ * (a / d2), 1.0f, false};
        return true;
    }
    FacingDiskSample s;
    if (!sample_facing_disk(position_, radius_, p, u, &s)) return false;
    const float a = attenuation(-dot(s.wi, axis_));
    if (!(a > 0.0f)) return false;
    *out = {s.wi, s.distance, disk_radiance(a), s.pdf, true};
    return true;
}

bool SpotLight::intersect(Vec3 origin, Vec3 dir, float t_max, float* t, Rgb* radiance, float* pdf) const {
    if (radius_ <= 0.0f) return false;
    const float a = attenuation(-dot(dir, axis_));
    if (!(a > 0.0f)) return false;
    if (!intersect_facing_disk(position_, radius_, origin, dir, t_max, t, pdf)) return false;
    *radiance = disk_radiance(a);
    return true;
}

bool SpotLight::sample_emission(Vec2 /*u_position*/, Vec2 u_direction, Vec3 /*center*/, float /*radius*/,
                                EmissionSample* out) const {
    const Frame frame = Frame::from_normal(axis_);
    const Vec3 local = sample_uniform_cone(u_direction, cos_half_);
    out->position = position_;
    out->direction = frame.to_world(local);
    out->normal = Vec3(0.0f, 0.0f, 0.0f);
    // 1/p_ω written out: the pdf helper returns 0 at the rim by rounding, where I(θ) is 0 anyway.
    out->weight = intensity_ * (attenuation(local.z) * 2.0f * kPi * (1.0f - cos_half_));
    out->soft_radius = radius_;
    return true;
}

std::optional<LightBounds> SpotLight::bounds() const {
    LightBounds b = omnidirectional_bounds(position_, radius_, 0.0);
    b.axis = axis_;
    // attenuation() is 1 from cos θ ≥ cos θ_h + smooth on, 0 from cos θ ≤ cos θ_h on; the
    // padding covers float rounding at the hard edge of a spot without blend.
    const double theta_h = std::acos(static_cast<double>(cos_half_));
    const double theta_o = std::acos(std::min(1.0, static_cast<double>(cos_half_) + smooth_));
    b.theta_o = static_cast<float>(theta_o);
    b.theta_e =
        static_cast<float>(std::min(static_cast<double>(kPi), theta_h - theta_o + LightBounds::kConePadding));
    return b;
}

namespace {

void check_spot_light_params(const LightParams& given, LightParams* params) {
    params->spot_size = light_param_in_open(given.spot_size, 0.0f, kPi, "spot light spot_size");
    params->spot_blend = light_param_in(given.spot_blend, 0.0f, 1.0f, "spot light spot_blend");
}

template <bool cosine_falloff>
std::unique_ptr<Light> make_spot_light(const LightParams& params) {
    return std::make_unique<SpotLight>(params.light_to_world, params.color * params.strength, params.radius,
                                       params.spot_size, params.spot_blend, cosine_falloff);
}

}  // namespace

const LightModel kSpotLightModel{&make_spot_light<false>, &check_spot_light_params};
const LightModel kSpotV1LightModel{&make_spot_light<true>, &check_spot_light_params};

}  // namespace stratum
