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
// Not a ray kind (Blender's object.is_shadow_catcher): an instance with it is a shadow catcher;
// a light with it lights the catcher-only copy of a camera path (integrators/shadow_catcher.h).
inline constexpr uint32_t kVisibleShadowCatcher = 32;

// Inside the render scene (Embree masks, LightSet bits) the catcher-only copy of a path is a
// ray kind of its own, as Cycles' SHADOW_CATCHER_VISIBILITY_SHIFT: its rays carry their kind's
// bit shifted by kCatcherPathShift, which only shadow catchers, the lights that light them and
// the world hold. trace_visibility gives those bits of an object or light's StratumVisibility.
inline constexpr uint32_t kCatcherPathShift = 8;
inline constexpr uint32_t trace_visibility(uint32_t bits) {
    const uint32_t rays = bits & kVisibleAll;
    return (bits & kVisibleShadowCatcher) ? rays | (rays << kCatcherPathShift) : rays;
}

}  // namespace stratum
