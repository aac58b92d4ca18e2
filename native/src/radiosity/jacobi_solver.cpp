// Jacobi gathering (textbook §3: "gathering, Jacobi"; Cohen & Wallace 1993 §5.3.1).
//
// | parameter | meaning |
// |-----------|---------|
// | iterate   | M⁽⁰⁾ = b;  M_i⁽ⁿ⁺¹⁾ = b_i + κ_i Σ_j G_ij M_j⁽ⁿ⁾ (every patch gathers from the previous
// iterate) | | iteration | one sweep over all rows: O(entries of G) | | converges | for κ < 1: the error
// shrinks by at most max κ per sweep (G's rows sum to ≤ 1) |
//
// Each row is a sum in index order into its own slot, so the rows can run on any number of
// threads and give the same bits.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>

#include "radiosity/radiosity_solvers.h"

namespace stratum {

RadiositySolve solve_jacobi(const RadiositySystem& system, const SolveOptions& options) {
    const uint32_t n = system.size();
    const IterationMeasures measures(system);
    RadiositySolve solve;
    std::vector<DoubleRgb> current = system.source, next(n);
    double seconds = 0.0;
    for (uint32_t iteration = 1;; ++iteration) {
        const auto t0 = std::chrono::steady_clock::now();
        tbb::parallel_for(tbb::blocked_range<uint32_t>(0, n, 1024),
                          [&](const tbb::blocked_range<uint32_t>& r) {
                              // A cancelled sweep skips its remaining rows; record_iteration
                              // then stops the solve.
                              if (options.cancel && options.cancel->load(std::memory_order_relaxed)) return;
                              for (uint32_t i = r.begin(); i != r.end(); ++i) {
                                  DoubleRgb gathered;
                                  for (const SparseEntry& e : system.gather.row(i))
                                      gathered += current[e.column] * e.value;
                                  next[i] = system.source[i] + system.albedo[i] * gathered;
                              }
                          });
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        IterationReport report = measures.measure(current, next);
        report.iteration = iteration;
        report.seconds = seconds;
        current.swap(next);
        if (record_iteration(options, report, solve)) break;
    }
    solve.exitance = std::move(current);
    return solve;
}

}  // namespace stratum
