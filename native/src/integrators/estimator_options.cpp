#include "integrators/estimator_options.h"

#include <array>

namespace stratum {

namespace {

// Index i of `names` is enumerator i of the option's enum.
template <typename Enum, size_t N>
bool parse_by_index(const std::array<std::string_view, N>& names, std::string_view name, Enum* out) {
    for (size_t i = 0; i < N; ++i) {
        if (names[i] == name) {
            *out = static_cast<Enum>(i);
            return true;
        }
    }
    return false;
}

// Enumerator order, not display order: each enum's value i is names[i]; the default is its
// first enumerator except where kDefault* say otherwise.
constexpr std::array<std::string_view, 3> kLightSampling = {"bsdf", "nee", "mis"};
constexpr std::array<std::string_view, 3> kMisHeuristic = {"balance", "power", "max"};
constexpr std::array<std::string_view, 3> kRouletteMode = {"off", "throughput", "albedo"};
constexpr std::array<std::string_view, 3> kLightSelection = {"mixed", "power", "uniform"};
constexpr std::array<std::string_view, 2> kTriangleSampling = {"solid_angle", "area"};

// Default-first lists for hosts (the UI's order).
constexpr std::array<std::string_view, 3> kLightSamplingNames = {"mis", "nee", "bsdf"};
constexpr std::array<std::string_view, 3> kMisHeuristicNames = {"power", "balance", "max"};
constexpr std::array<std::string_view, 3> kRouletteModeNames = {"throughput", "albedo", "off"};

}  // namespace

std::span<const std::string_view> light_sampling_names() { return kLightSamplingNames; }
std::span<const std::string_view> mis_heuristic_names() { return kMisHeuristicNames; }
std::span<const std::string_view> rr_mode_names() { return kRouletteModeNames; }
std::span<const std::string_view> light_selection_names() { return kLightSelection; }
std::span<const std::string_view> triangle_sampling_names() { return kTriangleSampling; }

bool parse_light_sampling(std::string_view name, LightSampling* out) {
    return parse_by_index(kLightSampling, name, out);
}
bool parse_mis_heuristic(std::string_view name, MisHeuristic* out) {
    return parse_by_index(kMisHeuristic, name, out);
}
bool parse_rr_mode(std::string_view name, RouletteMode* out) {
    return parse_by_index(kRouletteMode, name, out);
}
bool parse_light_selection(std::string_view name, LightSelection* out) {
    return parse_by_index(kLightSelection, name, out);
}
bool parse_triangle_sampling(std::string_view name, TriangleSampling* out) {
    return parse_by_index(kTriangleSampling, name, out);
}

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
