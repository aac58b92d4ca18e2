#include "radiosity/radiosity_settings.h"

#include <array>

namespace stratum {

std::span<const RegistryEntry> radiosity_solver_choices() {
    static constexpr std::array kSolvers = {
        RegistryEntry{"shooting", "Progressive Shooting",
                      "Progressive refinement: the patch with the most unshot power shoots it to every patch "
                      "it reaches (textbook §3)"},
        RegistryEntry{"gauss_seidel", "Gauss-Seidel",
                      "Gathering in place: each patch gathers from the others' latest values (textbook §3)"},
        RegistryEntry{"jacobi", "Jacobi",
                      "Gathering: every patch gathers from the values of the previous iteration (textbook "
                      "§3)"},
    };
    return kSolvers;
}

}  // namespace stratum
