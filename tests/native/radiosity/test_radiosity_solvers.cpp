// The radiosity solvers (radiosity/radiosity_solvers.h) against the integrating spheres' closed
// forms (textbook §3.3; research/textbook.md §2.1 tests A and B) and against each other.
//
// Discretisation bound. The solution of M = b + κĜM on the sphere's patches is compared with
// the sphere's radiance patch by patch. The form-factor noise drops out wherever the mesh is
// closed: every ray from the inner side hits the mesh, so each row of Ĝ sums to exactly 1
// (test_radiosity_form_factors.cpp), and (ĜM)_i is a weighted mean of the M_j. Then
// (maximum principle) max M ≤ max b + κ max M and min M ≥ min b + κ min M, so every M_i lies
// in [min b, max b]/(1 − κ) whatever the noise in Ĝ:
// * sphere B (b = π L_e everywhere): M_i = π L_e/(1 − κ) exactly; only the solver's stopping
//   error and rounding remain: with tolerance 1e-7 the iterate is within the remaining
//   geometric tail (≤ ΔE ≤ 1e-7 L̄, L̄ ≤ L), and the double iterates are stored as float
//   (6e-8): we allow 1e-6 of L;
// * sphere A (point lamp at the centre, b_i = κ E_i): E_i is a mean of point irradiances
//   I d_p/|x|³ ∈ [I d_min, I/d_min²] (d_min the facets' least distance from the centre), and
//   the exact mean Φ/A_s lies in [I, I/d_min²], so |L_i/L_A − 1| ≤ ε = 1/d_min³ − 1 (as in
//   test_integrating_sphere_point_light.cpp), plus the solver's 1e-6;
// * a black port (rows sum to 1 − ĥ_i, ĥ_i the share of i's rays leaving through it): the same
//   principle gives L_e/(1 − κ(1 − ĥ_max)) ≤ L_i ≤ L_e/(1 − κ(1 − ĥ_min)), checked with the
//   measured ĥ; and ĥ_i estimates the port's form factor, within the facets' tilt (|F − h| ≤
//   0.005, render_helpers.h) plus 4.5 σ of N rays (σ² = h(1 − h)/N; the Sobol set does better),
//   which bounds |L_i − L_e/(1 − κ(1 − h))| through the same interval.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "radiosity/form_factors.h"
#include "radiosity/radiosity_solution.h"
#include "radiosity/radiosity_solvers.h"
#include "radiosity_scenes.h"

using namespace stratum_test;
using stratum::RadiositySettings;
using stratum::RadiositySolution;
using stratum::RadiositySolver;
using stratum::RenderScene;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr RadiositySolver kSolvers[] = {RadiositySolver::Jacobi, RadiositySolver::GaussSeidel,
                                        RadiositySolver::Shooting};
const char* name(RadiositySolver s) {
    return s == RadiositySolver::Jacobi ? "jacobi"
                                        : (s == RadiositySolver::GaussSeidel ? "gauss_seidel" : "shooting");
}

RadiositySettings settings(RadiositySolver solver, float patch_size, uint32_t rays, float tolerance = 1e-7f) {
    RadiositySettings s;
    s.solver = solver;
    s.patch_size = patch_size;
    s.rays = rays;
    s.tolerance = tolerance;
    return s;
}

bool inner(const stratum::Patch& p) { return stratum::dot(p.normal, p.centroid()) < 0.0f; }

}  // namespace

TEST(RadiositySolvers, SphereBIsEmissionOverOneMinusAlbedo) {
    const PortedSphereMesh sphere = make_ported_sphere(24, 0);
    const stratum::Scene scene = sphere_scene(sphere, 0.8f, 1.0f);
    const RenderScene rs(scene);
    const double expected = 1.0 / (1.0 - 0.8);
    for (const RadiositySolver solver : kSolvers) {
        const RadiositySolution solution(rs, settings(solver, 0.2f, 256), nullptr);
        ASSERT_TRUE(solution.report().converged) << name(solver);
        double worst = 0.0;
        for (uint32_t i = 0; i < solution.patches().size(); ++i) {
            if (!inner(solution.patches().patch(i))) continue;
            worst = std::max(worst, std::abs(solution.exitance(i).r / kPi - expected) / expected);
        }
        std::printf("sphere B, %s: K = %u, %zu iterations, worst |L/L_B - 1| = %.2e\n", name(solver),
                    solution.patches().size(), solution.report().iterations.size(), worst);
        EXPECT_LT(worst, 1e-6) << name(solver);
    }
}

// The early stop (radiosity_system.h, record_iteration) must not cut short a solve that
// converges slowly but within the cap: sphere B at κ = 0.99 contracts by 0.99 per Jacobi sweep,
// so tolerance 1e-4 takes about ln(1e-4)/ln(0.99) ≈ 920 sweeps of the cap's 10,000. Its answer
// is then within the geometric tail ΔE ≤ 1e-4 L̄ of L_e/(1 − κ) = 100, plus the float storage
// of M (6e-8): we allow 2e-4.
TEST(RadiositySolvers, ANearlyWhiteSphereConvergesSlowlyWithoutStoppingEarly) {
    const PortedSphereMesh sphere = make_ported_sphere(8, 0);
    const stratum::Scene scene = sphere_scene(sphere, 0.99f, 1.0f);
    const RenderScene rs(scene);
    const RadiositySolution solution(rs, settings(RadiositySolver::Jacobi, 0.5f, 64, 1e-4f), nullptr);
    const size_t iterations = solution.report().iterations.size();
    std::printf("sphere B at 0.99: K = %u, %zu iterations\n", solution.patches().size(), iterations);
    ASSERT_TRUE(solution.report().converged) << iterations << " iterations";
    EXPECT_GT(iterations, 500u);
    const double expected = 1.0 / (1.0 - 0.99);
    for (uint32_t i = 0; i < solution.patches().size(); ++i) {
        if (!inner(solution.patches().patch(i))) continue;
        EXPECT_NEAR(solution.exitance(i).r / kPi / expected, 1.0, 2e-4) << "patch " << i;
    }
}

TEST(RadiositySolvers, SphereAIsTextbook317WithinTheTessellationBound) {
    const PortedSphereMesh sphere = make_ported_sphere(32, 0);
    stratum::Scene scene = sphere_scene(sphere, 0.8f);
    stratum::LightParams lamp;
    lamp.type = STRATUM_LIGHT_POINT;
    lamp.strength = static_cast<float>(4.0 * kPi);  // Φ = 4π W: intensity 1 W/sr
    scene.lights.push_back(lamp);
    const RenderScene rs(scene);
    const double d = sphere.min_plane_distance, epsilon = 1.0 / (d * d * d) - 1.0;
    const double expected = sphere_a_radiance(4.0 * kPi, sphere.total_area(), 0.8, 0.0, 100000);
    for (const RadiositySolver solver : kSolvers) {
        const RadiositySolution solution(rs, settings(solver, 0.3f, 256), nullptr);
        ASSERT_TRUE(solution.report().converged) << name(solver);
        double worst = 0.0;
        for (uint32_t i = 0; i < solution.patches().size(); ++i) {
            if (!inner(solution.patches().patch(i))) continue;
            worst = std::max(worst, std::abs(solution.exitance(i).r / kPi - expected) / expected);
        }
        std::printf(
            "sphere A, %s: K = %u, worst |L/L_A - 1| = %.2e, bound eps = %.2e (form factors %.2f s, solve "
            "%.3f s)\n",
            name(solver), solution.patches().size(), worst, epsilon, solution.report().form_factor_seconds,
            solution.report().solve_seconds);
        EXPECT_LT(worst, epsilon + 1e-6) << name(solver);
    }
}

TEST(RadiositySolvers, PortedSphereBStaysInsideTheFormFactorBound) {
    const PortedSphereMesh sphere = make_ported_sphere(24, 5);
    const double h = sphere.port_fraction(), k = 0.5;
    const stratum::Scene scene = sphere_scene(sphere, static_cast<float>(k), 1.0f);
    const RenderScene rs(scene);
    constexpr uint32_t kRays = 4096;
    const stratum::PatchSet patches(rs, 1.0f, nullptr);
    stratum::FormFactors f = stratum::estimate_form_factors(rs, patches, kRays, nullptr);
    // The system as RadiositySolution builds it (no lamp, black background: b = M_e = π L_e).
    stratum::RadiositySystem system;
    for (uint32_t i = 0; i < patches.size(); ++i) {
        system.area.push_back(patches.patch(i).area);
        system.albedo.push_back(patches.albedo(i));
        system.source.push_back(stratum::DoubleRgb(patches.emission(i)));
    }
    system.shoot = f.gather.transposed();
    system.gather = std::move(f.gather);
    double h_min = 1.0, h_max = 0.0;
    for (uint32_t i = 0; i < patches.size(); ++i) {
        if (!inner(patches.patch(i))) continue;
        double row = 0.0;
        for (const stratum::SparseEntry& e : system.gather.row(i)) row += e.value;
        h_min = std::min(h_min, 1.0 - row);
        h_max = std::max(h_max, 1.0 - row);
    }
    const double delta = 0.005 + 4.5 * std::sqrt(h * (1.0 - h) / kRays);
    EXPECT_GE(h_min, h - delta);
    EXPECT_LE(h_max, h + delta);
    stratum::SolveOptions options;
    options.tolerance = 1e-7;
    for (const RadiositySolver solver : kSolvers) {
        const stratum::RadiositySolve solve = stratum::solve_radiosity(solver, system, options);
        ASSERT_TRUE(solve.converged) << name(solver);
        double l_min = 1e30, l_max = 0.0;
        for (uint32_t i = 0; i < patches.size(); ++i) {
            if (!inner(patches.patch(i))) continue;
            l_min = std::min(l_min, solve.exitance[i].r / kPi);
            l_max = std::max(l_max, solve.exitance[i].r / kPi);
        }
        const double slack = 1e-6;
        EXPECT_GE(l_min, (1.0 - slack) / (1.0 - k * (1.0 - h_max))) << name(solver);
        EXPECT_LE(l_max, (1.0 + slack) / (1.0 - k * (1.0 - h_min))) << name(solver);
        std::printf(
            "ported sphere B, %s: h = %.4f, h^ in [%.4f, %.4f]; L in [%.4f, %.4f], closed form %.4f, "
            "bound [%.4f, %.4f]\n",
            name(solver), h, h_min, h_max, l_min, l_max, 1.0 / (1.0 - k * (1.0 - h)),
            1.0 / (1.0 - k * (1.0 - h - delta)), 1.0 / (1.0 - k * (1.0 - h + delta)));
    }
}

// The three solvers solve one system (shooting reads the transpose of the gathering rows), so
// they agree to their tolerance on a scene with colour, occlusion and an emitter; and each
// iteration's report holds the book's ΔE and the residual, both falling to the tolerance.
TEST(RadiositySolvers, JacobiGaussSeidelAndShootingAgreeOnTheCornellBox) {
    const stratum::Scene scene = cornell_scene();
    const RenderScene rs(scene);
    std::vector<RadiositySolution> solutions;
    for (const RadiositySolver solver : kSolvers) {
        solutions.emplace_back(rs, settings(solver, 0.25f, 256, 1e-6f), nullptr);
        const auto& report = solutions.back().report();
        ASSERT_TRUE(report.converged) << name(solver);
        const auto& its = report.iterations;
        ASSERT_GE(its.size(), 2u);
        std::printf("%-12s K = %llu, %zu iterations, last dE %.2e (relative %.2e), residual %.2e, %.3f s\n",
                    name(solver), static_cast<unsigned long long>(report.patches), its.size(),
                    its.back().delta_e, its.back().relative, its.back().residual, report.solve_seconds);
        EXPECT_LE(its.back().relative, 1e-6);
        // The residual falls with ΔE (for Jacobi it is the next iteration's change): at the end
        // within a few ΔE of zero, far below its start.
        const double mean_radiance = its.back().delta_e / its.back().relative;
        EXPECT_LT(its.back().residual, 1e-5 * mean_radiance) << name(solver);
        EXPECT_LT(its.back().residual, 1e-3 * its.front().residual) << name(solver);
        for (size_t n = 1; n < its.size(); ++n) EXPECT_GE(its[n].seconds, its[n - 1].seconds);
    }
    double worst = 0.0, mean = 0.0;
    for (uint32_t i = 0; i < solutions[0].patches().size(); ++i) mean += solutions[0].exitance(i).r;
    mean /= static_cast<double>(solutions[0].patches().size());
    for (size_t s = 1; s < solutions.size(); ++s) {
        for (uint32_t i = 0; i < solutions[0].patches().size(); ++i) {
            const stratum::Rgb a = solutions[0].exitance(i), b = solutions[s].exitance(i);
            worst = std::max({worst, double{std::abs(a.r - b.r)}, double{std::abs(a.g - b.g)},
                              double{std::abs(a.b - b.b)}});
        }
    }
    std::printf("largest difference between solvers: %.2e of the mean exitance\n", worst / mean);
    EXPECT_LT(worst, 1e-5 * mean);
    // Stein–Rosenberg: for a non-negative iteration matrix of spectral radius < 1, Gauss–Seidel's
    // is smaller than Jacobi's, so it needs fewer sweeps to the same tolerance.
    EXPECT_LT(solutions[1].report().iterations.size(), solutions[0].report().iterations.size());
}
