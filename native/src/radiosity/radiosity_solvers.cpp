#include "radiosity/radiosity_solvers.h"

namespace stratum {

RadiositySolve solve_radiosity(RadiositySolver solver, const RadiositySystem& system,
                               const SolveOptions& options) {
    switch (solver) {
        case RadiositySolver::Jacobi:
            return solve_jacobi(system, options);
        case RadiositySolver::GaussSeidel:
            return solve_gauss_seidel(system, options);
        case RadiositySolver::Shooting:
            break;
    }
    return solve_shooting(system, options);
}

}  // namespace stratum
