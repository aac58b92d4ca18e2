// Path guiding's mixture at one vertex (integrators/guided_direction.h), issue 17 acceptance 4:
// at a point of a trained tree, the mixed density p_mix = f p_bsdf + (1 − f) p_guide integrates
// to 1 over the sphere, the directions sample_guided() draws follow it (Pearson chi-square over
// equal-solid-angle bins, fixed seed, plus one bin for the draws that end the path), and each
// weight is the closures' value / p_mix. The tree is trained on records of a synthetic light
// field (radiance 100 within 20° of one direction, 1 elsewhere), as in test_guiding_tree.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "bsdf/closure_set.h"
#include "chi_square.h"
#include "integrators/guided_direction.h"
#include "stratum/stratum.h"

namespace stratum {
namespace {

constexpr double kPiD = 3.141592653589793;

Material make(int32_t model, Rgb c, float roughness, float ior = 1.5f) {
    return {model, c, roughness, 0.0f, 0.5f, ior, Rgb(), MicrofacetDistribution::Ggx};
}

GuidingTree trained_tree() {
    const Vec3 bright = normalize(Vec3(0.3f, -0.5f, 0.8f));
    GuidingTree tree(Vec3(0, 0, 0), 1.0f);
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(0.0f, 1.0f), p(-0.4f, 0.4f);
    for (int pass = 0; pass < 6; ++pass) {
        for (int k = 0; k < 20000; ++k) {
            const Vec3 d = GuidingTree::st_to_direction(u(rng), u(rng));
            tree.record(Vec3(p(rng), p(rng), p(rng)), d, dot(d, bright) > 0.9396926f ? 100.0f : 1.0f);
        }
        tree.update();
    }
    return tree;
}

struct Case {
    const char* label;
    SceneMaterial material;
    float bsdf_fraction;
    bool closures_always_draw;  // the closures' pdf integrates to 1 (no failed draws)
};

// Equal-solid-angle bins of the local sphere: kZ bands of cos θ × kPhi sectors.
constexpr int kZ = 16, kPhi = 32, kSub = 48;  // each bin integrated on a kSub² midpoint grid
int bin_of(Vec3 d) {
    const int z = std::min(kZ - 1, static_cast<int>((d.z + 1.0f) * 0.5f * kZ));
    double phi = std::atan2(d.y, d.x);
    if (phi < 0) phi += 2 * kPiD;
    const int s = std::min(kPhi - 1, static_cast<int>(phi / (2 * kPiD) * kPhi));
    return z * kPhi + s;
}

}  // namespace

TEST(GuidedDirection, MixedPdfIntegratesToOneAndMatchesItsSamples) {
    const GuidingTree tree = trained_tree();
    const Vec3 normal = normalize(Vec3(0.2f, -0.3f, 0.9f));
    const Frame frame = Frame::from_normal(normal);
    const Vec3 wo = normalize(Vec3(0.3f, 0.1f, 0.8f));  // local
    const Case cases[] = {
        {"lambert, f 0.5", SceneMaterial{{{Rgb(1.0f), make(STRATUM_MATERIAL_DIFFUSE, Rgb(0.8f), 0.0f)}}},
         0.5f, true},
        {"lambert + glossy 0.3, f 0.2",
         SceneMaterial{{{Rgb(0.5f), make(STRATUM_MATERIAL_DIFFUSE, Rgb(0.8f), 0.0f)},
                        {Rgb(0.5f), make(STRATUM_MATERIAL_GLOSSY, Rgb(1.0f), 0.3f)}}},
         0.2f, false},
        {"rough glass 0.5, f 0.7",
         SceneMaterial{{{Rgb(1.0f), make(STRATUM_MATERIAL_GLASS, Rgb(1.0f), 0.5f)}}}, 0.7f, false},
    };
    constexpr int kSamples = 400000;
    for (const Case& c : cases) {
        ClosureSet closures(c.material);
        const GuidedVertex guide{&tree, tree.region(Vec3(0.05f, -0.1f, 0.1f)), c.bsdf_fraction, frame};
        // Expected mass per bin: p_mix where the closures scatter; the rest (directions whose
        // value is 0 and the closures' own failed draws) is the last bin, the draws that end the path.
        std::vector<double> expected(kZ * kPhi + 1, 0.0), observed(kZ * kPhi + 1, 0.0);
        double mixed_integral = 0.0, scattered_mass = 0.0;
        const double cell = 4.0 * kPiD / (double(kZ) * kSub * kPhi * kSub);
        for (int i = 0; i < kZ * kSub; ++i)
            for (int j = 0; j < kPhi * kSub; ++j) {
                const double z = -1.0 + 2.0 * (i + 0.5) / (kZ * kSub),
                             phi = 2 * kPiD * (j + 0.5) / (kPhi * kSub);
                const double r = std::sqrt(1.0 - z * z);
                const Vec3 wi(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z));
                const BsdfEval e = closures.eval(wo, wi, HemisphereDistribution::Cosine);
                const double p = guide.mixed_pdf(e.pdf, frame.to_world(wi));
                mixed_integral += p * cell;
                if (!e.value.is_black()) {
                    expected[bin_of(wi)] += p * cell;
                    scattered_mass += p * cell;
                }
            }
        // p_mix = f p_bsdf + (1 − f) p_guide: the guide's part is exactly 1 − f; the closures'
        // pdf integrates to at most 1 (a GGX draw below the horizon is a failure, not a direction).
        // Midpoint rule on 768 × 1536 cells: its error on these smooth lobes and the tree's
        // cell edges is below 2e-3 (measured with twice the grid: the sums agree to 3e-4).
        if (c.closures_always_draw) {
            EXPECT_NEAR(mixed_integral, 1.0, 2e-3) << c.label;
        }
        EXPECT_LE(mixed_integral, 1.0 + 2e-3) << c.label;
        expected.back() = 1.0 - scattered_mass;
        for (double& e : expected) e *= kSamples;
        std::mt19937 rng(2024);
        std::uniform_real_distribution<float> u(0.0f, 1.0f);
        int bad_weights = 0;
        for (int k = 0; k < kSamples; ++k) {
            BsdfSample bs;
            const float u_choice = u(rng), u_lobe = u(rng);
            const Vec2 uv{u(rng), u(rng)};
            if (!sample_guided(closures, wo, guide, u_choice, u_lobe, uv, &bs,
                               HemisphereDistribution::Cosine)) {
                observed.back() += 1;
                continue;
            }
            ASSERT_FALSE(bs.delta) << c.label;
            observed[bin_of(bs.wi)] += 1;
            // weight = value / p_mix, with p_mix as mixed_pdf() gives it.
            const BsdfEval e = closures.eval(wo, bs.wi, HemisphereDistribution::Cosine);
            const float p = guide.mixed_pdf(e.pdf, frame.to_world(bs.wi));
            if (std::abs(bs.pdf - p) > 1e-3f * p ||
                std::abs(bs.weight.g - e.value.g / p) > 1e-3f * e.value.g / p)
                ++bad_weights;
        }
        // A direction on a tree cell's edge may fall on either side after the world round trip.
        EXPECT_LE(bad_weights, kSamples / 10000) << c.label;
        const chi_square::ChiSquare r = chi_square::pearson(observed, expected);
        EXPECT_GT(r.p_value, 0.01 / 3) << c.label << ": chi2 " << r.statistic << " dof " << r.dof;
    }
}

TEST(GuidedDirection, DeltaDirectionsAreDrawnByTheClosuresAlone) {
    // A transparent closure's straight-through direction only the closures draw, with
    // probability f × its pick: its weight is divided by f.
    const GuidingTree tree = trained_tree();
    const Frame frame = Frame::from_normal(Vec3(0, 0, 1));
    const SceneMaterial material{{{Rgb(0.5f), make(STRATUM_MATERIAL_DIFFUSE, Rgb(0.8f), 0.0f)},
                                  {Rgb(0.5f), make(STRATUM_MATERIAL_TRANSPARENT, Rgb(1.0f), 0.0f)}}};
    ClosureSet closures(material);
    const GuidedVertex guide{&tree, tree.region(Vec3(0, 0, 0)), 0.25f, frame};
    const Vec3 wo = normalize(Vec3(0.1f, 0.2f, 0.9f));
    std::mt19937 rng(1);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    double delta_weight = 0.0;
    constexpr int kSamples = 100000;
    for (int k = 0; k < kSamples; ++k) {
        BsdfSample bs;
        if (sample_guided(closures, wo, guide, u(rng), u(rng), Vec2{u(rng), u(rng)}, &bs,
                          HemisphereDistribution::Cosine) &&
            bs.delta)
            delta_weight += bs.weight.g;
    }
    // E[delta weight] = the transparent closure's weight 0.5 (× colour 1), whatever its pick
    // probability p_T: the draw is 0.5/(f p_T) with probability q = f p_T. With sample weights
    // 0.5·0.8 and 0.5·1, p_T = 5/9 and q = 0.139: variance 0.25 (1 − q)/q = 1.55, standard error
    // sqrt(1.55/N) = 3.9e-3 for N = 1e5; accept 5σ = 0.02.
    EXPECT_NEAR(delta_weight / kSamples, 0.5, 0.02);
}

}  // namespace stratum
