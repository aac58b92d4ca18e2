#include "lights/emissive_triangle.h"

#include <algorithm>
#include <cmath>

namespace stratum {

EmissiveTriangle::EmissiveTriangle(Vec3 p0, Vec3 p1, Vec3 p2, Rgb radiance)
    : p0_(p0), e1_(p1 - p0), e2_(p2 - p0), radiance_(radiance) {
    const Vec3 c = cross(e1_, e2_);
    const float twice_area = length(c);
    area_ = 0.5f * twice_area;
    normal_ = twice_area > 0.0f ? c / twice_area : Vec3(0, 0, 1);
    float magnitude = 0.0f;
    for (Vec3 v : {p0, p1, p2})
        magnitude = std::max({magnitude, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    coplanar_distance_ = kCoplanarTolerance * magnitude;
    const float longest_edge2 = std::max({dot(e1_, e1_), dot(e2_, e2_), dot(p2 - p1, p2 - p1)});
    spherical_distance2_ = kSphericalDistanceRatio * kSphericalDistanceRatio * longest_edge2;
}

BilinearWeights EmissiveTriangle::cosine_weights(const SphericalTriangle& spherical, Vec3 n) const {
    if (dot(n, n) == 0.0f) return {{1.0f, 1.0f, 1.0f, 1.0f}};
    const auto weight = [&](int vertex) {
        return std::max(kMinCosineWeight, std::abs(dot(spherical.direction(vertex), n)));
    };
    const float w0 = weight(0), w1 = weight(1), w2 = weight(2);
    return {{w1, w1, w0, w2}};
}

std::optional<SphericalTriangle> EmissiveTriangle::spherical_view(Vec3 p) const {
    const float plane_distance = std::abs(dot(p - p0_, normal_));
    if (!(plane_distance > coplanar_distance_)) return std::nullopt;
    if (!(plane_distance * plane_distance < spherical_distance2_)) return std::nullopt;
    SphericalTriangle spherical(p, p0_, p0_ + e1_, p0_ + e2_);
    if (spherical.solid_angle() < kMinSphericalSolidAngle) return std::nullopt;
    return spherical;
}

bool EmissiveTriangle::sample(Vec3 p, Vec3 n, Vec2 u, TriangleSampling mode, LightSample* out) const {
    if (mode == TriangleSampling::Area) return sample_area(p, u, out);
    const std::optional<SphericalTriangle> spherical = spherical_view(p);
    if (!spherical) return sample_area(p, u, out);
    const BilinearWeights weights = cosine_weights(*spherical, n);
    const Vec2 warped = sample_bilinear(u, weights);
    const Vec3 wi = spherical->sample(warped);
    // The light point is where wi meets the triangle's plane.
    const float distance = dot(p0_ - p, normal_) / dot(wi, normal_);
    if (!(distance > 0.0f) || !std::isfinite(distance)) return false;
    const float pdf = bilinear_pdf(warped, weights) / static_cast<float>(spherical->solid_angle());
    *out = {wi, distance, radiance_, pdf, true};
    return true;
}

float EmissiveTriangle::pdf(Vec3 p, Vec3 n, Vec3 hit, TriangleSampling mode) const {
    if (mode == TriangleSampling::Area) return pdf_area(p, hit);
    const std::optional<SphericalTriangle> spherical = spherical_view(p);
    if (!spherical) return pdf_area(p, hit);
    const Vec2 u = spherical->invert(normalize(hit - p));
    return bilinear_pdf(u, cosine_weights(*spherical, n)) / static_cast<float>(spherical->solid_angle());
}

bool EmissiveTriangle::sample_area(Vec3 p, Vec2 u, LightSample* out) const {
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

float EmissiveTriangle::pdf_area(Vec3 p, Vec3 hit) const {
    const Vec3 to = hit - p;
    const float d2 = dot(to, to);
    const float cos_light = std::abs(dot(to, normal_)) / std::sqrt(d2);
    if (!(cos_light > 0.0f) || !(area_ > 0.0f)) return 0.0f;
    return d2 / (area_ * cos_light);
}

bool EmissiveTriangle::sample_emission(Vec2 u_position, Vec2 u_direction, Vec3 /*center*/, float /*radius*/,
                                       EmissionSample* out) const {
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

std::optional<LightBounds> EmissiveTriangle::bounds() const {
    LightBounds b;
    b.lo = component_min(p0_, component_min(p0_ + e1_, p0_ + e2_));
    b.hi = component_max(p0_, component_max(p0_ + e1_, p0_ + e2_));
    b.axis = normal_;
    b.theta_o = 0.0f;
    b.theta_e = static_cast<float>(0.5 * kPi + LightBounds::kConePadding);
    b.two_sided = true;
    return b;
}

}  // namespace stratum
