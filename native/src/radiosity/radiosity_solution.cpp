#include "radiosity/radiosity_solution.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "core/memory_budget.h"
#include "radiosity/form_factors.h"
#include "radiosity/lamp_irradiance.h"
#include "radiosity/radiosity_solvers.h"

namespace stratum {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The patch size settings give `scene`, once the worst case of its K patches fits in memory.
float checked_patch_size(const RenderScene& scene, const RadiositySettings& settings) {
    const PatchCount count = count_patches(scene, settings.patch_size);
    const double bytes = radiosity_worst_case_bytes(count.patches, settings.rays, settings.solver);
    if (count.patches >= kNoPatch || bytes > memory_budget_bytes())
        throw std::runtime_error("radiosity: a patch size of " + std::to_string(count.patch_size) +
                                 " gives " + std::to_string(count.patches) +
                                 " patches, whose form factors at " + std::to_string(settings.rays) +
                                 " rays may need " + gib(bytes) + ", more than the " +
                                 gib(memory_budget_bytes()) +
                                 " a render may use: raise radiosity_patch_size or lower radiosity_rays");
    return count.patch_size;
}

}  // namespace

double radiosity_worst_case_bytes(uint64_t patches, uint32_t rays, RadiositySolver solver) {
    const double k = static_cast<double>(patches);
    const double matrix = k * (8.0 * rays + 16.0);
    const double per_patch = sizeof(Patch) + 3.0 * sizeof(Rgb) + sizeof(float) + 4.0 * sizeof(DoubleRgb);
    return k * per_patch + matrix * (solver == RadiositySolver::Shooting ? 2.0 : 1.0);
}

RadiositySolution::RadiositySolution(const RenderScene& scene, const RadiositySettings& settings,
                                     const std::atomic<bool>* cancel)
    : patches_(scene, checked_patch_size(scene, settings), cancel) {
    const auto t0 = std::chrono::steady_clock::now();
    const uint32_t n = patches_.size();
    FormFactors form_factors = estimate_form_factors(scene, patches_, settings.rays, cancel);
    const LampIrradiance lamps = lamp_irradiance(scene, patches_, cancel);
    RadiositySystem system;
    system.area.resize(n);
    system.albedo.resize(n);
    system.source.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
        system.area[i] = patches_.patch(i).area;
        system.albedo[i] = patches_.albedo(i);
        Rgb irradiance = form_factors.sky_irradiance[i];
        if (!lamps.irradiance.empty()) irradiance += lamps.irradiance[i];
        system.source[i] = DoubleRgb(patches_.emission(i) + system.albedo[i] * irradiance);
    }
    form_factors.sky_irradiance = {};
    report_.patches = n;
    // A, κ and b now; M, a previous iterate and (shooting) U or (Jacobi) the next in the solve.
    const double vectors = static_cast<double>(n) * (sizeof(float) + sizeof(Rgb) + 4.0 * sizeof(DoubleRgb));
    double matrices = static_cast<double>(form_factors.gather.bytes());
    if (settings.solver == RadiositySolver::Shooting) {
        system.shoot = form_factors.gather.transposed();
        matrices += static_cast<double>(system.shoot.bytes());
        form_factors.gather = SparseMatrix();
    } else {
        system.gather = std::move(form_factors.gather);
    }
    report_.peak_bytes = static_cast<double>(patches_.bytes()) + vectors + matrices;
    report_.form_factor_seconds = seconds_since(t0);
    SolveOptions options;
    options.tolerance = settings.tolerance;
    options.cancel = cancel;
    RadiositySolve solve = solve_radiosity(settings.solver, system, options);
    exitance_.reserve(n);
    for (const DoubleRgb& m : solve.exitance) exitance_.push_back(m.to_float());
    report_.iterations = std::move(solve.iterations);
    report_.converged = solve.converged;
    report_.projected_iterations = solve.projected_iterations;
    report_.solve_seconds = report_.iterations.empty() ? 0.0 : report_.iterations.back().seconds;
}

}  // namespace stratum
