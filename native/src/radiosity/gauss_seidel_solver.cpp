// Gauss–Seidel gathering (textbook §3: gathering "in place"; Cohen & Wallace 1993 §5.3.2).
//
// | parameter | meaning |
// |-----------|---------|
// | iterate   | M = b; for i = 0 .. K−1 in order: M_i ← b_i + κ_i Σ_j G_ij M_j, with the M_j already |
// |           | updated in this sweep |
// | iteration | one sweep over all rows: O(entries of G) |
// | converges | for κ < 1, at least as fast as Jacobi on this (diagonally dominant) system; each |
// |           | update uses the newest values, so light crosses several patches within one sweep |
//
// The sweep is sequential by nature (row i reads the rows before it): one thread, in index
// order, so the result does not depend on the thread count.
#include <chrono>

#include "radiosity/radiosity_solvers.h"

namespace stratum {

RadiositySolve solve_gauss_seidel(const RadiositySystem& system, const SolveOptions& options) {
    const uint32_t n = system.size();
    const IterationMeasures measures(system);
    RadiositySolve solve;
    std::vector<DoubleRgb> current = system.source, before;
    double seconds = 0.0;
    for (uint32_t iteration = 1;; ++iteration) {
        before = current;
        const auto t0 = std::chrono::steady_clock::now();
        for (uint32_t i = 0; i < n; ++i) {
            if (i % kCancelCheckRows == 0) stop_if_cancelled(options);
            DoubleRgb gathered;
            for (const SparseEntry& e : system.gather.row(i)) gathered += current[e.column] * e.value;
            current[i] = system.source[i] + system.albedo[i] * gathered;
        }
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        IterationReport report = measures.measure(before, current);
        report.iteration = iteration;
        report.seconds = seconds;
        if (record_iteration(options, report, solve)) break;
    }
    solve.exitance = std::move(current);
    return solve;
}

}  // namespace stratum
