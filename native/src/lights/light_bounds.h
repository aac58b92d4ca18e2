// The spatial and directional bound of a light or of a cluster of lights, and the importance
// of such a bound at a shading point: the light tree's measure (lights/light_tree.h).
//
// | field        | meaning                                                                    |
// |--------------|----------------------------------------------------------------------------|
// | lo, hi       | world-space box holding every emitting point                               |
// | phi          | power Φ in W (LightSet::power), the sum over a cluster                     |
// | axis         | unit axis w of the orientation cone                                        |
// | theta_o      | normals lie within θ_o of w (π: any direction, a point lamp)               |
// | theta_e      | each normal emits within θ_e of itself (π/2 a Lambertian face, θ_h a spot) |
// | two_sided    | the normals are ±w (emissive triangles emit from both faces)                |
//
// Conty Estévez & Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree Splitting"
// (HPG), §4.1 orientation bounds and §4.3 importance, as pbrt-v4 LightBounds::Importance states
// it: with d the distance from p to the box's centre, θ_w the angle between w and the direction
// from the centre to p, θ_b the half angle the box's bounding sphere subtends at p (π when p is
// inside it) and θ_i the angle between n and that direction,
//     θ' = max(0, θ_w − θ_o − θ_b),   θ'_i = max(0, θ_i − θ_b),
//     I = 0 if θ' ≥ θ_e, else Φ cos θ' cos θ'_i / max(d², (|diagonal|/2)²),
// θ'_i omitted when n = 0 and cos θ_i taken as |n·ω| (a surface that transmits sees lights
// below it). Every angle is a lower bound of the true one for every point of the cluster, so
// I = 0 only where no light of the cluster can reach p. The d² clamp is pbrt's (it keeps a
// shading point inside a cluster from giving that cluster infinite weight), squared here so
// that it has the units of d². A strict θ' ≥ θ_e (pbrt: cos θ' ≤ cos θ_e) would zero a hard-
// edged spot (θ_e = 0) everywhere; the test below is cos θ' < cos θ_e.
//
// Float (importance() runs twice per tree level for every choice and every MIS pmf; in double it
// was ~40% of the many-lights hall's render time). I = 0 must stay exact-arithmetic safe, so
// every zero test leans toward "can contribute" by more than float rounding:
// * sin θ_w and sin θ_i are |w × ω| and |n × ω|, accurate to a few ulp; √(1 − cos²) would err by
//   up to √ulp ≈ 2.4e-4 near cos = ±1, more than any margin below;
// * the bounding sphere's radius is padded by kRadiusPadding − 1 = 1e-5 relative, so that near
//   its surface (where cos θ_b = √(d² − r²)/d cancels) the padding's 2e-5 r² in d² − r² exceeds
//   the ~3 ulp (2e-7 d²) rounding of d², and θ_b only grows;
// * the cosines tested against cos θ_e and 0 are sums of products of values in [−1, 1], each
//   off by a few ulp: the tests allow kCosMargin = 1e-5 (≥ 50× that rounding);
// * a cluster that passes the tests weighs at least kMinImportance (FLT_MIN, a normal number, so
//   flush-to-zero cannot remove it) and Φ is stored over the tree's total so that I ≤ 1e20 with
//   d² ≥ kMinRadius2 = 1e-20 (closer counts as inside the sphere, θ_b = π; the cross products'
//   squares then cannot underflow by more than 1e-9 in a sine): neither underflow nor overflow
//   turns a contributing cluster to 0.
// Where the margins make a cluster weigh FLT_MIN instead of 0 it is next to never chosen unless
// its sibling weighs as little (then a light that adds nothing may be chosen where none was).
//
// Orientation union (the paper's §4.1, pbrt-v4 DirectionCone Union): the cone holding both
// cones, half angle (θ_a + θ_d + θ_b)/2, axis rotated from w_a toward w_b; θ_e the larger. The
// union's angle is widened by kConePadding so that float rounding never leaves a child's normal
// outside its parent's cone (a node wrongly weighted 0 would bias the estimate).
//
// Split cost (the paper's eq. 2, pbrt-v4 BVHLightSampler::EvaluateCost): Φ M_Ω area(box) K_r,
//     M_Ω = 2π(1 − cos θ_o) + π/2 (2 θ_w sin θ_o − cos(θ_o − 2θ_w) − 2 θ_o sin θ_o + cos θ_o),
// θ_w = min(θ_o + θ_e, π), K_r = longest box side / side along the split axis. The box's sides
// count as at least one bucket of the node's centroid box long: a row of point lamps has a box
// of area 0, and with the exact area every split peeled off one row at no cost (a 32 × 32 grid
// of lamps built 26 levels deep instead of 13, and NEE variance 0.18× power selection's instead
// of 0.13×).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "core/math.h"

namespace stratum {

struct LightBounds {
    Vec3 lo, hi;
    double phi = 0.0;
    Vec3 axis{0.0f, 0.0f, 1.0f};
    float theta_o = 0.0f, theta_e = 0.0f;
    bool two_sided = false;

    // Radians added to a merged cone's θ_o (float rounding of the axis is ~1e-7).
    static constexpr double kConePadding = 1e-5;

    Vec3 centre() const { return (lo + hi) * 0.5f; }
    Vec3 diagonal() const { return hi - lo; }
};

inline Vec3 component_min(Vec3 a, Vec3 b) {
    return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
inline Vec3 component_max(Vec3 a, Vec3 b) {
    return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}

// Bounds of a light at `position` radiating in every direction within `radius` of it.
inline LightBounds omnidirectional_bounds(Vec3 position, float radius, double phi) {
    const Vec3 r(radius, radius, radius);
    return {position - r, position + r, phi, Vec3(0.0f, 0.0f, 1.0f), kPi, 0.0f, false};
}

// The cluster of a and b (the header's orientation union).
inline LightBounds merge(const LightBounds& a, const LightBounds& b) {
    LightBounds m;
    m.lo = component_min(a.lo, b.lo);
    m.hi = component_max(a.hi, b.hi);
    m.phi = a.phi + b.phi;
    m.theta_e = std::max(a.theta_e, b.theta_e);
    m.two_sided = a.two_sided || b.two_sided;
    const double ta = a.theta_o, tb = b.theta_o;
    const double td = std::acos(std::clamp(static_cast<double>(dot(a.axis, b.axis)), -1.0, 1.0));
    double theta = 0.0;
    Vec3 axis = a.axis;
    if (std::min(td + tb, static_cast<double>(kPi)) <= ta) {
        theta = ta;
    } else if (std::min(td + ta, static_cast<double>(kPi)) <= tb) {
        theta = tb;
        axis = b.axis;
    } else {
        theta = 0.5 * (ta + td + tb);
        const Vec3 w = cross(a.axis, b.axis);
        const double w2 = dot(w, w);
        if (theta >= kPi || !(w2 > 0.0)) {
            theta = kPi;
        } else {
            // Rotate a.axis by θ − θ_a about w (Rodrigues; a.axis ⟂ w).
            const double rotate = theta - ta;
            const Vec3 k = w / static_cast<float>(std::sqrt(w2));
            const Vec3 r = a.axis * static_cast<float>(std::cos(rotate)) +
                           cross(k, a.axis) * static_cast<float>(std::sin(rotate));
            axis = normalize(r);
        }
    }
    m.axis = axis;
    m.theta_o = static_cast<float>(
        theta >= kPi ? kPi : std::min(theta + LightBounds::kConePadding, static_cast<double>(kPi)));
    return m;
}

// cos(max(0, a − b)) and sin(max(0, a − b)) from the sines and cosines of a and b in [0, π].
inline float cos_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
    return cos_a > cos_b ? 1.0f : cos_a * cos_b + sin_a * sin_b;
}
inline float sin_sub_clamped(float sin_a, float cos_a, float sin_b, float cos_b) {
    return cos_a > cos_b ? 0.0f : sin_a * cos_b - cos_a * sin_b;
}

// What importance() reads of the two children of a tree node, side by side (struct of arrays,
// lane k the child k) so that one descent step reads one 128-byte block; the cone's
// trigonometry is done once at the build. Float throughout (the header's float section).
struct alignas(64) ImportancePair {
    float centre_x[2], centre_y[2], centre_z[2];
    float axis_x[2], axis_y[2], axis_z[2];
    float radius[2];  // the bounding sphere's radius times kRadiusPadding
    float phi[2];  // Φ over the tree's total Φ ≤ 1, so that I ≤ 1/kMinRadius2 and I_0 + I_1 are finite
    float cos_o[2], sin_o[2], cos_e[2];
    uint32_t child[2];   // the child's pair (inner) or the caller's light (leaf)
    uint32_t flags = 0;  // bit k: child k is a leaf; bit 2 + k: child k is two-sided

    // Lane k from bound b (its Φ times phi_scale) and the child's pair index or light.
    void set(int k, const LightBounds& b, double phi_scale, uint32_t child_or_light, bool leaf);
    bool leaf(int k) const { return (flags >> k) & 1u; }
    bool two_sided(int k) const { return (flags >> (2 + k)) & 1u; }
};

static_assert(sizeof(ImportancePair) == 128, "both children of a node in two cache lines");

// Float-rounding allowances of importance() (the header's float section).
inline constexpr float kRadiusPadding = 1.0f + 1e-5f;
inline constexpr float kCosMargin = 1e-5f;
inline constexpr float kMinRadius2 = 1e-20f;
inline constexpr float kMinImportance = std::numeric_limits<float>::min();

inline void ImportancePair::set(int k, const LightBounds& b, double phi_scale, uint32_t child_or_light,
                                bool is_leaf) {
    const Vec3 c = b.centre(), half = b.diagonal() * 0.5f;
    centre_x[k] = c.x;
    centre_y[k] = c.y;
    centre_z[k] = c.z;
    axis_x[k] = b.axis.x;
    axis_y[k] = b.axis.y;
    axis_z[k] = b.axis.z;
    radius[k] = static_cast<float>(std::sqrt(static_cast<double>(dot(half, half)))) * kRadiusPadding;
    phi[k] = static_cast<float>(b.phi * phi_scale);
    cos_o[k] = static_cast<float>(std::cos(static_cast<double>(b.theta_o)));
    sin_o[k] = static_cast<float>(std::sin(static_cast<double>(b.theta_o)));
    cos_e[k] = static_cast<float>(std::cos(static_cast<double>(b.theta_e)));
    child[k] = child_or_light;
    const uint32_t bits = (is_leaf ? 1u << k : 0u) | (b.two_sided ? 1u << (2 + k) : 0u);
    flags = (flags & ~((1u << k) | (1u << (2 + k)))) | bits;
}

// The header's importance I of lane k of pair b at the shading point p; n is the unit normal
// and has_normal false when n = 0 (the n-term is then skipped).
inline float importance(const ImportancePair& b, int k, Vec3 p, Vec3 n, bool has_normal) {
    const float tx = p.x - b.centre_x[k], ty = p.y - b.centre_y[k], tz = p.z - b.centre_z[k];
    const float d2 = tx * tx + ty * ty + tz * tz;
    const float r = b.radius[k], r2 = r * r;
    // Inside the bounding sphere (θ_b = π) every angle bound is 0: I = Φ / max(r², tiny).
    if (!(d2 > std::max(r2, kMinRadius2)))
        return std::max(b.phi[k] / std::max(r2, kMinRadius2), kMinImportance);
    // 1/d² and d side by side, 1/d from both: the chains of divisions and square roots that
    // follow start together instead of one after the other (this is latency-bound).
    const float inv_d2 = 1.0f / d2;
    const float inv_d = std::sqrt(d2) * inv_d2;
    const float sin_b = std::min(r * inv_d, 1.0f);
    const float cos_b = std::sqrt(std::max(0.0f, d2 - r2)) * inv_d;
    // θ' = 0 where the cone holds every direction (θ_o = π: point lamps and their clusters); the
    // general formula gives cos θ' = 1 there too (cos θ_w > cos θ_o = −1, or both −1), at the
    // cost of a square root.
    float cos_theta = 1.0f;
    if (b.cos_o[k] > -1.0f) {
        const float ax = b.axis_x[k], ay = b.axis_y[k], az = b.axis_z[k];
        // θ_w: its sine from |w × t|/d, not √(1 − cos²), which loses half the digits near ±1.
        float cos_w = (ax * tx + ay * ty + az * tz) * inv_d;
        const float qx = ay * tz - az * ty, qy = az * tx - ax * tz, qz = ax * ty - ay * tx;
        const float sin_w = std::sqrt(qx * qx + qy * qy + qz * qz) * inv_d;
        if (b.two_sided(k)) cos_w = std::abs(cos_w);
        const float cos_x = cos_sub_clamped(sin_w, cos_w, b.sin_o[k], b.cos_o[k]);
        const float sin_x = sin_sub_clamped(sin_w, cos_w, b.sin_o[k], b.cos_o[k]);
        cos_theta = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
    }
    if (cos_theta < b.cos_e[k] - kCosMargin || cos_theta <= -kCosMargin) return 0.0f;
    float result = b.phi[k] * std::max(0.0f, cos_theta) * inv_d2;
    // cos θ'_i ≥ 0 (θ_i ≤ π/2 as cos θ_i = |n·ω|, θ_b ≤ π/2 outside the sphere): the n-term
    // scales I but never zeroes it beyond the floor below.
    if (has_normal) {
        const float cos_i = std::abs(n.x * tx + n.y * ty + n.z * tz) * inv_d;
        const float mx = n.y * tz - n.z * ty, my = n.z * tx - n.x * tz, mz = n.x * ty - n.y * tx;
        const float sin_i = std::sqrt(mx * mx + my * my + mz * mz) * inv_d;
        result *= cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
    }
    return std::max(result, kMinImportance);
}

// The header's split cost of bounds b for a split along `axis` (0, 1, 2); each side of the box
// counts as at least min_extent long in its area (below).
inline double split_cost(const LightBounds& b, int axis, float min_extent) {
    const double theta_o = b.theta_o, theta_e = b.theta_e;
    const double theta_w = std::min(theta_o + theta_e, static_cast<double>(kPi));
    const double cos_o = std::cos(theta_o), sin_o = std::sin(theta_o);
    const double m_omega =
        2.0 * kPi * (1.0 - cos_o) +
        0.5 * kPi *
            (2.0 * theta_w * sin_o - std::cos(theta_o - 2.0 * theta_w) - 2.0 * theta_o * sin_o + cos_o);
    const Vec3 d = component_max(b.diagonal(), Vec3(min_extent, min_extent, min_extent));
    const double longest = std::max({d.x, d.y, d.z});
    const double k_r = d[axis] > 0.0f ? longest / d[axis] : 1.0;
    const double area = 2.0 * (static_cast<double>(d.x) * d.y + static_cast<double>(d.y) * d.z +
                               static_cast<double>(d.z) * d.x);
    return b.phi * m_omega * k_r * area;
}

}  // namespace stratum
