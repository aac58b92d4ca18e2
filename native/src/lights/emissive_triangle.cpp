#include "lights/emissive_triangle.h"

#include "sampling/warps.h"

namespace stratum {

EmissiveTriangle::EmissiveTriangle(Vec3 p0, Vec3 p1, Vec3 p2, Rgb radiance)
    : p0_(p0), e1_(p1 - p0), e2_(p2 - p0), radiance_(radiance) {
    const Vec3 c = cross(e1_, e2_);
    const float twice_area = length(c);
    area_ = 0.5f * twice_area;
    normal_ = twice_area > 0.0f ? c / twice_area : Vec3(0, 0, 1);
}

bool EmissiveTriangle::sample(Vec3 p, Vec2 u, LightSample* out) const {
    if (!(area_ > 0.0f)) return false;
    const Vec3 b = sample_uniform_triangle(u);
    const Vec3 q = p0_ + e1_ * b.y + e2_ * b.z;
    const Vec3 to = q - p;
    const float d2 = dot(to, to);
    const float d = std::sqrt(d2);
    if (!(d > 0.0f)) return false;
    const Vec3 wi = to / d;
    const float cos_light = std::abs(dot(wi, normal_));
    if (cos_light <= 0.0f) return false;
    *out = {wi, d, radiance_, d2 / (area_ * cos_light), true};
    return true;
}

float EmissiveTriangle::pdf(Vec3 p, Vec3 hit) const {
    const Vec3 to = hit - p;
    const float d2 = dot(to, to);
    const float cos_light = std::abs(dot(to, normal_)) / std::sqrt(d2);
    if (!(cos_light > 0.0f) || !(area_ > 0.0f)) return 0.0f;
    return d2 / (area_ * cos_light);
}

bool EmissiveTriangle::sample_emission(Vec2 u_position, Vec2 u_direction, EmissionSample* out) const {
    if (!(area_ > 0.0f)) return false;
    const Vec3 b = sample_uniform_triangle(u_position);
    const bool front = u_direction.x < 0.5f;
    const float u_side = front ? 2.0f * u_direction.x : 2.0f * u_direction.x - 1.0f;
    const Vec3 n = front ? normal_ : -normal_;
    out->position = p0_ + e1_ * b.y + e2_ * b.z;
    out->direction = Frame::from_normal(n).to_world(
        sample_cosine_hemisphere({std::min(u_side, kOneMinusEpsilon), u_direction.y}));
    out->normal = n;
    out->weight = radiance_ * (2.0f * kPi * area_);
    out->soft_radius = 0.0f;
    return true;
}

}  // namespace stratum
