// Cycles' light groups (Blender's view_layer.lightgroups; Cycles 3.4 / 5.0 scene/film.cpp
// update_lightgroups, kernel/film/light_passes.h): one RGB pass per group, "Combined_<name>" in
// Blender, holding the light its emitters contribute. The film keeps them after the passes
// (FilmLayout), as Average sums over the camera samples, not denoised; the integrator adds to
// them with PassValues::add_lightgroup (integrators/light_group_writer.h says which light).
//
// | quantity         | value                                                                  |
// |------------------|------------------------------------------------------------------------|
// | group numbers    | 1..kMaxLightGroups, in the order of the view layer's light groups;     |
// |                  | 0 = none (an emitter in no group, or in a group the view layer lacks)  |
// | emitters         | lights, emissive objects (their instances), the world                  |
// | per group, pixel | mean over the camera samples of the clamped contributions of its       |
// |                  | emitters (NEE at every vertex, emission and background rays meet)      |
#pragma once

#include <cstdint>

namespace stratum {

// STRATUM_MAX_LIGHT_GROUPS (api/validation.cpp checks that they agree).
inline constexpr uint32_t kMaxLightGroups = 64;

}  // namespace stratum
