// The linear system the radiosity solvers share (textbook §3, eqs. 3.2–3.3, with M = πL):
//     M_i = b_i + κ_i Σ_j G_ij M_j,     b_i = M_e,i + κ_i E_i,
// E_i the irradiance pre-converted from lamps and the sky (radiosity/lamp_irradiance.h,
// radiosity/form_factors.h). Per RGB channel; the three solvers (radiosity/radiosity_solvers.h)
// report every iteration with the two measures below.
//
// | measure  | definition |
// |----------|------------|
// | ΔE       | the book's stopping estimate |Σ_i A_i (M_i⁽ⁿ⁾ − M_i⁽ⁿ⁻¹⁾)| / (π (1 − κ_ave) Σ_i A_i), κ_ave
// the | |          | area-weighted mean albedo: the change of the mean radiance times the geometric series |
// |          | 1/(1 − κ_ave) of the changes still to come, an estimate of the mean radiance's error |
// | residual | Σ_i A_i |b_i + κ_i (GM)_i − M_i| / (π Σ_i A_i): how far the current M is from solving |
// |          | the system, in radiance (0 exactly at the solution) |
// | relative | ΔE over the current mean radiance L̄ = Σ_i A_i M_i / (π Σ_i A_i); the solve stops when it |
// |          | is at most the tolerance |
// Each is the largest over the channels (a channel with L̄ = 0 has nothing to converge).
// The iterates are kept in double: in float the last change of a patch that has received
// thousands of shots is below the rounding of its sum (measured: 2e-5 of L on sphere B with
// shooting), so no tolerance under ~1e-5 would be reachable; form factors and albedos stay
// float (a hit count / N and a colour are exact enough as they are).
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "radiosity/sparse_matrix.h"

namespace stratum {

// RGB in double, for the iterates.
struct DoubleRgb {
    double r = 0.0, g = 0.0, b = 0.0;
    DoubleRgb() = default;
    DoubleRgb(double r_, double g_, double b_) : r(r_), g(g_), b(b_) {}
    explicit DoubleRgb(Rgb c) : r(c.r), g(c.g), b(c.b) {}
    DoubleRgb& operator+=(DoubleRgb o) {
        r += o.r;
        g += o.g;
        b += o.b;
        return *this;
    }
    double channel(int k) const { return k == 0 ? r : (k == 1 ? g : b); }
    Rgb to_float() const { return {static_cast<float>(r), static_cast<float>(g), static_cast<float>(b)}; }
};
inline DoubleRgb operator+(DoubleRgb a, DoubleRgb b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
inline DoubleRgb operator-(DoubleRgb a, DoubleRgb b) { return {a.r - b.r, a.g - b.g, a.b - b.b}; }
inline DoubleRgb operator*(DoubleRgb a, double s) { return {a.r * s, a.g * s, a.b * s}; }
inline DoubleRgb operator*(Rgb a, DoubleRgb b) { return {a.r * b.r, a.g * b.g, a.b * b.b}; }

struct RadiositySystem {
    std::vector<float> area;        // A_i
    std::vector<Rgb> albedo;        // κ_i
    std::vector<DoubleRgb> source;  // b_i
    SparseMatrix gather;            // rows (j, G_ij): Jacobi, Gauss–Seidel
    SparseMatrix shoot;             // rows (j, G_ji), the transpose: shooting from i
    uint32_t size() const { return static_cast<uint32_t>(area.size()); }
};

struct IterationReport {
    uint32_t iteration = 0;  // 1, 2, ...
    double delta_e = 0.0;    // the book's ΔE (radiance)
    double relative = 0.0;   // ΔE / L̄
    double residual = 0.0;   // radiance
    double seconds = 0.0;    // the solver's time since it started, without the measures
};

struct SolveOptions {
    double tolerance = 1e-3;  // on `relative`
    uint32_t max_iterations = 10000;
    const std::atomic<bool>* cancel = nullptr;  // throws RenderScene::BuildCancelled when set
};

struct RadiositySolve {
    std::vector<DoubleRgb> exitance;  // M_i
    std::vector<IterationReport> iterations;
    bool converged = false;  // stopped by the tolerance (or nothing left to move), not the cap
    // When the solve stopped early because the tolerance is out of the cap's reach: the
    // iterations it would need at the measured contraction (infinite when nothing contracts).
    double projected_iterations = 0.0;
};

// The measures of the header between two iterates (`before` → `after`), with the residual of
// `after` from whichever matrix the system holds (gather rows, else shoot rows).
class IterationMeasures {
public:
    explicit IterationMeasures(const RadiositySystem& system);
    IterationReport measure(const std::vector<DoubleRgb>& before, const std::vector<DoubleRgb>& after) const;

private:
    const RadiositySystem& system_;
    double total_area_ = 0.0;
    double one_minus_albedo_[3] = {1.0, 1.0, 1.0};
};

// Throws RenderScene::BuildCancelled when options.cancel is set: the solvers call it every
// kCancelCheckRows rows or shots, so that Esc stops even a sweep of a large scene at once.
void stop_if_cancelled(const SolveOptions& options);
inline constexpr uint32_t kCancelCheckRows = 4096;
inline constexpr uint32_t kRateWindow = 16;

// Records `report` (numbered and timed by the caller) and says whether to stop: converged, the
// cap reached, or the cap out of reach. The last: ΔE of the last kRateWindow iterations shrinks
// by a rate r per iteration (its geometric mean; the spectral radius of κĜ once the iteration
// settles), so the tolerance τ needs about ln(τ/ΔE_rel)/ln r more; when that passes the cap,
// iterating on is time spent for an iterate no better than the one at hand. A closed space
// whose surfaces all reflect everything (κ = 1) has no finite solution: M grows by the same
// step each iteration, so r = 1 (ΔE_rel itself falls as 1/n, too slowly to tell from a slow
// geometric series), and without this the solve ran to the cap (measured: more than 10 minutes for a white
// box of 17,496 patches lit by a point lamp). Checked only after 2 kRateWindow iterations, past the first
// iterations' transient. Throws RenderScene::BuildCancelled when options.cancel is set.
bool record_iteration(const SolveOptions& options, IterationReport report, RadiositySolve& solve);

}  // namespace stratum
