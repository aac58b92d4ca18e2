// The solid angle of a triangle and Arvo's uniform sampling of it (sampling/spherical_triangle.h).
//
// Uniformity is a chi-square test: the planar triangle is cut into n² similar sub-triangles
// (n = 16, 256 cells), each cell's probability is its own solid angle over the whole one's
// (exact, by the same Van Oosterom–Strackee formula, which the first test checks against closed
// forms), and each sampled direction is located by where it meets the triangle's plane. Seeds
// are fixed; each of the kConfigurations tests rejects at 1%/kConfigurations (Bonferroni), so
// the chance of any false failure is below 1%.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "chi_square.h"
#include "sampling/spherical_triangle.h"

namespace stratum {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Configuration {
    const char* label;
    Vec3 p, v0, v1, v2;
};

// Seen from near and far, from either side, edge-on, a sliver, and just above area sampling's
// cut-off (lights/emissive_triangle.h: 3e-4 sr; this one subtends ≈ 5.5e-4).
const Configuration kConfigurations[] = {
    {"2 cm under a large triangle", {0, 0, 0}, {-0.3f, -0.2f, 0.02f}, {0.3f, -0.2f, 0.02f}, {0, 0.3f, 0.02f}},
    {"2 cm over it (reversed winding)",
     {0, 0, 0.04f},
     {-0.3f, -0.2f, 0.02f},
     {0.3f, -0.2f, 0.02f},
     {0, 0.3f, 0.02f}},
    {"oblique, far", {2, 1, -1}, {-0.3f, -0.2f, 0.02f}, {0.3f, -0.2f, 0.02f}, {0, 0.3f, 0.02f}},
    {"grazing", {1.5f, 0, 0.05f}, {-0.3f, -0.2f, 0}, {0.3f, -0.2f, 0}, {0, 0.3f, 0}},
    {"sliver", {0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0.01f, 1}},
    {"small", {0, 0, 0}, {0, 0, 3}, {0.1f, 0, 3}, {0, 0.1f, 3}},
};
constexpr int kConfigurationCount = sizeof(kConfigurations) / sizeof(kConfigurations[0]);

TEST(SphericalTriangle, SolidAngleMatchesClosedForms) {
    // An octant: the triangle of the three axis points covers 1/8 of the sphere.
    EXPECT_NEAR(SphericalTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}).solid_angle(), kPi / 2, 1e-6);
    EXPECT_NEAR(SphericalTriangle({0, 0, 0}, {0, 0, 1}, {0, 1, 0}, {1, 0, 0}).solid_angle(), kPi / 2, 1e-6);
    // A 2 × 2 square at distance 1, as two triangles: Ω = 4 asin(ab / √((a² + 4d²)(b² + 4d²)))
    // = 4 asin(1/2) = 2π/3.
    const Vec3 a(-1, -1, 1), b(1, -1, 1), c(1, 1, 1), d(-1, 1, 1);
    EXPECT_NEAR(SphericalTriangle({0, 0, 0}, a, b, c).solid_angle() +
                    SphericalTriangle({0, 0, 0}, a, c, d).solid_angle(),
                2 * kPi / 3, 1e-6);
    // More than a hemisphere's half: the square 1 cm away, Ω → 2π.
    const float e = 0.01f;
    const double near_square = SphericalTriangle({0, 0, 1 - e}, a, b, c).solid_angle() +
                               SphericalTriangle({0, 0, 1 - e}, a, c, d).solid_angle();
    EXPECT_NEAR(near_square, 4 * std::asin(4 / (4 + 4 * double(e) * e)), 1e-5);
    EXPECT_GT(near_square, kPi);
    // In the triangle's plane: nothing.
    EXPECT_EQ(SphericalTriangle({5, 0, 1}, a, b, c).solid_angle(), 0.0);
    // Small and far: Ω → A cos θ / r².
    const double far =
        SphericalTriangle({0, 0, 0}, {100, 0, 0}, {100, 0.01f, 0}, {100, 0, 0.01f}).solid_angle();
    EXPECT_NEAR(far, 0.5e-4 / 1e4, 1e-6 * 0.5e-8);
}

double dot_d(Vec3 a, Vec3 b) { return double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z; }

// Which of the n² cells of (v0, v1, v2) the point q of its plane lies in; -1 outside. In double:
// the sliver's Gram determinant is 1e-4 of its entries, and float dot products would move the
// barycentrics by ~1e-3.
int cell_of(const Configuration& c, Vec3 q, int n) {
    const Vec3 e1 = c.v1 - c.v0, e2 = c.v2 - c.v0, r = q - c.v0;
    const double d11 = dot_d(e1, e1), d12 = dot_d(e1, e2), d22 = dot_d(e2, e2), r1 = dot_d(r, e1),
                 r2 = dot_d(r, e2);
    const double det = d11 * d22 - d12 * d12;
    const double b1 = (d22 * r1 - d12 * r2) / det, b2 = (d11 * r2 - d12 * r1) / det;
    constexpr double kSlack = 1e-4;  // float rounding of directions hitting the edges
    if (b1 < -kSlack || b2 < -kSlack || b1 + b2 > 1 + kSlack) return -1;
    const int i = std::clamp(int(b1 * n), 0, n - 1), j = std::clamp(int(b2 * n), 0, n - 1 - i);
    const bool upper = b1 * n - i + b2 * n - j > 1.0 && i + j < n - 1;
    return 2 * (i * n + j) + (upper ? 1 : 0);
}

Vec3 lerp_grid(const Configuration& c, double i, double j, int n) {
    return c.v0 + (c.v1 - c.v0) * float(i / n) + (c.v2 - c.v0) * float(j / n);
}

TEST(SphericalTriangle, SamplesAreUniformInSolidAngle) {
    constexpr int kN = 16, kSamples = 400'000;
    constexpr double kSignificance = 0.01 / kConfigurationCount;
    uint64_t seed = 1;
    for (const Configuration& c : kConfigurations) {
        const SphericalTriangle spherical(c.p, c.v0, c.v1, c.v2);
        ASSERT_GT(spherical.solid_angle(), 0.0) << c.label;
        std::vector<double> expected(2 * kN * kN, 0.0), observed(2 * kN * kN, 0.0);
        double total = 0;
        for (int i = 0; i < kN; ++i) {
            for (int j = 0; i + j < kN; ++j) {
                const Vec3 a = lerp_grid(c, i, j, kN), b = lerp_grid(c, i + 1, j, kN),
                           d = lerp_grid(c, i, j + 1, kN);
                expected[2 * (i * kN + j)] = SphericalTriangle(c.p, a, b, d).solid_angle();
                if (i + j < kN - 1) {
                    const Vec3 e = lerp_grid(c, i + 1, j + 1, kN);
                    expected[2 * (i * kN + j) + 1] = SphericalTriangle(c.p, b, e, d).solid_angle();
                }
            }
        }
        for (double x : expected) total += x;
        // The cells tile the triangle: their solid angles add up to the whole one's.
        EXPECT_NEAR(total, spherical.solid_angle(), 1e-6 * spherical.solid_angle()) << c.label;
        for (double& x : expected) x *= kSamples / total;
        std::mt19937_64 rng(seed++);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        int outside = 0;
        const Vec3 normal = normalize(cross(c.v1 - c.v0, c.v2 - c.v0));
        for (int k = 0; k < kSamples; ++k) {
            const Vec3 w = spherical.sample({u(rng), u(rng)});
            EXPECT_NEAR(length(w), 1.0f, 1e-5f);
            const float t = dot(c.v0 - c.p, normal) / dot(w, normal);
            const int cell = t > 0 ? cell_of(c, c.p + w * t, kN) : -1;
            if (cell < 0) {
                ++outside;
            } else {
                observed[cell] += 1;
            }
        }
        EXPECT_EQ(outside, 0) << c.label;
        const chi_square::ChiSquare r = chi_square::pearson(observed, expected);
        EXPECT_GT(r.p_value, kSignificance) << c.label << ": chi2 = " << r.statistic << ", dof = " << r.dof;
    }
}

TEST(SphericalTriangle, InvertUndoesSample) {
    // sample() returns float directions (~6e-8 relative); through invert's cosines that moves u by
    // less than 1e-5 for these configurations (arcs ≥ 0.03 rad: 1 − cos ≥ 4e-4).
    for (const Configuration& c : kConfigurations) {
        const SphericalTriangle spherical(c.p, c.v0, c.v1, c.v2);
        for (int i = 1; i < 20; ++i) {
            for (int j = 1; j < 20; ++j) {
                const Vec2 u{float(i) / 20.0f, float(j) / 20.0f};
                const Vec2 back = spherical.invert(spherical.sample(u));
                EXPECT_NEAR(back.x, u.x, 1e-4f) << c.label << " u = " << u.x << ", " << u.y;
                EXPECT_NEAR(back.y, u.y, 1e-4f) << c.label << " u = " << u.x << ", " << u.y;
            }
        }
    }
}

TEST(SphericalTriangle, CornersOfTheSquareMapToTheVertices) {
    const Configuration& c = kConfigurations[2];
    const SphericalTriangle spherical(c.p, c.v0, c.v1, c.v2);
    const auto toward = [&](Vec3 v) { return normalize(v - c.p); };
    const auto expect_close = [](Vec3 a, Vec3 b, const char* what) {
        EXPECT_NEAR(length(a - b), 0.0f, 1e-5f) << what;
    };
    expect_close(spherical.sample({0, 0}), toward(c.v1), "(0,0) -> v1");
    expect_close(spherical.sample({1, 0}), toward(c.v1), "(1,0) -> v1");
    expect_close(spherical.sample({0, 1}), toward(c.v0), "(0,1) -> v0");
    expect_close(spherical.sample({1, 1}), toward(c.v2), "(1,1) -> v2");
}

}  // namespace
}  // namespace stratum
