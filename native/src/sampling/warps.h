// Warps: maps from the unit square [0,1)^2 to directions and points, each with its density.
//
// | warp                              | density                         | reference                       |
// |-----------------------------------|---------------------------------|---------------------------------|
// | sample_uniform_disk_concentric    | 1/pi on the unit disk           | Shirley & Chiu 1997             |
// | sample_cosine_hemisphere          | cos(theta)/pi                   | textbook 4.60-4.61 (Malley)     |
// | sample_uniform_hemisphere         | 1/(2 pi)                        | textbook 4.45-4.52, half sphere |
// | sample_uniform_angles_hemisphere  | 1/(pi^2 sin(theta))             | uniform in (theta, phi)         |
// | sample_uniform_sphere             | 1/(4 pi)                        | textbook 4.45-4.52              |
// | sample_uniform_cone               | 1/(2 pi (1 - cos_max))          | uniform in cos(theta) on a cap  |
// | sample_uniform_triangle           | 2 (barycentric area measure)    | textbook 4.38, fold method      |
// | sample_ggx_visible_normal         | G1(wo) max(0,wo.h) D(h) / wo.z  | Heitz 2018, JCGT 7(4)           |
// | sample_bilinear                   | bilinear in the corner weights  | marginal then conditional,      |
// |                                   | (unit-square measure)           | each linear (inverse CDF)       |
//
// Directions are in a local frame with z up; densities are per unit solid angle unless stated.
#pragma once

#include "core/math.h"

namespace stratum {

// Shirley & Chiu 1997: maps concentric squares to concentric circles, so strata of the square
// stay compact on the disk (unlike r = sqrt(u), phi = 2 pi v, which shears them).
inline Vec2 sample_uniform_disk_concentric(Vec2 u) {
    const float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
    if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f};
    float r, phi;
    if (std::abs(a) > std::abs(b)) {
        r = a;
        phi = (kPi / 4.0f) * (b / a);
    } else {
        r = b;
        phi = (kPi / 2.0f) - (kPi / 4.0f) * (a / b);
    }
    return {r * std::cos(phi), r * std::sin(phi)};
}

// Malley's method: a uniform disk point lifted to the hemisphere has density cos(theta)/pi,
// the same density as the textbook's normalize(N + uniform sphere point) (4.60-4.61), with one
// square root instead of a normalisation and with the disk's stratification preserved.
inline Vec3 sample_cosine_hemisphere(Vec2 u) {
    const Vec2 d = sample_uniform_disk_concentric(u);
    return {d.x, d.y, safe_sqrt(1.0f - d.x * d.x - d.y * d.y)};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return std::max(cos_theta, 0.0f) * kInvPi; }

// Textbook 4.45-4.52 restricted to z >= 0: z = u uniform, phi = 2 pi v (Archimedes).
inline Vec3 sample_uniform_hemisphere(Vec2 u) {
    const float z = u.x, r = safe_sqrt(1.0f - z * z), phi = 2.0f * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float uniform_hemisphere_pdf() { return kInv2Pi; }

// phi = 2 pi u, theta = (pi/2) v: uniform in the angles, so the solid-angle density is
// 1/(2 pi * pi/2) / sin(theta) = 1/(pi^2 sin(theta)); it crowds samples at the pole. It exists
// as the naive strategy the comparisons need, not as a good one.
inline Vec3 sample_uniform_angles_hemisphere(Vec2 u) {
    const float phi = 2.0f * kPi * u.x, theta = 0.5f * kPi * u.y;
    const float s = std::sin(theta);
    return {s * std::cos(phi), s * std::sin(phi), std::cos(theta)};
}
inline float uniform_angles_hemisphere_pdf(float cos_theta) {
    const float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta);
    return (cos_theta < 0.0f || sin_theta == 0.0f) ? 0.0f : 1.0f / (kPi * kPi * sin_theta);
}

// Textbook 4.45-4.52: h = 2u - 1, phi = 2 pi v, s = (sqrt(1-h^2) cos phi, sqrt(1-h^2) sin phi, h).
inline Vec3 sample_uniform_sphere(Vec2 u) {
    const float z = 1.0f - 2.0f * u.x, r = safe_sqrt(1.0f - z * z), phi = 2.0f * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float uniform_sphere_pdf() { return kInv4Pi; }

// Uniform over the spherical cap theta <= theta_max around +z: cos(theta) uniform on
// [cos_max, 1] (the sphere construction restricted to the cap), so the density is 1/cap area.
inline Vec3 sample_uniform_cone(Vec2 u, float cos_max) {
    const float z = 1.0f - u.x * (1.0f - cos_max), r = safe_sqrt(1.0f - z * z), phi = 2.0f * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float uniform_cone_pdf(float cos_theta, float cos_max) {
    return cos_theta < cos_max ? 0.0f : 1.0f / (2.0f * kPi * (1.0f - cos_max));
}

// Textbook 4.38, fold method: (u, v) uniform in the unit square, reflected into the lower-left
// triangle when u + v > 1. Returns barycentrics (b0, b1, b2) with P = b0 P0 + b1 P1 + b2 P2,
// i.e. P = P0 + b1 E1 + b2 E2; the area density is 2 / |E1 x E2|.
inline Vec3 sample_uniform_triangle(Vec2 u) {
    float b1 = u.x, b2 = u.y;
    if (b1 + b2 > 1.0f) {
        b1 = 1.0f - b1;
        b2 = 1.0f - b2;
    }
    return {1.0f - b1 - b2, b1, b2};
}

// Density on [0,1] proportional to (1 − t) a + t b (a, b >= 0, not both 0):
// p(t) = 2 ((1 − t) a + t b) / (a + b). Inverting F(t) = (a t + (b − a) t²/2) / ((a + b)/2) = u
// gives t = (−a + √(a² + u (b² − a²))) / (b − a); multiplied through by the conjugate,
// t = u (a + b) / (a + √((1 − u) a² + u b²)), which has no cancellation and holds for a = b.
// Its denominator is 0 only for a = 0 and u = 0, where t = 0.
inline float sample_linear(float u, float a, float b) {
    const float denominator = a + std::sqrt((1.0f - u) * a * a + u * b * b);
    if (!(denominator > 0.0f)) return 0.0f;
    return std::min(u * (a + b) / denominator, kOneMinusEpsilon);
}

// Corner weights of a bilinear density on the unit square: w[0] at (0,0), w[1] at (1,0),
// w[2] at (0,1), w[3] at (1,1); all >= 0, not all 0.
struct BilinearWeights {
    float w[4];
};
// p(x, y) = 4 ((1−x)(1−y) w0 + x(1−y) w1 + (1−x) y w2 + x y w3) / (w0 + w1 + w2 + w3).
inline float bilinear_pdf(Vec2 u, const BilinearWeights& b) {
    const float sum = b.w[0] + b.w[1] + b.w[2] + b.w[3];
    return 4.0f *
           ((1 - u.x) * (1 - u.y) * b.w[0] + u.x * (1 - u.y) * b.w[1] + (1 - u.x) * u.y * b.w[2] +
            u.x * u.y * b.w[3]) /
           sum;
}
// y from its marginal (linear between the bottom and top edge sums), then x from the
// conditional at that y (linear between the left and right edge weights there).
inline Vec2 sample_bilinear(Vec2 u, const BilinearWeights& b) {
    const float y = sample_linear(u.y, b.w[0] + b.w[1], b.w[2] + b.w[3]);
    const float x = sample_linear(u.x, (1 - y) * b.w[0] + y * b.w[2], (1 - y) * b.w[1] + y * b.w[3]);
    return {x, y};
}

// Heitz 2018, "Sampling the GGX Distribution of Visible Normals" (JCGT 7(4)), isotropic alpha:
// stretch wo to the alpha = 1 configuration, sample the projected hemisphere of visible
// normals there (a disk, warped towards the visible half), unstretch. The returned half vector
// h has density D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z. Requires wo.z > 0.
inline Vec3 sample_ggx_visible_normal(Vec3 wo, float alpha, Vec2 u) {
    const Vec3 vh = normalize(Vec3(alpha * wo.x, alpha * wo.y, wo.z));
    const float len_sq = vh.x * vh.x + vh.y * vh.y;
    const Vec3 t1 = len_sq > 0.0f ? Vec3(-vh.y, vh.x, 0.0f) / std::sqrt(len_sq) : Vec3(1.0f, 0.0f, 0.0f);
    const Vec3 t2 = cross(vh, t1);
    const float r = std::sqrt(u.x), phi = 2.0f * kPi * u.y;
    const float p1 = r * std::cos(phi);
    const float s = 0.5f * (1.0f + vh.z);
    const float p2 = (1.0f - s) * safe_sqrt(1.0f - p1 * p1) + s * r * std::sin(phi);
    const Vec3 nh = t1 * p1 + t2 * p2 + vh * safe_sqrt(1.0f - p1 * p1 - p2 * p2);
    return normalize(Vec3(alpha * nh.x, alpha * nh.y, std::max(nh.z, 1e-7f)));
}

}  // namespace stratum
