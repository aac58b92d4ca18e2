#include "lights/area_light.h"

#include <cmath>

#include "lights/light_param_checks.h"
#include "sampling/warps.h"
#include "scene/scene_limits.h"

namespace stratum {

float area_light_spread_attenuation(float cos_a, float tan_half, float normalize) {
    if (std::isinf(tan_half)) return 1.0f;
    if (!(cos_a > 0.0f)) return 0.0f;
    const float tan_a = safe_sqrt(1.0f - cos_a * cos_a) / cos_a;
    return std::max((tan_half - tan_a) * normalize, 0.0f);
}

AreaLight::AreaLight(const Transform& light_to_world, float size_x, float size_y, bool ellipse, Rgb power,
                     float spread)
    : center_(light_to_world.translation()),
      axis_x_(light_to_world.vector(Vec3(0.5f * size_x, 0, 0))),
      axis_y_(light_to_world.vector(Vec3(0, 0.5f * size_y, 0))),
      ellipse_(ellipse),
      power_(power) {
    const Vec3 c = cross(axis_x_, axis_y_);
    const float parallelogram = 4.0f * length(c);
    area_ = ellipse ? parallelogram * (kPi / 4.0f) : parallelogram;
    // Local −Z; in world the normal follows the handedness of the transform.
    normal_ = normalize(light_to_world.normal(Vec3(0, 0, -1)));
    radiance_ = saturating_product(power, 1.0 / (kPi * static_cast<double>(area_)));
    const float half = 0.5f * spread;
    if (spread >= kPi) {
        tan_half_spread_ = kInfinity;
        normalize_spread_ = 1.0f;
        sin_half_spread_ = 1.0f;
    } else {
        tan_half_spread_ = std::tan(half);
        sin_half_spread_ = std::sin(half);
        normalize_spread_ = half > 0.05f ? 1.0f / (tan_half_spread_ - half) : 3.0f / (half * half * half);
    }
}

Vec3 AreaLight::point(Vec2 u) const {
    float a, b;
    if (ellipse_) {
        const Vec2 d = sample_uniform_disk_concentric(u);
        a = d.x;
        b = d.y;
    } else {
        a = 2.0f * u.x - 1.0f;
        b = 2.0f * u.y - 1.0f;
    }
    return center_ + axis_x_ * a + axis_y_ * b;
}

bool AreaLight::sample(Vec3 p, Vec3 /*n*/, Vec2 u, TriangleSampling /*triangle_sampling*/,
                       LightSample* out) const {
    const Vec3 to = point(u) - p;
    const float d2 = dot(to, to);
    const float d = std::sqrt(d2);
    if (!(d > 0.0f)) return false;
    const Vec3 wi = to / d;
    const float cos_light = -dot(wi, normal_);
    if (cos_light <= 0.0f) return false;  // the back side does not emit
    const float f = area_light_spread_attenuation(cos_light, tan_half_spread_, normalize_spread_);
    if (!(f > 0.0f)) return false;
    *out = {wi, d, radiance_ * f, d2 / (area_ * cos_light), true};
    return true;
}

bool AreaLight::intersect(Vec3 origin, Vec3 dir, float t_max, float* t, Rgb* radiance, float* pdf) const {
    const float cos_light = -dot(dir, normal_);
    if (!(cos_light > 0.0f)) return false;  // parallel, or seen from the back
    const float hit_t = dot(center_ - origin, normal_) / -cos_light;
    if (!(hit_t > 0.0f && hit_t < t_max)) return false;
    // Coordinates along the half axes (orthogonal for a light transform without shear).
    const Vec3 q = origin + dir * hit_t - center_;
    const float a = dot(q, axis_x_) / dot(axis_x_, axis_x_), b = dot(q, axis_y_) / dot(axis_y_, axis_y_);
    const bool inside = ellipse_ ? a * a + b * b <= 1.0f : std::abs(a) <= 1.0f && std::abs(b) <= 1.0f;
    if (!inside) return false;
    *t = hit_t;
    *pdf = hit_t * hit_t / (area_ * cos_light);  // sample()'s solid-angle pdf of this direction
    *radiance = radiance_ * area_light_spread_attenuation(cos_light, tan_half_spread_, normalize_spread_);
    return true;
}

bool AreaLight::sample_emission(Vec2 u_position, Vec2 u_direction, Vec3 /*center*/, float /*radius*/,
                                EmissionSample* out) const {
    const Vec2 unit = sample_uniform_disk_concentric(u_direction);
    const Vec2 d{unit.x * sin_half_spread_, unit.y * sin_half_spread_};
    const float cos_theta = safe_sqrt(1.0f - d.x * d.x - d.y * d.y);
    const Frame frame = Frame::from_normal(normal_);
    out->position = point(u_position);
    out->direction = frame.to_world(Vec3(d.x, d.y, cos_theta));
    out->normal = normal_;
    out->soft_radius = 0.0f;
    const float f = area_light_spread_attenuation(cos_theta, tan_half_spread_, normalize_spread_);
    out->weight = radiance_ * (f * kPi * sin_half_spread_ * sin_half_spread_ * area_);
    return true;
}

std::optional<LightBounds> AreaLight::bounds() const {
    LightBounds b;
    b.lo = b.hi = center_ - axis_x_ - axis_y_;
    for (const Vec3 corner :
         {center_ + axis_x_ - axis_y_, center_ - axis_x_ + axis_y_, center_ + axis_x_ + axis_y_}) {
        b.lo = component_min(b.lo, corner);
        b.hi = component_max(b.hi, corner);
    }
    b.axis = normal_;
    b.theta_o = 0.0f;
    // f(a) > 0 only for tan a < tan h; tan h = ∞ without spread (h = π/2). Padded for rounding
    // at grazing angles, where the contribution is 0 anyway.
    const double half =
        std::isinf(tan_half_spread_) ? 0.5 * kPi : std::atan(static_cast<double>(tan_half_spread_));
    b.theta_e = static_cast<float>(half + LightBounds::kConePadding);
    return b;
}

namespace {

void check_area_light_params(const LightParams& given, LightParams* params) {
    params->size_x = light_param_in_open(given.size_x, 0.0f, kMaxCoordinate, "area light size_x");
    params->size_y = light_param_in_open(given.size_y, 0.0f, kMaxCoordinate, "area light size_y");
    require_light_param(std::isfinite(given.spread) && given.spread >= 0.0f && given.spread <= kPi,
                        "area light spread = " + light_param_text(given.spread) + " must be in (0, " +
                            light_param_text(kPi) + "] (0 reads as pi)");
    params->spread = given.spread == 0.0f ? kPi : given.spread;
}

template <bool ellipse>
std::unique_ptr<Light> make_area_light(const LightParams& params) {
    return std::make_unique<AreaLight>(params.light_to_world, params.size_x, params.size_y, ellipse,
                                       params.color * params.strength, params.spread);
}

}  // namespace

const LightModel kRectangleAreaLightModel{&make_area_light<false>, &check_area_light_params};
const LightModel kEllipseAreaLightModel{&make_area_light<true>, &check_area_light_params};

}  // namespace stratum
