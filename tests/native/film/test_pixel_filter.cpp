// Pixel filter importance sampling: offsets follow the filter profile. The empirical CDF of N
// offsets is compared with the profile's CDF by a Kolmogorov–Smirnov test; at N = 2^16 the
// 0.1% critical value of the KS statistic is 1.95/√N.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "film/pixel_filter.h"

using namespace stratum;

namespace {

// Closed-form CDF of the Blackman-Harris window on [−R, R].
double blackman_harris_cdf(double x, double R) {
    const double a0 = 0.35875, a1 = 0.48829, a2 = 0.14128, a3 = 0.01168, pi = 3.14159265358979323846;
    const auto integral = [&](double t) {
        const double k = 2 * pi / (2 * R);  // θ = k t + π
        return a0 * t - a1 * std::sin(k * t + pi) / k + a2 * std::sin(2 * (k * t + pi)) / (2 * k) -
               a3 * std::sin(3 * (k * t + pi)) / (3 * k);
    };
    return (integral(x) - integral(-R)) / (integral(R) - integral(-R));
}

double ks_statistic(std::vector<double> xs, double (*cdf)(double, double), double R) {
    std::sort(xs.begin(), xs.end());
    double d = 0;
    const double n = static_cast<double>(xs.size());
    for (size_t i = 0; i < xs.size(); ++i) {
        const double f = cdf(xs[i], R);
        d = std::max(
            {d, std::abs(f - static_cast<double>(i) / n), std::abs(f - static_cast<double>(i + 1) / n)});
    }
    return d;
}

double box_cdf(double x, double R) { return (x + R) / (2 * R); }

std::vector<double> offsets(const PixelFilter& f, int n) {
    std::vector<double> xs;
    for (int i = 0; i < n; ++i) {
        // Stratified u: the filter map itself is tested, not a random generator.
        const float u = (static_cast<float>(i) + 0.5f) / static_cast<float>(n);
        xs.push_back(f.sample(Vec2{u, 0.5f}).x);
    }
    return xs;
}

}  // namespace

TEST(PixelFilter, BoxCoversHalfTheWidthEachSide) {
    const PixelFilter f(FilterType::Box, 1.0f);
    EXPECT_FLOAT_EQ(f.radius(), 0.5f);
    const auto xs = offsets(f, 1 << 16);
    EXPECT_LT(ks_statistic(xs, box_cdf, 0.5), 1.95 / 256.0);
    EXPECT_GE(*std::min_element(xs.begin(), xs.end()), -0.5);
    EXPECT_LE(*std::max_element(xs.begin(), xs.end()), 0.5);
}

TEST(PixelFilter, BlackmanHarrisFollowsItsWindowOverTwiceTheWidth) {
    // Cycles samples Blackman-Harris over a support of twice filter_width: radius = width.
    const PixelFilter f(FilterType::BlackmanHarris, 1.5f);
    EXPECT_FLOAT_EQ(f.radius(), 1.5f);
    const auto xs = offsets(f, 1 << 16);
    EXPECT_LT(ks_statistic(xs, blackman_harris_cdf, 1.5), 1.95 / 256.0);
    // And it is not the box: the KS distance to a uniform law is large.
    EXPECT_GT(ks_statistic(xs, box_cdf, 1.5), 0.1);
}

TEST(PixelFilter, RegistryNamesParse) {
    FilterType t;
    EXPECT_TRUE(parse_filter_type("box", &t));
    EXPECT_EQ(t, FilterType::Box);
    EXPECT_TRUE(parse_filter_type("blackman_harris", &t));
    EXPECT_EQ(t, FilterType::BlackmanHarris);
    EXPECT_FALSE(parse_filter_type("gaussian", &t));
    EXPECT_EQ(filter_registry().size(), 2u);
}
