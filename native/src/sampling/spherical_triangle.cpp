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

// Unit vector along a, or false for a zero vector.
bool unit(Dir a, Dir* out) {
    const double l2 = dot(a, a);
    if (!(l2 > 0.0)) return false;
    *out = a * (1.0 / std::sqrt(l2));
    return true;
}

Dir difference(Vec3 v, Vec3 p) {
    return {double(v.x) - double(p.x), double(v.y) - double(p.y), double(v.z) - double(p.z)};
}

// 1 − a·b for unit a and b, without the cancellation of 1 − (a·b) for close directions.
double one_minus_cosine(Dir a, Dir b) {
    const Dir d = a - b;
    return 0.5 * dot(d, d);
}

// Van Oosterom & Strackee for unit a, b, c; atan2 keeps Ω > π (a negative denominator) and small
// Ω (no 1 − cos cancellation) exact. The triple product from the differences b − a, c − a:
// a·((b − a)×(c − a)) = a·(b×c) (a·(a×·) = 0), and the differences of close directions are
// exact where b×c of nearly parallel vectors would cancel.
double solid_angle_of(Dir a, Dir b, Dir c) {
    const double triple = std::abs(dot(a, cross(b - a, c - a)));
    const double denominator = 1.0 + dot(a, b) + dot(b, c) + dot(c, a);
    return 2.0 * double(std::atan2(float(triple), float(denominator)));
}

}  // namespace

SphericalTriangle::SphericalTriangle(Vec3 p, Vec3 v0, Vec3 v1, Vec3 v2) {
    if (!unit(difference(v0, p), &a_) || !unit(difference(v1, p), &b_) || !unit(difference(v2, p), &c_))
        return;
    solid_angle_ = solid_angle_of(a_, b_, c_);
    if (!(solid_angle_ > 0.0)) solid_angle_ = 0.0;
}

Vec3 SphericalTriangle::sample(Vec2 u) const {
    // Arvo's construction: the point ĉ on arc a→c such that the sub-triangle (a, b, ĉ) has area
    // Â = u₁Ω. With s, t = sin, cos(Â − α), cos c = a·b (c the side opposite vertex c) and α the
    // angle at a, the spherical law of cosines gives q = cos |aĉ|:
    //     q = ((v t − w s) cos α − v) / ((v s + w t) sin α),  w = t − cos α,  v = s + sin α cos c.
    // Expanding s and t in Â and α, the numerator of 1 − q is sin α (1 − cos Â)(1 + cos c), and
    // the denominator (v s + w t) sin α = sin α ((1 − cos Â) + sin α (1 − cos c) sin(α − Â)):
    //     1 − q = (1 − cos Â)(1 + cos c) / ((1 − cos Â) + sin α (1 − cos c) sin(α − Â)),
    // a ratio of products without cancellation (1 − cos Â = 2 sin²(Â/2)), where q itself is
    // within rounding of 1 for every ĉ near a.
    // sin α and cos α: the normals a×b and a×c of the arcs at a, from the differences (a×b =
    // a×(b − a)); (a×b)×(a×c) = a (a·(b×c)), so with m = |a×b||a×c|, sin α = T/m for the triple
    // product T, and cos α = (a×b)·(a×c)/m. Numerator and denominator are multiplied by m², so
    // that neither m nor α is taken (no square root, no division, no inverse cosine).
    const Dir ab = b_ - a_, ac = c_ - a_;
    const Dir normal_ab = cross(a_, ab), normal_ac = cross(a_, ac);
    const double m2 = dot(normal_ab, normal_ab) * dot(normal_ac, normal_ac);
    const double m_sin_alpha = std::abs(dot(a_, cross(ab, ac))), m_cos_alpha = dot(normal_ab, normal_ac);
    const double one_minus_cos_c = 0.5 * dot(ab, ab);

    const float half_area = static_cast<float>(0.5 * double(u.x) * solid_angle_);
    const double h = double(std::sin(half_area)), k = double(std::cos(half_area));
    const double one_minus_cos_area = 2.0 * h * h, sin_area = 2.0 * h * k;
    // m² sin α sin(α − Â) = m sin α (m sin α cos Â − m cos α sin Â).
    const double m2_sin_alpha_sin_difference =
        m_sin_alpha * (m_sin_alpha * (1.0 - one_minus_cos_area) - m_cos_alpha * sin_area);
    const double denominator = m2 * one_minus_cos_area + one_minus_cos_c * m2_sin_alpha_sin_difference;
    const double one_minus_q =
        denominator > 0.0
            ? std::clamp(m2 * one_minus_cos_area * (2.0 - one_minus_cos_c) / denominator, 0.0, 2.0)
            : 0.0;
    // ĉ = q a + sin|aĉ| t_c, t_c the unit tangent toward c at a: the component of c − a
    // orthogonal to a (exact for close a and c, where c itself would cancel), scaled once.
    const Dir tangent_c = ac - a_ * dot(ac, a_);
    const double tangent_c2 = dot(tangent_c, tangent_c);
    const double sin_q = std::sqrt(one_minus_q * (2.0 - one_minus_q));
    const Dir c_hat =
        tangent_c2 > 0.0 ? a_ * (1.0 - one_minus_q) + tangent_c * (sin_q / std::sqrt(tangent_c2)) : c_;
    // Given ĉ, Arvo takes the point on the arc b→ĉ whose cosine to b is uniform in [b·ĉ, 1]:
    // 1 − z = u₂ (1 − b·ĉ), and the direction z b + √(1 − z²) t, t the unit tangent toward ĉ.
    const Dir b_to_c_hat = c_hat - b_;
    const double one_minus_z = double(u.y) * 0.5 * dot(b_to_c_hat, b_to_c_hat);
    const Dir tangent = b_to_c_hat - b_ * dot(b_to_c_hat, b_);
    const double tangent2 = dot(tangent, tangent);
    if (!(tangent2 > 0.0)) return direction(1);
    const Dir d =
        b_ * (1.0 - one_minus_z) + tangent * std::sqrt(one_minus_z * (2.0 - one_minus_z) / tangent2);
    return {float(d.x), float(d.y), float(d.z)};
}

Vec2 SphericalTriangle::invert(Vec3 w_float) const {
    const Dir w{w_float.x, w_float.y, w_float.z};
    // ĉ: where the great circle through b and w meets the arc a→c, on w's side of b. The normals
    // of the two great circles from differences, as in solid_angle_of.
    Dir c_hat;
    if (!unit(cross(cross(b_, w - b_), cross(a_, c_ - a_)), &c_hat)) return {0.0f, 0.0f};
    if (dot(c_hat, a_ + c_) < 0.0) c_hat = c_hat * -1.0;
    const double u1 = solid_angle_of(a_, b_, c_hat) / solid_angle_;
    const double denominator = one_minus_cosine(c_hat, b_);
    const double u2 = denominator > 0.0 ? one_minus_cosine(w, b_) / denominator : 0.0;
    return {static_cast<float>(std::clamp(u1, 0.0, 1.0)), static_cast<float>(std::clamp(u2, 0.0, 1.0))};
}

}  // namespace stratum
