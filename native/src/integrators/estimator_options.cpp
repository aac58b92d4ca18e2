#include "integrators/estimator_options.h"

#include <algorithm>
#include <array>

namespace stratum {

namespace {

// Menu order (default first, except light_selection's auto, appended): a host stores a choice by
// its position.
constexpr std::array kLightSampling = {
    RegistryEntry{"mis", "Multiple Importance",
                  "Light sampling (next-event estimation) and BSDF sampling combined by multiple importance "
                  "sampling (textbook §5.5)"},
    RegistryEntry{
        "nee", "Light Sampling",
        "Next-event estimation only: emission is found by shadow rays to sampled lights; a scattered "
        "ray counts emission only after the camera or a delta vertex (eq. 5.16)"},
    RegistryEntry{
        "bsdf", "BSDF Sampling",
        "BSDF sampling only: emission is found by scattered rays hitting lights (eq. 5.2); point and "
        "sun lights cannot be hit and stay black"},
};
constexpr std::array kLightSamplingValues = {LightSampling::Mis, LightSampling::Nee, LightSampling::Bsdf};

constexpr std::array kMisHeuristic = {
    RegistryEntry{"power", "Power", "Power heuristic with beta = 2: w = p_a^2 / (p_a^2 + p_b^2) (§4.4)"},
    RegistryEntry{"balance", "Balance", "Balance heuristic: w = p_a / (p_a + p_b) (§4.4)"},
    RegistryEntry{"max", "Maximum",
                  "Maximum heuristic: weight 1 for the strategy with the larger pdf (§4.4)"},
};
constexpr std::array kMisHeuristicValues = {MisHeuristic::Power, MisHeuristic::Balance,
                                            MisHeuristic::Maximum};

constexpr std::array kLightSelection = {
    RegistryEntry{"mixed", "Mixed",
                  "Half proportional to power, half uniform over the lights (a defensive mixture)"},
    RegistryEntry{"power", "Power", "Proportional to each light's power: p_j = Phi_j / sum Phi (eq. 5.14)"},
    RegistryEntry{"uniform", "Uniform", "Every light with the same probability 1/N"},
    RegistryEntry{"tree", "Light Tree",
                  "A tree over the lights picks one by its power, distance and orientation from each shading "
                  "point (Conty Estevez & Kulla 2018); light tracing emits by power"},
    // Appended last (a host stores the position), the default (integrators/integrator.h).
    RegistryEntry{"auto", "Automatic",
                  "The light tree when the scene holds more than 3 lights (lamps, suns, the world, "
                  "emissive triangles), else mixed"},
};
constexpr std::array kLightSelectionValues = {LightSelection::Mixed, LightSelection::Power,
                                              LightSelection::Uniform, LightSelection::Tree,
                                              LightSelection::Auto};

constexpr std::array kTriangleSampling = {
    RegistryEntry{
        "solid_angle", "Solid Angle",
        "A direction uniform in the solid angle the triangle subtends (Arvo 1995): no fireflies next "
        "to emissive meshes"},
    RegistryEntry{"area", "Area",
                  "A point uniform in the triangle's area (textbook eq. 5.9): its weight grows as 1/r^2 near "
                  "the emitter"},
};
constexpr std::array kTriangleSamplingValues = {TriangleSampling::SolidAngle, TriangleSampling::Area};

constexpr std::array kRouletteMode = {
    RegistryEntry{"throughput", "Throughput",
                  "Survival probability min(1, max channel of the path throughput) (eq. 5.5-5.6)"},
    RegistryEntry{"albedo", "Albedo",
                  "Survival probability min(1, max channel of the surface reflectance) (eq. 5.5-5.6)"},
    RegistryEntry{"off", "Off", "No Russian roulette: paths end only at the bounce limit or on escaping"},
};
constexpr std::array kRouletteModeValues = {RouletteMode::Throughput, RouletteMode::Albedo,
                                            RouletteMode::Off};

static_assert(kLightSampling.size() == kLightSamplingValues.size() &&
              kMisHeuristic.size() == kMisHeuristicValues.size() &&
              kLightSelection.size() == kLightSelectionValues.size() &&
              kTriangleSampling.size() == kTriangleSamplingValues.size() &&
              kRouletteMode.size() == kRouletteModeValues.size());

template <typename Enum, size_t N>
size_t position(const std::array<Enum, N>& values, Enum value) {
    return static_cast<size_t>(std::find(values.begin(), values.end(), value) - values.begin());
}

}  // namespace

std::span<const RegistryEntry> light_sampling_choices() { return kLightSampling; }
std::span<const RegistryEntry> mis_heuristic_choices() { return kMisHeuristic; }
std::span<const RegistryEntry> light_selection_choices() { return kLightSelection; }
std::span<const RegistryEntry> triangle_sampling_choices() { return kTriangleSampling; }
std::span<const RegistryEntry> rr_mode_choices() { return kRouletteMode; }

LightSampling light_sampling_at(size_t choice) { return kLightSamplingValues.at(choice); }
MisHeuristic mis_heuristic_at(size_t choice) { return kMisHeuristicValues.at(choice); }
LightSelection light_selection_at(size_t choice) { return kLightSelectionValues.at(choice); }
TriangleSampling triangle_sampling_at(size_t choice) { return kTriangleSamplingValues.at(choice); }
RouletteMode rr_mode_at(size_t choice) { return kRouletteModeValues.at(choice); }

size_t choice_of(LightSampling value) { return position(kLightSamplingValues, value); }
size_t choice_of(MisHeuristic value) { return position(kMisHeuristicValues, value); }
size_t choice_of(LightSelection value) { return position(kLightSelectionValues, value); }
size_t choice_of(TriangleSampling value) { return position(kTriangleSamplingValues, value); }
size_t choice_of(RouletteMode value) { return position(kRouletteModeValues, value); }

float mis_weight(MisHeuristic heuristic, float pdf_a, float pdf_b) {
    if (!(pdf_a > 0.0f)) return 0.0f;
    // In terms of r = p_b / p_a, so that pdfs near FLT_MAX (and their squares) do not overflow.
    const float r = pdf_b / pdf_a;
    switch (heuristic) {
        case MisHeuristic::Balance:
            return 1.0f / (1.0f + r);
        case MisHeuristic::Power:
            return 1.0f / (1.0f + r * r);
        case MisHeuristic::Maximum:
            // Ties split evenly so the two weights of one path still sum to 1.
            return pdf_a > pdf_b ? 1.0f : (pdf_a == pdf_b ? 0.5f : 0.0f);
    }
    return 0.0f;
}

}  // namespace stratum
