// Small vector algebra shared by every layer of the core: 3-vectors, RGB, orthonormal frames
// and 4x4 affine transforms (row-major, as Blender's Matrix and the C ABI).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace stratum {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;
// Largest float below 1: samples are clamped to it so a warp never sees u == 1.
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

struct Vec3 {
    float x = 0, y = 0, z = 0;
    constexpr Vec3() = default;
    constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3& operator+=(Vec3 b) {
        x += b.x;
        y += b.y;
        z += b.z;
        return *this;
    }
    constexpr Vec3& operator*=(float s) {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
};
constexpr Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
constexpr Vec3 operator*(float s, Vec3 a) { return a * s; }
constexpr Vec3 operator/(Vec3 a, float s) { return a * (1.0f / s); }
constexpr float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) { return a / length(a); }
inline bool is_finite(Vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

struct Vec2 {
    float x = 0, y = 0;
};

// Linear RGB radiance / reflectance.
// Rec.709 luminance weights Cycles uses to turn a colour into a float (rgb_to_y, svm/convert.h).
inline constexpr float kLuminanceR = 0.2126729f, kLuminanceG = 0.7151522f, kLuminanceB = 0.0721750f;

struct Rgb {
    float r = 0, g = 0, b = 0;
    constexpr Rgb() = default;
    constexpr Rgb(float r_, float g_, float b_) : r(r_), g(g_), b(b_) {}
    constexpr explicit Rgb(float v) : r(v), g(v), b(v) {}
    constexpr Rgb& operator+=(Rgb o) {
        r += o.r;
        g += o.g;
        b += o.b;
        return *this;
    }
    constexpr Rgb& operator*=(Rgb o) {
        r *= o.r;
        g *= o.g;
        b *= o.b;
        return *this;
    }
    constexpr Rgb& operator*=(float s) {
        r *= s;
        g *= s;
        b *= s;
        return *this;
    }
    constexpr float max_component() const { return std::max(r, std::max(g, b)); }
    constexpr float average() const { return (r + g + b) * (1.0f / 3.0f); }
    constexpr bool is_black() const { return r == 0 && g == 0 && b == 0; }
};
constexpr Rgb operator+(Rgb a, Rgb b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
constexpr Rgb operator-(Rgb a, Rgb b) { return {a.r - b.r, a.g - b.g, a.b - b.b}; }
constexpr Rgb operator*(Rgb a, Rgb b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }
constexpr Rgb operator*(Rgb a, float s) { return {a.r * s, a.g * s, a.b * s}; }
constexpr Rgb operator*(float s, Rgb a) { return a * s; }
constexpr Rgb operator/(Rgb a, float s) { return a * (1.0f / s); }
constexpr Rgb lerp(Rgb a, Rgb b, float t) { return a * (1.0f - t) + b * t; }

// Orthonormal basis around a unit normal; local z is the normal. Duff et al. 2017,
// "Building an Orthonormal Basis, Revisited" (branchless, no singularity at n = ±z).
struct Frame {
    Vec3 s, t, n;
    static Frame from_normal(Vec3 n) {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z);
        const float b = n.x * n.y * a;
        return {Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3(b, sign + n.y * n.y * a, -n.y),
                n};
    }
    Vec3 to_local(Vec3 v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
    Vec3 to_world(Vec3 v) const { return s * v.x + t * v.y + n * v.z; }
};

// Affine transform, row-major 4x4 (the last row is 0 0 0 1 and is not stored).
struct Transform {
    std::array<float, 12> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    static Transform from_row_major(const float* v) {
        Transform t;
        std::copy(v, v + 12, t.m.begin());
        return t;
    }
    Vec3 point(Vec3 p) const {
        return {m[0] * p.x + m[1] * p.y + m[2] * p.z + m[3], m[4] * p.x + m[5] * p.y + m[6] * p.z + m[7],
                m[8] * p.x + m[9] * p.y + m[10] * p.z + m[11]};
    }
    Vec3 vector(Vec3 v) const {
        return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[4] * v.x + m[5] * v.y + m[6] * v.z,
                m[8] * v.x + m[9] * v.y + m[10] * v.z};
    }
    // Normals transform by the inverse transpose of the linear part: the cofactor matrix
    // gives the same direction without dividing by the determinant.
    Vec3 normal(Vec3 v) const {
        const Vec3 c0(m[0], m[4], m[8]), c1(m[1], m[5], m[9]), c2(m[2], m[6], m[10]);
        const Vec3 r0 = cross(c1, c2), r1 = cross(c2, c0), r2 = cross(c0, c1);
        const float det = dot(c0, r0);
        const Vec3 n = r0 * v.x + r1 * v.y + r2 * v.z;
        return det < 0 ? -n : n;
    }
    Vec3 column(int c) const { return {m[c], m[4 + c], m[8 + c]}; }
    Vec3 translation() const { return column(3); }
    // The inverse (a singular linear part gives non-finite entries): the cofactor rows over the
    // determinant, and the translation taken back through them.
    Transform inverse() const {
        const Vec3 c0(m[0], m[4], m[8]), c1(m[1], m[5], m[9]), c2(m[2], m[6], m[10]);
        const Vec3 r0 = cross(c1, c2), r1 = cross(c2, c0), r2 = cross(c0, c1);
        const float inv_det = 1.0f / dot(c0, r0);
        Transform t;
        const Vec3 rows[3] = {r0 * inv_det, r1 * inv_det, r2 * inv_det};
        const Vec3 o = translation();
        for (int i = 0; i < 3; ++i) {
            t.m[4 * i] = rows[i].x;
            t.m[4 * i + 1] = rows[i].y;
            t.m[4 * i + 2] = rows[i].z;
            t.m[4 * i + 3] = -dot(rows[i], o);
        }
        return t;
    }
};

inline float safe_sqrt(float x) { return std::sqrt(std::max(x, 0.0f)); }

// The mean of the channels in double: (r + g + b) / 3 in float overflows for channels near
// FLT_MAX (a lamp of 3e38 W), which made such a lamp's selection probability NaN.
inline double mean(Rgb c) { return (static_cast<double>(c.r) + c.g + c.b) / 3.0; }

// c × s in double, saturating at ±FLT_MAX: a radiance derived from an input near FLT_MAX (a
// lamp's power over a small area) stays finite instead of becoming Inf, which would be dropped
// as a non-finite sample and leave the lamp black.
inline float saturate_to_float(double v) {
    constexpr double kMax = 3.4028234663852886e38;  // FLT_MAX
    return static_cast<float>(std::clamp(v, -kMax, kMax));
}
inline Rgb saturating_product(Rgb c, double s) {
    return {saturate_to_float(c.r * s), saturate_to_float(c.g * s), saturate_to_float(c.b * s)};
}
inline float sqr(float x) { return x * x; }

}  // namespace stratum
