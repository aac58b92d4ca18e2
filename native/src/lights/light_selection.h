// How next-event estimation and the light tracer pick a light and a point on it: the values of
// the render settings `light_selection` and `triangle_sampling` (their names and meanings are
// listed in integrators/estimator_options.h; the distributions are LightSet's).
#pragma once

#include <cstdint>

namespace stratum {

// Power (textbook 5.14), uniform, or half of each over light objects (lights/light_set.h); or
// the light tree (lights/light_tree.h), whose probabilities depend on the shading point; or
// auto, the tree or mixed by the scene's number of lights (LightSet::resolve).
enum class LightSelection : uint8_t { Mixed, Power, Uniform, Tree, Auto };
inline constexpr uint32_t kLightSelectionModes = 5;
// The modes whose probabilities are one table for the whole scene (all but the tree).
inline constexpr uint32_t kStaticLightSelectionModes = 3;
// A point on an emissive triangle: uniform in the solid angle it subtends (Arvo 1995), or
// uniform in its area (textbook eq. 5.9).
enum class TriangleSampling : uint8_t { SolidAngle, Area };

}  // namespace stratum
