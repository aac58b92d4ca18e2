// The estimator choices of the path and light tracers as render settings (textbook §4–§6): how
// emission is found, how the two strategies are weighted, how paths are terminated. Names are
// the values of the string settings `light_sampling`, `mis_heuristic`, `rr_mode`,
// `light_selection` and `triangle_sampling`.
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
// | light_selection   | mixed, power, uniform | (5.14) p_j = Φ_j/ΣΦ; uniform 1/N; mixed = ½ power |
// |                   |                       | + ½ uniform over objects (lights/light_set.h)    |
// | triangle_sampling | solid_angle, area     | the point NEE takes on an emissive triangle:     |
// |                   |                       | uniform in the solid angle it subtends (Arvo     |
// |                   |                       | 1995; lights/emissive_triangle.h), or uniform in |
// |                   |                       | area, the textbook's (5.9)                       |
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "lights/light_selection.h"

namespace stratum {

enum class LightSampling : uint8_t { Bsdf, Nee, Mis };
enum class MisHeuristic : uint8_t { Balance, Power, Maximum };
enum class RouletteMode : uint8_t { Off, Throughput, Albedo };

// The accepted names of each setting, default first.
std::span<const std::string_view> light_sampling_names();
std::span<const std::string_view> mis_heuristic_names();
std::span<const std::string_view> rr_mode_names();
std::span<const std::string_view> light_selection_names();
std::span<const std::string_view> triangle_sampling_names();

// Each returns false (leaving *out unchanged) for an unknown name.
bool parse_light_sampling(std::string_view name, LightSampling* out);
bool parse_mis_heuristic(std::string_view name, MisHeuristic* out);
bool parse_rr_mode(std::string_view name, RouletteMode* out);
bool parse_light_selection(std::string_view name, LightSelection* out);
bool parse_triangle_sampling(std::string_view name, TriangleSampling* out);

// The weight of strategy a's sample when strategy b could have drawn the same path
// (both pdfs in the same measure); a pdf of 0 for a means the sample cannot come from a.
float mis_weight(MisHeuristic heuristic, float pdf_a, float pdf_b);

}  // namespace stratum
