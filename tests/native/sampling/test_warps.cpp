// Warps against their densities. Each direction warp is checked by a chi-square goodness-of-fit
// test: bins in (theta, phi) over the whole sphere, theta edges at quantiles of the warp's own
// density (so expected counts are roughly equal), expected counts integrated from the density
// (midpoint rule in (theta, phi), where p sin(theta) is smooth for every warp here), bins with
// an expected count below 5 pooled, samples outside the support counted against zero mass.
//
// Significance: the file runs kChiSquareTests tests; to keep the chance of any false failure at
// alpha = 1% we reject each at alpha / kChiSquareTests (Bonferroni: P(any) <= sum of P(each)).
// Seeds are fixed, so a run is reproducible; the threshold says how surprising a failure is.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "chi_square.h"
#include "sampling/warps.h"

namespace stratum {
namespace {

constexpr int kChiSquareTests = 12;
constexpr double kSignificance = 0.01 / kChiSquareTests;
constexpr int kSampleCount = 1'000'000;

using chi_square::ChiSquare;
using chi_square::pearson;

// Warps take no lobe choice: the shared test's u_lobe is ignored.
ChiSquare chi_square_directions(const std::function<bool(Vec2, Vec3*)>& sample,
                                const chi_square::DirectionDensity& density, uint64_t seed) {
    return chi_square::chi_square_directions([&](Vec2 u, float, Vec3* w) { return sample(u, w); }, density,
                                             seed, kSampleCount, 512, 200);
}

void expect_fits(const ChiSquare& r, double expected_mass = 1.0) {
    EXPECT_GT(r.p_value, kSignificance) << "chi2 = " << r.statistic << ", dof = " << r.dof;
    // Midpoint rule on pi/512 theta rows: exact to ~1e-5 for smooth densities, but a density
    // with a jump (the cone's rim) misplaces up to half a row of mass, ~3e-3 for the caps here.
    EXPECT_NEAR(r.density_mass, expected_mass, 5e-3);
}

TEST(Warps, CosineHemisphere) {
    expect_fits(chi_square_directions(
        [](Vec2 u, Vec3* w) {
            *w = sample_cosine_hemisphere(u);
            return true;
        },
        [](Vec3 w) { return cosine_hemisphere_pdf(w.z); }, 1));
}

TEST(Warps, ConcentricDiskLiftsToCosineHemisphere) {
    // Malley: the disk is uniform iff its lift (x, y, sqrt(1 - r^2)) has density cos/pi.
    expect_fits(chi_square_directions(
        [](Vec2 u, Vec3* w) {
            const Vec2 d = sample_uniform_disk_concentric(u);
            const float r2 = d.x * d.x + d.y * d.y;
            if (r2 > 1.0f + 1e-6f) return false;
            *w = Vec3(d.x, d.y, safe_sqrt(1.0f - r2));
            return true;
        },
        [](Vec3 w) { return cosine_hemisphere_pdf(w.z); }, 2));
}

TEST(Warps, UniformHemisphere) {
    expect_fits(chi_square_directions(
        [](Vec2 u, Vec3* w) {
            *w = sample_uniform_hemisphere(u);
            return true;
        },
        [](Vec3 w) { return w.z >= 0 ? uniform_hemisphere_pdf() : 0.0f; }, 3));
}

TEST(Warps, UniformAnglesHemisphere) {
    expect_fits(chi_square_directions(
        [](Vec2 u, Vec3* w) {
            *w = sample_uniform_angles_hemisphere(u);
            return true;
        },
        [](Vec3 w) { return uniform_angles_hemisphere_pdf(w.z); }, 4));
}

TEST(Warps, UniformSphere) {
    expect_fits(chi_square_directions(
        [](Vec2 u, Vec3* w) {
            *w = sample_uniform_sphere(u);
            return true;
        },
        [](Vec3) { return uniform_sphere_pdf(); }, 5));
}

TEST(Warps, UniformCone) {
    for (const float cos_max : {0.8f, -0.3f}) {
        expect_fits(chi_square_directions(
            [cos_max](Vec2 u, Vec3* w) {
                *w = sample_uniform_cone(u, cos_max);
                return true;
            },
            [cos_max](Vec3 w) { return uniform_cone_pdf(w.z, cos_max); }, 6));
    }
}

TEST(Warps, GgxVisibleNormals) {
    // D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z with the GGX D and Smith G1 (Heitz 2018, eq. 3).
    struct Case {
        float alpha, theta_o;
    };
    for (const Case c : {Case{0.3f, 1.05f}, Case{1.0f, 0.2f}, Case{0.1f, 1.4f}}) {
        const Vec3 wo(std::sin(c.theta_o), 0.0f, std::cos(c.theta_o));
        const auto d = [&](Vec3 h) {
            if (h.z <= 0) return 0.0f;
            const float a2 = c.alpha * c.alpha, t = h.z * h.z * (a2 - 1) + 1;
            return a2 / (kPi * t * t);
        };
        const float tan2 = (1 - wo.z * wo.z) / (wo.z * wo.z);
        const float g1 = 2.0f / (1.0f + std::sqrt(1.0f + c.alpha * c.alpha * tan2));
        expect_fits(chi_square_directions(
            [&](Vec2 u, Vec3* h) {
                *h = sample_ggx_visible_normal(wo, c.alpha, u);
                return true;
            },
            [&](Vec3 h) { return g1 * std::max(dot(wo, h), 0.0f) * d(h) / wo.z; }, 7));
    }
}

TEST(Warps, UniformTriangleBarycentrics) {
    // Bins on the (b1, b2) unit square; expected mass = area(bin within b1 + b2 <= 1) / (1/2).
    constexpr int kGrid = 20, kSteps = 2000;
    std::vector<double> expected(kGrid * kGrid + 1, 0.0), observed(kGrid * kGrid + 1, 0.0);
    for (int i = 0; i < kGrid; ++i) {
        for (int j = 0; j < kGrid; ++j) {
            const double x0 = double(i) / kGrid, y0 = double(j) / kGrid, h = 1.0 / kGrid;
            double area = 0;
            for (int s = 0; s < kSteps; ++s) {
                const double x = x0 + (s + 0.5) * h / kSteps;
                area += std::clamp(1.0 - x - y0, 0.0, h) * h / kSteps;
            }
            expected[i * kGrid + j] = 2.0 * area * kSampleCount;
        }
    }
    std::mt19937_64 rng(8);
    std::uniform_real_distribution<float> uniform(0.0f, kOneMinusEpsilon);
    for (int s = 0; s < kSampleCount; ++s) {
        const Vec3 b = sample_uniform_triangle({uniform(rng), uniform(rng)});
        ASSERT_NEAR(b.x + b.y + b.z, 1.0f, 1e-6f);
        ASSERT_GE(b.x, -1e-6f);
        const int i = std::min(int(b.y * kGrid), kGrid - 1), j = std::min(int(b.z * kGrid), kGrid - 1);
        observed[i * kGrid + j] += 1;
    }
    const ChiSquare r = pearson(observed, expected);
    EXPECT_GT(r.p_value, kSignificance) << "chi2 = " << r.statistic << ", dof = " << r.dof;
}

// The bilinear warp on a 16 × 16 grid of cells of the unit square. A bilinear function's mean
// over a cell is its value at the cell's centre (it is linear in each variable), so the expected
// count of a cell is N · pdf(centre) / 256 exactly. Two weight sets: skewed, and one corner 0.
TEST(Warps, BilinearMatchesItsDensity) {
    constexpr int kGrid = 16;
    const BilinearWeights cases[] = {{{0.1f, 1.0f, 2.0f, 0.5f}}, {{0.0f, 0.3f, 0.3f, 1.0f}}};
    uint64_t seed = 21;
    for (const BilinearWeights& w : cases) {
        std::vector<double> expected(kGrid * kGrid), observed(kGrid * kGrid, 0.0);
        for (int i = 0; i < kGrid; ++i)
            for (int j = 0; j < kGrid; ++j)
                expected[i * kGrid + j] =
                    kSampleCount * bilinear_pdf({(float(i) + 0.5f) / kGrid, (float(j) + 0.5f) / kGrid}, w) /
                    (kGrid * kGrid);
        std::mt19937_64 rng(seed++);
        std::uniform_real_distribution<float> uniform(0.0f, kOneMinusEpsilon);
        for (int s = 0; s < kSampleCount; ++s) {
            const Vec2 p = sample_bilinear({uniform(rng), uniform(rng)}, w);
            ASSERT_TRUE(p.x >= 0.0f && p.x < 1.0f && p.y >= 0.0f && p.y < 1.0f) << p.x << ", " << p.y;
            observed[int(p.x * kGrid) * kGrid + int(p.y * kGrid)] += 1;
        }
        const ChiSquare r = pearson(observed, expected);
        EXPECT_GT(r.p_value, kSignificance) << "chi2 = " << r.statistic << ", dof = " << r.dof;
    }
    // Equal weights: the identity, density 1.
    const BilinearWeights flat{{2.0f, 2.0f, 2.0f, 2.0f}};
    const Vec2 u{0.3f, 0.7f};
    EXPECT_NEAR(sample_bilinear(u, flat).x, u.x, 1e-6f);
    EXPECT_NEAR(sample_bilinear(u, flat).y, u.y, 1e-6f);
    EXPECT_FLOAT_EQ(bilinear_pdf(u, flat), 1.0f);
    // A zero corner: u = 0 maps to that corner (not to 0/0).
    const Vec2 corner = sample_bilinear({0.0f, 0.0f}, cases[1]);
    EXPECT_EQ(corner.x, 0.0f);
    EXPECT_EQ(corner.y, 0.0f);
}

TEST(Warps, ChiSquareRejectsAWrongDensity) {
    // The test must have power: uniform hemisphere samples do not fit the cosine density.
    const ChiSquare r = chi_square_directions(
        [](Vec2 u, Vec3* w) {
            *w = sample_uniform_hemisphere(u);
            return true;
        },
        [](Vec3 w) { return cosine_hemisphere_pdf(w.z); }, 9);
    EXPECT_LT(r.p_value, 1e-12);
}

TEST(Warps, PdfFunctionsMatchTheirClosedForms) {
    EXPECT_FLOAT_EQ(cosine_hemisphere_pdf(0.5f), 0.5f / kPi);
    EXPECT_FLOAT_EQ(cosine_hemisphere_pdf(-0.5f), 0.0f);
    EXPECT_FLOAT_EQ(uniform_angles_hemisphere_pdf(0.0f), 1.0f / (kPi * kPi));
    EXPECT_FLOAT_EQ(uniform_cone_pdf(0.9f, 0.8f), 1.0f / (2.0f * kPi * 0.2f));
    EXPECT_FLOAT_EQ(uniform_cone_pdf(0.7f, 0.8f), 0.0f);
}

}  // namespace
}  // namespace stratum
