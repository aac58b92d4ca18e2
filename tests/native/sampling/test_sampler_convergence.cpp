// Acceptance: how fast each sampler's error falls (research/samplers.md §4, "Measured MSE
// slopes"). For 2D integrands over [0,1)² with known integrals, the estimate from one pixel's
// N samples of a dimension pair is repeated R = 8 seeds × 16 pixels = 128 times for
// N = 16, 32, ..., 4096 (a sampler built with samples = N each time, as a render would), its
// MSE taken per N, and the least-squares slope of ln MSE against ln N reported.
//
// Integrands (asymmetric and non-periodic, as §4 advises; a centred Gaussian gave misleading
// slopes):
//   smooth  exp(x·y):            ∫∫ e^{xy} = Σ_k ∫∫ (xy)^k / k! = Σ_k 1 / (k! (k+1)²)
//   disk    (x−0.5)² + (y−0.45)² < 0.3²: inside the square, so the area is π·0.09
//   edge    y < 0.3 + 0.4·x:     ∫_0^1 (0.3 + 0.4x) dx = 0.5
// Pairs: the first camera pair (dims 0, 1) and a deep one, bounce_dimension(1,
// kDimBsdfDirection) = (18, 19), where Halton-type samplers use large bases (pitfall 2).
//
// Noise of the fitted slope: with R = 128 repetitions the relative standard error of each MSE
// is about √(2/R) = 0.125 (more with heavy tails), i.e. ±0.125 in ln MSE; over 9 points spaced
// ln 2 apart the least-squares slope then has a standard error ≈ 0.125 / √(Σ(x − x̄)²) =
// 0.125 / 5.4 ≈ 0.025, so a ±0.15 band is ≥ 6 standard errors wide.
//
// Expectations (kExpectations; each from §4's measurements, with margin):
//   random, lcg, lhs  slope −1 ± 0.15 on every integrand and both pairs (independent-like: any
//                     flatter rate betrays correlated streams, §5.1);
//   sobol             ≤ −2.4 smooth (Owen-scrambled nets: −2.8 measured), ≤ −1.35 on both
//                     discontinuous ones (−1.5) — on the first pair;
//   halton_owen, halton_rd, stratified   ≤ −1.35 on the discontinuous ones, first pair.
// The deep pair is asserted only for the independent-like samplers: for Halton in bases 67 and
// 71 the 2D strata need N ≫ 67·71, so a flatter slope over N ≤ 4096 is the method's known
// weakness, not a defect; its slopes are printed. Other samplers (halton, zsobol, bluenoise,
// fibonacci, fibonacci_static) are printed without assertions.
//
// A name in kExpectations that is not registered is a failure: the expectations are part of
// the sampler's contract.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "sampling/dimensions.h"
#include "sampling/sampler_registry.h"

using namespace stratum;

namespace {

constexpr double kNoBound = 1e9;
struct Expectation {
    const char* name;
    // Per integrand (smooth, disk, edge): slope must lie in [lo, hi] on the first pair.
    double lo[3], hi[3];
    bool deep_pair_too;  // the same bounds on the deep pair
};

constexpr Expectation kExpectations[] = {
    {"random", {-1.15, -1.15, -1.15}, {-0.85, -0.85, -0.85}, true},
    {"lcg", {-1.15, -1.15, -1.15}, {-0.85, -0.85, -0.85}, true},
    {"lhs", {-1.15, -1.15, -1.15}, {-0.85, -0.85, -0.85}, true},
    {"sobol", {-kNoBound, -kNoBound, -kNoBound}, {-2.4, -1.35, -1.35}, false},
    {"halton_owen", {-kNoBound, -kNoBound, -kNoBound}, {kNoBound, -1.35, -1.35}, false},
    {"halton_rd", {-kNoBound, -kNoBound, -kNoBound}, {kNoBound, -1.35, -1.35}, false},
    {"stratified", {-kNoBound, -kNoBound, -kNoBound}, {kNoBound, -1.35, -1.35}, false},
};

struct Integrand {
    const char* name;
    double (*f)(double, double);
    double integral;
};

double exp_xy_integral() {
    double sum = 0, factorial = 1;
    for (int k = 0; k < 30; ++k) {
        if (k > 0) factorial *= k;
        sum += 1.0 / (factorial * (k + 1.0) * (k + 1.0));
    }
    return sum;
}

const Integrand kIntegrands[] = {
    {"exp(xy)", [](double x, double y) { return std::exp(x * y); }, exp_xy_integral()},
    {"disk",
     [](double x, double y) { return (x - 0.5) * (x - 0.5) + (y - 0.45) * (y - 0.45) < 0.09 ? 1.0 : 0.0; },
     3.14159265358979323846 * 0.09},
    {"edge", [](double x, double y) { return y < 0.3 + 0.4 * x ? 1.0 : 0.0; }, 0.5},
};

constexpr uint32_t kPairs[] = {0, bounce_dimension(1, kDimBsdfDirection)};
constexpr uint32_t kSeeds = 8, kPixelsPerSeed = 16, kImageSize = 16;
constexpr uint32_t kMinLog2N = 4, kMaxLog2N = 12;

// slopes[pair][integrand]
using Slopes = std::array<std::array<double, 3>, 2>;

Slopes measure_slopes(const SamplerEntry& entry) {
    constexpr uint32_t kCounts = kMaxLog2N - kMinLog2N + 1;
    // squared errors summed over repetitions: [pair][integrand][log2 N]
    double sq[2][3][kCounts] = {};
    for (uint32_t m = 0; m < kCounts; ++m) {
        const uint32_t n = 1u << (kMinLog2N + m);
        for (uint32_t seed = 0; seed < kSeeds; ++seed) {
            const auto sampler = entry.create({n, 1000 + seed, kImageSize, kImageSize});
            for (uint32_t k = 0; k < kPixelsPerSeed; ++k) {
                const uint32_t px = (5 * k) % kImageSize, py = (3 * k + seed) % kImageSize;
                for (size_t p = 0; p < 2; ++p) {
                    double sum[3] = {};
                    for (uint32_t i = 0; i < n; ++i) {
                        const Vec2 u = sampler->get_2d({px, py, i}, kPairs[p]);
                        for (size_t f = 0; f < 3; ++f) sum[f] += kIntegrands[f].f(u.x, u.y);
                    }
                    for (size_t f = 0; f < 3; ++f) {
                        const double e = sum[f] / n - kIntegrands[f].integral;
                        sq[p][f][m] += e * e;
                    }
                }
            }
        }
    }
    Slopes slopes{};
    for (size_t p = 0; p < 2; ++p) {
        for (size_t f = 0; f < 3; ++f) {
            double sx = 0, sy = 0, sxx = 0, sxy = 0;
            for (uint32_t m = 0; m < kCounts; ++m) {
                const double x = std::log(static_cast<double>(1u << (kMinLog2N + m)));
                // An exact estimate (MSE 0) would be log(0): floor it far below any real MSE.
                const double y = std::log(std::max(sq[p][f][m] / (kSeeds * kPixelsPerSeed), 1e-30));
                sx += x;
                sy += y;
                sxx += x * x;
                sxy += x * y;
            }
            slopes[p][f] = (kCounts * sxy - sx * sy) / (kCounts * sxx - sx * sx);
        }
    }
    return slopes;
}

// The table of every sampler measured in this process, printed at the end.
std::mutex g_table_mutex;
std::map<std::string, Slopes>& table() {
    static std::map<std::string, Slopes> t;
    return t;
}

class SlopeTablePrinter : public ::testing::Environment {
public:
    void TearDown() override {
        if (table().empty()) return;
        std::printf("\nMSE slope (ln MSE vs ln N, N = 16..4096, %u reps)\n", kSeeds * kPixelsPerSeed);
        std::printf("%-18s | %8s %8s %8s | %8s %8s %8s\n", "sampler", "exp(xy)", "disk", "edge", "exp 18",
                    "disk 18", "edge 18");
        for (const auto& [name, s] : table()) {
            std::printf("%-18s | %8.2f %8.2f %8.2f | %8.2f %8.2f %8.2f\n", name.c_str(), s[0][0], s[0][1],
                        s[0][2], s[1][0], s[1][1], s[1][2]);
        }
    }
};
[[maybe_unused]] ::testing::Environment* const g_printer =
    ::testing::AddGlobalTestEnvironment(new SlopeTablePrinter);

// Registered samplers plus any expected one that is missing (so that it fails by name).
std::vector<std::string> sampler_names() {
    std::vector<std::string> names;
    for (const SamplerEntry& e : sampler_registry()) names.emplace_back(e.info.name);
    for (const Expectation& e : kExpectations)
        if (std::find(names.begin(), names.end(), e.name) == names.end()) names.emplace_back(e.name);
    return names;
}

class Slope : public ::testing::TestWithParam<std::string> {};

TEST_P(Slope, MseFallsAtTheExpectedRate) {
    const std::string& name = GetParam();
    const SamplerEntry* entry = find_sampler(name);
    ASSERT_NE(entry, nullptr) << "sampler '" << name << "' is expected by kExpectations but not registered";
    const Slopes s = measure_slopes(*entry);
    {
        std::lock_guard lock(g_table_mutex);
        table()[name] = s;
    }
    std::printf("%-18s slopes  pair (0,1): %.2f %.2f %.2f   pair (%u,%u): %.2f %.2f %.2f\n", name.c_str(),
                s[0][0], s[0][1], s[0][2], kPairs[1], kPairs[1] + 1, s[1][0], s[1][1], s[1][2]);
    for (const Expectation& e : kExpectations) {
        if (name != e.name) continue;
        for (size_t p = 0; p < (e.deep_pair_too ? 2u : 1u); ++p) {
            for (size_t f = 0; f < 3; ++f) {
                EXPECT_GE(s[p][f], e.lo[f]) << name << ", " << kIntegrands[f].name << ", dims " << kPairs[p];
                EXPECT_LE(s[p][f], e.hi[f]) << name << ", " << kIntegrands[f].name << ", dims " << kPairs[p];
            }
        }
    }
}

INSTANTIATE_TEST_SUITE_P(SamplerConvergence, Slope, ::testing::ValuesIn(sampler_names()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

}  // namespace
