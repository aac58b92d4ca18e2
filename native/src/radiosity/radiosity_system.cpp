#include "radiosity/radiosity_system.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render_scene/render_scene.h"

namespace stratum {

namespace {

// The floor of 1 − κ_ave: a white enclosure (κ_ave = 1) has no finite series to sum, and its
// ΔE stays finite and large instead.
constexpr double kMinAbsorption = 1e-6;

}  // namespace

IterationMeasures::IterationMeasures(const RadiositySystem& system) : system_(system) {
    double weighted[3] = {0.0, 0.0, 0.0};
    for (uint32_t i = 0; i < system.size(); ++i) {
        total_area_ += system.area[i];
        for (int k = 0; k < 3; ++k) weighted[k] += system.area[i] * DoubleRgb(system.albedo[i]).channel(k);
    }
    for (int k = 0; k < 3; ++k) {
        const double mean_albedo = total_area_ > 0.0 ? weighted[k] / total_area_ : 0.0;
        one_minus_albedo_[k] = std::max(1.0 - mean_albedo, kMinAbsorption);
    }
}

IterationReport IterationMeasures::measure(const std::vector<DoubleRgb>& before,
                                           const std::vector<DoubleRgb>& after) const {
    const uint32_t n = system_.size();
    // (GM)_i: by rows when the system has them, else scattered along the transpose's rows, in
    // index order either way (the same sums for any thread count).
    std::vector<DoubleRgb> gathered(n);
    if (system_.gather.rows() == n) {
        for (uint32_t i = 0; i < n; ++i)
            for (const SparseEntry& e : system_.gather.row(i)) gathered[i] += after[e.column] * e.value;
    } else {
        for (uint32_t j = 0; j < n; ++j)
            for (const SparseEntry& e : system_.shoot.row(j)) gathered[e.column] += after[j] * e.value;
    }
    double change[3] = {0.0, 0.0, 0.0}, residual[3] = {0.0, 0.0, 0.0}, exitance[3] = {0.0, 0.0, 0.0};
    for (uint32_t i = 0; i < n; ++i) {
        const double a = system_.area[i];
        const DoubleRgb r = system_.source[i] + system_.albedo[i] * gathered[i] - after[i];
        for (int k = 0; k < 3; ++k) {
            change[k] += a * (after[i].channel(k) - before[i].channel(k));
            residual[k] += a * std::abs(r.channel(k));
            exitance[k] += a * after[i].channel(k);
        }
    }
    IterationReport report;
    if (!(total_area_ > 0.0)) return report;
    const double scale = 1.0 / (kPi * total_area_);
    for (int k = 0; k < 3; ++k) {
        const double delta_e = std::abs(change[k]) * scale / one_minus_albedo_[k];
        report.delta_e = std::max(report.delta_e, delta_e);
        report.residual = std::max(report.residual, residual[k] * scale);
        const double mean_radiance = exitance[k] * scale;
        if (mean_radiance > 0.0) report.relative = std::max(report.relative, delta_e / mean_radiance);
    }
    return report;
}

void stop_if_cancelled(const SolveOptions& options) {
    if (options.cancel && options.cancel->load(std::memory_order_relaxed))
        throw RenderScene::BuildCancelled();
}

bool record_iteration(const SolveOptions& options, IterationReport report, RadiositySolve& solve) {
    solve.iterations.push_back(report);
    stop_if_cancelled(options);
    if (report.relative <= options.tolerance) {
        solve.converged = true;
        return true;
    }
    if (report.iteration >= options.max_iterations) return true;
    const size_t n = solve.iterations.size();
    const double then = n > 2 * kRateWindow ? solve.iterations[n - 1 - kRateWindow].delta_e : 0.0;
    if (!(then > 0.0)) return false;
    const double rate = std::pow(report.delta_e / then, 1.0 / kRateWindow);
    // Below 1e-9 a rate's distance from 1 is the rounding of the sums (a constant ΔE measures
    // 1 − r ≈ 2e-16): no contraction.
    const double needed = rate < 1.0 - 1e-9 ? std::log(options.tolerance / report.relative) / std::log(rate)
                                            : std::numeric_limits<double>::infinity();
    if (static_cast<double>(report.iteration) + needed <= static_cast<double>(options.max_iterations))
        return false;
    solve.projected_iterations = static_cast<double>(report.iteration) + needed;
    return true;
}

}  // namespace stratum
