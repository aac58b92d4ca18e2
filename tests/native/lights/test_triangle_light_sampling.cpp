// Next-event estimation's two ways of taking a point on an emissive triangle
// (lights/emissive_triangle.h, setting triangle_sampling): uniform in area (textbook 5.9) and in
// solid angle with the cosine warp (the default).
//
// * Both estimate the irradiance a triangle of radiance L gives a point, against Lambert's
//   closed form for a polygon wholly above the point's horizon,
//       E = (L/2) |Σ_i Θ_i (n · Γ_i)|,  Γ_i = (u_i × u_{i+1}) / |u_i × u_{i+1}|,  Θ_i = ∠(u_i, u_{i+1})
//   (u_i the unit directions to the vertices; Arvo 1995, "Applications of Irradiance Tensors"),
//   within 4 standard errors s/√N of N independent samples.
// * The pdf a sample reports is the pdf() a BSDF ray reaching the same point gets (MIS).
// * Next to the emitter, solid-angle sampling's weight L cos θ / pdf is bounded (derived below)
//   while area sampling's reaches L A / d².
// * Where the cut-offs apply (a far triangle, by its solid angle or by its distance over its
//   longest edge, a point in the triangle's plane) the solid-angle mode is area sampling,
//   sample for sample.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>

#include "lights/emissive_triangle.h"

namespace stratum {
namespace {

constexpr float kRadiance = 2.0f;

struct Configuration {
    const char* label;
    Vec3 p, n, v0, v1, v2;
};

// A 0.6 × 0.5 triangle seen from 2 cm (under it and, through its back face, over it), obliquely
// from afar, from far enough that its solid angle is under the cut-off (area sampling), and from
// a tilted surface.
const Vec3 kA(-0.3f, -0.2f, 0.02f), kB(0.3f, -0.2f, 0.02f), kC(0.0f, 0.3f, 0.02f);
const Configuration kConfigurations[] = {
    {"2 cm under it", {0, 0, 0}, {0, 0, 1}, kA, kB, kC},
    {"2 cm over its back", {0.05f, 0.02f, 0.04f}, {0, 0, -1}, kA, kB, kC},
    {"oblique", {1.2f, 0.4f, -0.5f}, normalize(Vec3(-1, -0.2f, 1)), kA, kB, kC},
    {"far (area sampling)", {0, 0, -25}, {0, 0, 1}, kA, kB, kC},
    {"tilted receiver", {0.4f, -0.5f, -0.1f}, normalize(Vec3(-0.5f, 0.6f, 1)), kA, kB, kC},
};

// In double throughout: from 25 units the edges subtend ~0.02 rad, and an angle taken from a
// float dot product (acos near 1) would be off by ~1e-4 of itself.
double lambert_irradiance(const Configuration& c) {
    using D = std::array<double, 3>;
    const auto unit_toward = [&](Vec3 v) {
        const D d = {double(v.x) - c.p.x, double(v.y) - c.p.y, double(v.z) - c.p.z};
        const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        return D{d[0] / l, d[1] / l, d[2] / l};
    };
    const D u[3] = {unit_toward(c.v0), unit_toward(c.v1), unit_toward(c.v2)};
    double sum = 0;
    for (int i = 0; i < 3; ++i) {
        const D& a = u[i];
        const D& b = u[(i + 1) % 3];
        const D x = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
        const double sine = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        const double angle = std::atan2(sine, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]);
        sum += angle * (x[0] * c.n.x + x[1] * c.n.y + x[2] * c.n.z) / sine;
    }
    return 0.5 * kRadiance * std::abs(sum);
}

// L cos θ / pdf of one sample, 0 when sample() gives none.
double weight(const LightSample& ls, Vec3 n) {
    return ls.radiance.r * std::max(0.0f, dot(ls.wi, n)) / ls.pdf;
}

TEST(TriangleLightSampling, BothModesMeasureLambertsIrradiance) {
    constexpr int kSamples = 200'000;
    for (const Configuration& c : kConfigurations) {
        const EmissiveTriangle tri(c.v0, c.v1, c.v2, Rgb(kRadiance));
        const double expected = lambert_irradiance(c);
        for (const TriangleSampling mode : {TriangleSampling::Area, TriangleSampling::SolidAngle}) {
            const char* name = mode == TriangleSampling::Area ? "area" : "solid angle";
            std::mt19937_64 rng(7);
            std::uniform_real_distribution<float> u(0.0f, kOneMinusEpsilon);
            double sum = 0, sum2 = 0;
            for (int k = 0; k < kSamples; ++k) {
                LightSample ls;
                const double w = tri.sample(c.p, c.n, {u(rng), u(rng)}, mode, &ls) ? weight(ls, c.n) : 0.0;
                sum += w;
                sum2 += w * w;
            }
            const double mean = sum / kSamples;
            const double se = std::sqrt(std::max(0.0, sum2 / kSamples - mean * mean) / (kSamples - 1));
            EXPECT_NEAR(mean, expected, 4.0 * se + 1e-6 * expected)
                << c.label << ", " << name << ": se " << se;
            EXPECT_GT(expected, 0.0) << c.label;
        }
    }
}

TEST(TriangleLightSampling, SamplePdfIsThePdfOfReachingItsPoint) {
    // Both sides compute the same expression from the same point, except that pdf() recovers the
    // square's sample from the float direction (SphericalTriangle::invert, ~1e-5 of u): the
    // bilinear density's slope is at most max w / min w ≤ 100 (the floor 0.01), so ≤ 1e-3.
    for (const Configuration& c : kConfigurations) {
        const EmissiveTriangle tri(c.v0, c.v1, c.v2, Rgb(kRadiance));
        for (const TriangleSampling mode : {TriangleSampling::Area, TriangleSampling::SolidAngle}) {
            std::mt19937_64 rng(11);
            std::uniform_real_distribution<float> u(0.0f, kOneMinusEpsilon);
            for (int k = 0; k < 2000; ++k) {
                LightSample ls;
                if (!tri.sample(c.p, c.n, {u(rng), u(rng)}, mode, &ls)) continue;
                const float pdf = tri.pdf(c.p, c.n, c.p + ls.wi * ls.distance, mode);
                ASSERT_NEAR(pdf, ls.pdf, 1e-3f * ls.pdf)
                    << c.label << (mode == TriangleSampling::Area ? " area" : "");
            }
        }
    }
}

TEST(TriangleLightSampling, SolidAngleWeightIsBoundedNextToTheEmitter) {
    // Solid angle: weight = L cos θ Ω / bilinear_pdf(u), with cos θ ≤ 1 and
    // bilinear_pdf ≥ 4 min w / Σ w (the density's minimum is at a corner), so
    //     weight ≤ L Ω Σw / (4 min w).
    // Area sampling at 2 cm under the triangle: a point within 5 mm of the foot of p (probability
    // π 0.005² / A ≈ 5e-4, about 100 of 200 000 samples) has weight ≥ L A cos⁴ / r² with
    // r ≤ √(0.02² + 0.005²): ≥ 0.88 L A / 0.000425 ≈ 310 L, ten times the bound and more.
    const Configuration& c = kConfigurations[0];
    const EmissiveTriangle tri(c.v0, c.v1, c.v2, Rgb(kRadiance));
    const SphericalTriangle spherical(c.p, c.v0, c.v1, c.v2);
    float w_sum = 0, w_min = 1;
    for (Vec3 v : {c.v0, c.v1, c.v1, c.v2}) {
        const float w = std::max(EmissiveTriangle::kMinCosineWeight, std::abs(dot(normalize(v - c.p), c.n)));
        w_sum += w;
        w_min = std::min(w_min, w);
    }
    const double bound = kRadiance * spherical.solid_angle() * w_sum / (4 * w_min);
    double max_solid = 0, max_area = 0;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<float> u(0.0f, kOneMinusEpsilon);
    for (int k = 0; k < 200'000; ++k) {
        const Vec2 s{u(rng), u(rng)};
        LightSample ls;
        if (tri.sample(c.p, c.n, s, TriangleSampling::SolidAngle, &ls))
            max_solid = std::max(max_solid, weight(ls, c.n));
        if (tri.sample(c.p, c.n, s, TriangleSampling::Area, &ls))
            max_area = std::max(max_area, weight(ls, c.n));
    }
    EXPECT_LE(max_solid, bound * (1 + 1e-4)) << "bound " << bound;
    EXPECT_GT(max_area, 10 * bound) << "area sampling's largest weight " << max_area;
    std::printf("2 cm under the triangle: largest weight %.3g (solid angle, bound %.3g), %.3g (area)\n",
                max_solid, bound, max_area);
}

TEST(TriangleLightSampling, CutOffsFallBackToAreaSampling) {
    const EmissiveTriangle tri(kA, kB, kC, Rgb(kRadiance));
    const Vec3 up(0, 0, 1);
    // On the triangle (a shading point of the emitter itself), in its plane outside it, and far:
    // the solid-angle mode samples exactly as area sampling.
    const Vec3 points[] = {(kA + kB + kC) * (1.0f / 3.0f), Vec3(2, 0, 0.02f), Vec3(0, 0, -25)};
    ASSERT_LT(SphericalTriangle(points[2], kA, kB, kC).solid_angle(),
              EmissiveTriangle::kMinSphericalSolidAngle);
    for (const Vec3& p : points) {
        for (const Vec2 s : {Vec2{0.2f, 0.3f}, Vec2{0.7f, 0.1f}, Vec2{0.5f, 0.9f}}) {
            LightSample a, b;
            const bool ok_a = tri.sample(p, up, s, TriangleSampling::Area, &a);
            const bool ok_b = tri.sample(p, up, s, TriangleSampling::SolidAngle, &b);
            ASSERT_EQ(ok_a, ok_b);
            if (!ok_a) continue;
            EXPECT_EQ(a.pdf, b.pdf);
            EXPECT_EQ(a.distance, b.distance);
        }
    }
}

TEST(TriangleLightSampling, FarFromItsPlaneByMoreThanTheLongestEdgeIsAreaSampling) {
    // Cycles' test (lights/emissive_triangle.h): solid angle while the distance to the plane is
    // under kSphericalDistanceRatio × the longest edge (here |AB| = 0.6), area sampling from
    // there on, on either side and off to the side alike; the pdf of a BSDF ray follows.
    const EmissiveTriangle tri(kA, kB, kC, Rgb(kRadiance));
    const float edge = length(kB - kA) * EmissiveTriangle::kSphericalDistanceRatio;
    const Vec3 up(0, 0, 1);
    const auto same_as_area = [&](Vec3 p) {
        const Vec2 s{0.3f, 0.6f};
        LightSample a, b;
        EXPECT_TRUE(tri.sample(p, up, s, TriangleSampling::Area, &a));
        EXPECT_TRUE(tri.sample(p, up, s, TriangleSampling::SolidAngle, &b));
        const Vec3 hit = p + b.wi * b.distance;
        const bool pdfs_agree =
            tri.pdf(p, up, hit, TriangleSampling::SolidAngle) == tri.pdf(p, up, hit, TriangleSampling::Area);
        return a.pdf == b.pdf && a.distance == b.distance && pdfs_agree;
    };
    for (const float side : {-1.0f, 1.0f}) {
        EXPECT_FALSE(same_as_area({0.05f, 0.0f, 0.02f + side * 0.98f * edge})) << side;
        EXPECT_TRUE(same_as_area({0.05f, 0.0f, 0.02f + side * 1.02f * edge})) << side;
        EXPECT_TRUE(same_as_area({2.0f, 1.0f, 0.02f + side * 1.02f * edge})) << side;
    }
}

}  // namespace
}  // namespace stratum
