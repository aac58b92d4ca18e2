// The radiosity solution of a render scene (textbook §3): patches (radiosity/patch_set.h), form
// factors by ray casting (radiosity/form_factors.h), lamps pre-converted to direct irradiance
// (radiosity/lamp_irradiance.h), the system M = b + κGM (radiosity/radiosity_system.h) solved by
// the chosen solver (radiosity/radiosity_solvers.h). It depends on the scene only, not on the
// camera: the `radiosity` integrator computes it once per render, before the first sample.
//
// | step             | memory                                                              |
// |------------------|---------------------------------------------------------------------|
// | patches          | K × (sizeof(Patch) + 2 Rgb) and 8 bytes per triangle                |
// | form factors     | 16 bytes per row + 8 per non-zero entry (≤ rays per row): ≤ K (8N + 16) |
// | shooting         | the transpose as well, while it is built and used: twice that       |
// | system and solve | A, κ (float), b, M and two more iterates (double): K × 112 bytes     |
// Before anything is allocated, the worst case (every ray of every patch hitting another
// patch) must fit in the memory budget (core/memory_budget.h), or the render stops with an
// error naming K and the bytes, and asking for a larger radiosity_patch_size. Only the patches
// and M are kept after the solve.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "radiosity/patch_set.h"
#include "radiosity/radiosity_settings.h"
#include "radiosity/radiosity_system.h"
#include "render_scene/render_scene.h"

namespace stratum {

// What the solve cost and how it ended (for the render's progress and for studies).
struct RadiosityReport {
    uint64_t patches = 0;              // K
    double peak_bytes = 0.0;           // the most the solution held at once
    double form_factor_seconds = 0.0;  // form factors, lamps and (shooting) the transpose
    double solve_seconds = 0.0;        // the solver's own time (without the measures)
    std::vector<IterationReport> iterations;
    bool converged = false;  // false: stopped at SolveOptions::max_iterations or short of its reach
    double projected_iterations = 0.0;  // RadiositySolve::projected_iterations
};

class RadiositySolution {
public:
    // Throws std::runtime_error when the worst case does not fit in memory, and
    // RenderScene::BuildCancelled when *cancel (may be null) becomes true.
    RadiositySolution(const RenderScene& scene, const RadiositySettings& settings,
                      const std::atomic<bool>* cancel);

    const PatchSet& patches() const { return patches_; }
    // M_i, and the part of it that is reflected light: M_i − M_e,i.
    Rgb exitance(uint32_t i) const { return exitance_[i]; }
    Rgb reflected(uint32_t i) const { return exitance_[i] - patches_.emission(i); }
    const RadiosityReport& report() const { return report_; }

private:
    PatchSet patches_;
    std::vector<Rgb> exitance_;
    RadiosityReport report_;
};

// The worst-case bytes of a solution with `patches` patches and `rays` rays per patch.
double radiosity_worst_case_bytes(uint64_t patches, uint32_t rays, RadiositySolver solver);

}  // namespace stratum
