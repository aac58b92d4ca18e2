#include "sampling/spherical_triangle.h"

#include <algorithm>
#include <cmath>

namespace stratum {

namespace {

using Dir = SphericalTriangle::Dir;

Dir operator+(Dir a, Dir b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Dir operator-(Dir a, Dir b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Dir operator*(Dir a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(Dir a, Dir b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Dir cross(Dir a, Dir b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double length(Dir a) { return std::sqrt(dot(a, a)); }

// Unit vector along a, or false for a zero vector.
bool unit(Dir a, Dir* out) {
    const double l = length(a);
    if (!(l > 0.0)) return false;
    *out = a * (1.0 / l);
    return true;
}

Dir difference(Vec3 v, Vec3 p) {
    return {double(v.x) - double(p.x), double(v.y) - double(p.y), double(v.z) - double(p.z)};
}

// The component of v orthogonal to the unit vector n, normalised; false when v is along n.
bool orthogonal_unit(Dir v, Dir n, Dir* out) { return unit(v - n * dot(v, n), out); }

// Van Oosterom & Strackee for unit a, b, c; atan2 keeps Ω > π (a negative denominator) and small
// Ω (no 1 − cos cancellation) exact.
double solid_angle_of(Dir a, Dir b, Dir c) {
    const double triple = std::abs(dot(a, cross(b, c)));
    return 2.0 * std::atan2(triple, 1.0 + dot(a, b) + dot(b, c) + dot(c, a));
}

}  // namespace

SphericalTriangle::SphericalTriangle(Vec3 p, Vec3 v0, Vec3 v1, Vec3 v2) {
    if (!unit(difference(v0, p), &a_) || !unit(difference(v1, p), &b_) || !unit(difference(v2, p), &c_))
        return;
    solid_angle_ = solid_angle_of(a_, b_, c_);
    // The angle at a between the great circles toward b and toward c: the angle between the
    // tangents of the two arcs at a, by atan2(|t_b × t_c|, t_b · t_c) (accurate at any size).
    const Dir tb = b_ - a_ * dot(a_, b_), tc = c_ - a_ * dot(a_, c_);
    alpha_ = std::atan2(length(cross(tb, tc)), dot(tb, tc));
    if (!(solid_angle_ > 0.0) || !(alpha_ > 0.0)) solid_angle_ = 0.0;
}

Vec3 SphericalTriangle::sample(Vec2 u) const {
    // Arvo's construction: the point ĉ on arc a→c such that the sub-triangle (a, b, ĉ) has area
    // Â = u₁Ω. With s, t = sin, cos(Â − α) and cos c = a·b (c the side opposite vertex c), the
    // spherical law of cosines gives q = cos |aĉ|:
    //     q = ((v t − w s) cos α − v) / ((v s + w t) sin α),  w = t − cos α,  v = s + sin α cos c.
    const double area = double(u.x) * solid_angle_;
    const double s = std::sin(area - alpha_), t = std::cos(area - alpha_);
    const double cos_alpha = std::cos(alpha_), sin_alpha = std::sin(alpha_);
    const double w = t - cos_alpha;
    const double v = s + sin_alpha * dot(a_, b_);
    const double denominator = (v * s + w * t) * sin_alpha;
    const double q =
        denominator != 0.0 ? std::clamp(((v * t - w * s) * cos_alpha - v) / denominator, -1.0, 1.0) : 1.0;
    Dir toward_c;
    if (!orthogonal_unit(c_, a_, &toward_c)) toward_c = c_;
    const Dir c_hat = a_ * q + toward_c * std::sqrt(std::max(0.0, 1.0 - q * q));
    // Given ĉ, Arvo takes the point on the arc b→ĉ whose cosine to b is uniform in [b·ĉ, 1].
    const double z = 1.0 - double(u.y) * (1.0 - dot(c_hat, b_));
    Dir toward_c_hat;
    if (!orthogonal_unit(c_hat, b_, &toward_c_hat)) return {float(b_.x), float(b_.y), float(b_.z)};
    const Dir d = b_ * z + toward_c_hat * std::sqrt(std::max(0.0, 1.0 - z * z));
    return {float(d.x), float(d.y), float(d.z)};
}

Vec2 SphericalTriangle::invert(Vec3 w_float) const {
    const Dir w{w_float.x, w_float.y, w_float.z};
    // ĉ: where the great circle through b and w meets the arc a→c, on w's side of b.
    Dir c_hat;
    if (!unit(cross(cross(b_, w), cross(a_, c_)), &c_hat)) return {0.0f, 0.0f};
    if (dot(c_hat, a_ + c_) < 0.0) c_hat = c_hat * -1.0;
    const double u1 = solid_angle_of(a_, b_, c_hat) / solid_angle_;
    const double denominator = 1.0 - dot(c_hat, b_);
    const double u2 = denominator > 0.0 ? (1.0 - dot(w, b_)) / denominator : 0.0;
    return {static_cast<float>(std::clamp(u1, 0.0, 1.0)), static_cast<float>(std::clamp(u2, 0.0, 1.0))};
}

}  // namespace stratum
