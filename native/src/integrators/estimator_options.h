// The estimator choices of the path and light tracers as render settings (textbook §4–§6): how
// emission is found, how the two strategies are weighted, how paths are terminated. Names are
// the values of the settings `light_sampling`, `mis_heuristic`, `rr_mode`, `light_selection`
// and `triangle_sampling`, listed here once with their labels and descriptions.
//
// | setting           | values                | reference                                        |
// |-------------------|-----------------------|--------------------------------------------------|
// | light_sampling    | bsdf, nee, mis        | §5: (5.2) BSDF sampling only; (5.7–5.16) NEE,    |
// |                   |                       | emission hit by a scattered ray counted only     |
// |                   |                       | after a camera or delta vertex (5.16); §5.5 MIS  |
// | mis_heuristic     | balance, power, max   | §4.4: p_a/(p_a+p_b); p_a²/(p_a²+p_b²) (β = 2);   |
// |                   |                       | 1 for the larger pdf                             |
// | rr_mode           | off, throughput,      | (5.5–5.6): survival min(1, max β) or             |
// |                   | albedo                | min(1, max ρ), ρ the closures' albedo            |
// | light_selection   | mixed, power, uniform,| (5.14) p_j = Φ_j/ΣΦ; uniform 1/N; mixed = ½ power |
// |                   | tree, auto            | + ½ uniform over objects (lights/light_set.h);   |
// |                   |                       | tree: Conty Estévez & Kulla 2018, per shading    |
// |                   |                       | point (lights/light_tree.h); auto (the default): |
// |                   |                       | tree above 3 lights, else mixed (LightSet)       |
// | triangle_sampling | solid_angle, area     | the point NEE takes on an emissive triangle:     |
// |                   |                       | uniform in the solid angle it subtends (Arvo     |
// |                   |                       | 1995; lights/emissive_triangle.h), or uniform in |
// |                   |                       | area, the textbook's (5.9)                       |
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "core/registry.h"
#include "lights/light_selection.h"

namespace stratum {

enum class LightSampling : uint8_t { Bsdf, Nee, Mis };
enum class MisHeuristic : uint8_t { Balance, Power, Maximum };
enum class RouletteMode : uint8_t { Off, Throughput, Albedo };

// The choices of each option in menu order (a host stores the position: never reorder), and
// the enumerator each stands for. A default is IntegratorSettings' (integrators/integrator.h).
std::span<const RegistryEntry> light_sampling_choices();
std::span<const RegistryEntry> mis_heuristic_choices();
std::span<const RegistryEntry> light_selection_choices();
std::span<const RegistryEntry> triangle_sampling_choices();
std::span<const RegistryEntry> rr_mode_choices();
LightSampling light_sampling_at(size_t choice);
MisHeuristic mis_heuristic_at(size_t choice);
LightSelection light_selection_at(size_t choice);
TriangleSampling triangle_sampling_at(size_t choice);
RouletteMode rr_mode_at(size_t choice);
// The menu position of an enumerator.
size_t choice_of(LightSampling value);
size_t choice_of(MisHeuristic value);
size_t choice_of(LightSelection value);
size_t choice_of(TriangleSampling value);
size_t choice_of(RouletteMode value);

// The weight of strategy a's sample when strategy b could have drawn the same path
// (both pdfs in the same measure); a pdf of 0 for a means the sample cannot come from a.
float mis_weight(MisHeuristic heuristic, float pdf_a, float pdf_b);

}  // namespace stratum
