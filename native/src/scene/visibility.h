// Ray visibility bits of instances and lights (Blender's Object > Visibility > Ray Visibility):
// a ray of kind k sees an object iff its visibility has bit k. The values are the ABI's
// StratumVisibility bits (api/validation.cpp checks that they agree).
#pragma once

#include <cstdint>

namespace stratum {

inline constexpr uint32_t kVisibleCamera = 1;
inline constexpr uint32_t kVisibleDiffuse = 2;
inline constexpr uint32_t kVisibleGlossy = 4;
inline constexpr uint32_t kVisibleTransmission = 8;
inline constexpr uint32_t kVisibleShadow = 16;
inline constexpr uint32_t kVisibleAll = 31;

}  // namespace stratum
