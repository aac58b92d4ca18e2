// The three solvers of the radiosity system (radiosity/radiosity_system.h; textbook §3), one
// file each: jacobi_solver.cpp, gauss_seidel_solver.cpp, shooting_solver.cpp. Each starts from
// M = b (emission and pre-converted direct light), reports every iteration (ΔE, residual,
// time) and stops at options.tolerance or options.max_iterations. All three converge to the
// same M (the system's solution, unique for κ < 1) and are deterministic for any thread count.
#pragma once

#include "radiosity/radiosity_settings.h"
#include "radiosity/radiosity_system.h"

namespace stratum {

// Needs system.gather.
RadiositySolve solve_jacobi(const RadiositySystem& system, const SolveOptions& options);
// Needs system.gather.
RadiositySolve solve_gauss_seidel(const RadiositySystem& system, const SolveOptions& options);
// Needs system.shoot.
RadiositySolve solve_shooting(const RadiositySystem& system, const SolveOptions& options);

RadiositySolve solve_radiosity(RadiositySolver solver, const RadiositySystem& system,
                               const SolveOptions& options);

}  // namespace stratum
