#include "lights/point_light.h"

#include "sampling/warps.h"

namespace stratum {

bool sample_facing_disk(Vec3 center, float radius, Vec3 p, Vec2 u, FacingDiskSample* out) {
    const Vec3 to_center = center - p;
    const float d = length(to_center);
    if (!(d > 0.0f)) return false;
    const Frame frame = Frame::from_normal(to_center / d);
    const Vec2 disk = sample_uniform_disk_concentric(u);
    const Vec3 to = to_center + (frame.s * disk.x + frame.t * disk.y) * radius;
    const float dist = length(to);
    const Vec3 wi = to / dist;
    // The disk's normal is −axis (toward p); the ray meets it at cos θ_l = wi·axis = d/dist.
    const float cos_light = d / dist;
    out->wi = wi;
    out->distance = dist;
    out->pdf = dist * dist / (kPi * radius * radius * cos_light);
    return true;
}

bool intersect_facing_disk(Vec3 center, float radius, Vec3 origin, Vec3 dir, float t_max, float* t,
                           float* pdf) {
    const Vec3 to_center = center - origin;
    const float d = length(to_center);
    if (!(d > 0.0f)) return false;
    const Vec3 axis = to_center / d;  // the disk's normal is −axis
    const float cos_light = dot(dir, axis);
    if (!(cos_light > 0.0f)) return false;  // moving away from the disk's plane
    const float hit_t = d / cos_light;
    if (!(hit_t < t_max)) return false;
    const Vec3 offset = origin + dir * hit_t - center;
    if (dot(offset, offset) > radius * radius) return false;
    *t = hit_t;
    *pdf = hit_t * hit_t / (kPi * radius * radius * cos_light);
    return true;
}

PointLight::PointLight(Vec3 position, Rgb power, float radius)
    : position_(position),
      power_(power),
      intensity_(power * kInv4Pi),
      disk_radiance_(saturating_product(intensity_, 1.0 / (kPi * static_cast<double>(radius) * radius))),
      radius_(radius) {}

bool PointLight::sample(Vec3 p, Vec3 /*n*/, Vec2 u, TriangleSampling /*triangle_sampling*/,
                        LightSample* out) const {
    if (radius_ <= 0.0f) {
        const Vec3 to_center = position_ - p;
        const float d2 = dot(to_center, to_center);
        const float d = std::sqrt(d2);
        if (!(d > 0.0f)) return false;
        *out = {to_center / d, d, intensity_ / d2, 1.0f, false};
        return true;
    }
    FacingDiskSample s;
    if (!sample_facing_disk(position_, radius_, p, u, &s)) return false;
    *out = {s.wi, s.distance, disk_radiance_, s.pdf, true};
    return true;
}

bool PointLight::intersect(Vec3 origin, Vec3 dir, float t_max, float* t, Rgb* radiance, float* pdf) const {
    if (radius_ <= 0.0f) return false;
    if (!intersect_facing_disk(position_, radius_, origin, dir, t_max, t, pdf)) return false;
    *radiance = disk_radiance_;
    return true;
}

bool PointLight::sample_emission(Vec2 /*u_position*/, Vec2 u_direction, Vec3 /*center*/, float /*radius*/,
                                 EmissionSample* out) const {
    out->position = position_;
    out->direction = sample_uniform_sphere(u_direction);
    out->normal = Vec3(0.0f, 0.0f, 0.0f);
    out->weight = intensity_ * (1.0f / uniform_sphere_pdf());
    out->soft_radius = radius_;
    return true;
}

namespace {

std::unique_ptr<Light> make_point_light(const LightParams& params) {
    return std::make_unique<PointLight>(params.light_to_world.translation(), params.color * params.strength,
                                        params.radius);
}

}  // namespace

const LightModel kPointLightModel{&make_point_light, nullptr};

}  // namespace stratum
