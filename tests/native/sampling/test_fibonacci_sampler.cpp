// `fibonacci` and `fibonacci_static`: the lattice of seed 000 eq. 19, its per-pixel (or static)
// toroidal shift, and the rank-1 structure of every pixel's points in a pair.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sampling/fibonacci_sampler.h"
#include "sampling/stratified_sampler.h"

using namespace stratum;

namespace {

double frac(double v) { return v - std::floor(v); }
// Distance on the unit circle.
double circle_distance(double a, double b) {
    const double d = frac(a - b);
    return std::min(d, 1.0 - d);
}

}  // namespace

TEST(FibonacciSampler, UnshiftedLatticeIsEquation19) {
    // Seed 000, eq. 19: (x_i, y_i) = ((i + 1)/φ mod 1, (i + 0.5)/n), φ = (1 + √5)/2.
    const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
    for (uint32_t n : {8u, 16u, 32u, 100u}) {
        for (uint32_t i = 0; i < n; ++i) {
            const LatticePoint p = fibonacci_lattice_point(i, n);
            EXPECT_NEAR(p.x, frac((i + 1) / phi), 1e-12);
            EXPECT_DOUBLE_EQ(p.y, (i + 0.5) / n);
        }
    }
    EXPECT_NEAR(fibonacci_lattice_point(0, 8).x, 0.6180339887498949, 1e-15);
    EXPECT_NEAR(fibonacci_lattice_point(1, 8).x, 0.2360679774997898, 1e-15);
}

TEST(FibonacciSampler, EachPixelsPairIsTheShiftedLattice) {
    for (uint32_t n : {1u, 8u, 13u, 32u}) {
        for (bool per_pixel : {true, false}) {
            const FibonacciSampler s({n, 2, 8, 8}, per_pixel);
            for (uint32_t pair : {0u, 2u, 8u, 10u}) {
                const LatticePoint t = s.shift({3, 4, 0}, pair);
                std::vector<int> hit(n, 0);
                for (uint32_t i = 0; i < n; ++i) {
                    const Vec2 v = s.get_2d({3, 4, i}, pair);
                    // Undo the shift in y to find the lattice index j, then check x.
                    const double y = frac(v.y - t.y);
                    const auto j = static_cast<uint32_t>(std::lround(y * n - 0.5)) % n;
                    ++hit[j];
                    const LatticePoint p = fibonacci_lattice_point(j, n);
                    EXPECT_LT(circle_distance(v.y, p.y + t.y), 1e-6);
                    EXPECT_LT(circle_distance(v.x, p.x + t.x), 1e-6);
                }
                for (int h : hit) ASSERT_EQ(h, 1);
            }
        }
    }
}

TEST(FibonacciSampler, PointsOfAPairAreARankOneLattice) {
    // p_j = t + j·g mod 1 with g = (1/φ, 1/n): every difference p_a − p_b is k·g mod 1 for an
    // integer k in (−n, n); k mod n is read off the y difference, then k or k − n must give x.
    const double inv_phi = (std::sqrt(5.0) - 1.0) / 2.0;
    const uint32_t n = 32;
    const FibonacciSampler s({n, 8, 16, 16});
    std::vector<Vec2> pts;
    for (uint32_t i = 0; i < n; ++i) pts.push_back(s.get_2d({9, 1, i}, 10));
    for (uint32_t a = 0; a < n; ++a)
        for (uint32_t b = 0; b < n; ++b) {
            const double dy = frac(double(pts[a].y) - pts[b].y);
            const long k = std::lround(dy * n) % static_cast<long>(n);
            EXPECT_LT(circle_distance(dy, double(k) / n), 1e-6);
            const double dx = double(pts[a].x) - pts[b].x;
            const double err = std::min(circle_distance(dx, double(k) * inv_phi),
                                        circle_distance(dx, double(k - static_cast<long>(n)) * inv_phi));
            EXPECT_LT(err, 1e-5) << a << " " << b;
        }
}

TEST(FibonacciSampler, ShiftDiffersAcrossPixelsUnlessStatic) {
    const FibonacciSampler random_shift({16, 1, 8, 8});
    const StaticFibonacciSampler static_shift({16, 1, 8, 8});
    const LatticePoint r0 = random_shift.shift({0, 0, 0}, 4 + 4), s0 = static_shift.shift({0, 0, 0}, 8);
    int equal_random = 0;
    for (uint32_t p = 1; p < 64; ++p) {
        const PixelSample ps{p % 8, p / 8, 0};
        const LatticePoint r = random_shift.shift(ps, 8), t = static_shift.shift(ps, 8);
        equal_random += r.x == r0.x || r.y == r0.y;
        EXPECT_EQ(t.x, s0.x);
        EXPECT_EQ(t.y, s0.y);
        for (uint32_t i = 0; i < 16; ++i)  // static: the very same values in every pixel
            ASSERT_EQ(static_shift.get_1d(ps, 9), static_shift.get_1d({0, 0, 0}, 9));
    }
    EXPECT_EQ(equal_random, 0);
    // The static shift still differs between pairs, so the pairs are not copies of each other.
    EXPECT_NE(static_shift.shift({0, 0, 0}, 0).x, s0.x);
}

TEST(FibonacciSampler, PerPixelShiftIsUniformOnTheTorus) {
    // Shifts of N pixels: each coordinate U[0,1), mean 1/2 with standard error sqrt(1/12 / N);
    // correlation of the two coordinates has standard error 1/sqrt(N). Accept within 4.
    const FibonacciSampler s({8, 21, 64, 64});
    const int n = 4096;
    double sx = 0, sy = 0, sxy = 0;
    for (int p = 0; p < n; ++p) {
        const LatticePoint t = s.shift({static_cast<uint32_t>(p % 64), static_cast<uint32_t>(p / 64), 0}, 2);
        sx += t.x, sy += t.y, sxy += (t.x - 0.5) * (t.y - 0.5);
    }
    const double se = std::sqrt(1.0 / 12.0 / n);
    EXPECT_NEAR(sx / n, 0.5, 4 * se);
    EXPECT_NEAR(sy / n, 0.5, 4 * se);
    EXPECT_NEAR(sxy / n * 12.0, 0.0, 4.0 / std::sqrt(double(n)));
}

TEST(FibonacciSampler, OneDPairsAreShiftedCentredStrata) {
    // Dimensions of (time, unused), (light choice, roulette), ...: (π(i) + 0.5)/n + shift_d.
    const uint32_t n = 16;
    const FibonacciSampler s({n, 5, 4, 4});
    for (uint32_t d : {4u, 5u, 6u, 7u, 12u}) {
        ASSERT_TRUE(pair_holds_1d_quantities(d));
        std::vector<double> v;
        for (uint32_t i = 0; i < n; ++i) v.push_back(s.get_1d({2, 2, i}, d));
        // All pairwise gaps are multiples of 1/n on the circle and the n values are distinct.
        for (uint32_t a = 0; a < n; ++a)
            for (uint32_t b = a + 1; b < n; ++b) {
                const double gap = frac(v[a] - v[b]) * n;
                EXPECT_NEAR(gap, std::round(gap), 1e-4);
                EXPECT_GT(circle_distance(v[a], v[b]), 0.5 / n);
            }
    }
}
