// A lamp's emission scaled by a shader program (stratum_scene_set_light_program), as Cycles
// shades a lamp with its node tree (Light > Nodes): the lamp's radiance times the program's RGB
// (the tree's Emission Color x Strength), evaluated wherever the emission is used.
//
// | input      | value                                                                      |
// |------------|----------------------------------------------------------------------------|
// | RAY_LENGTH | the distance from the point being lit (or the ray's origin) to the point on |
// |            | the lamp; FLT_MAX for a lamp at infinity (Cycles' ls->t and sd->ray_length) |
// | Light Path | the path's state as Cycles' PATH_RAY_EMISSION evaluation sees it (no ray    |
// |            | kind, one bounce further: LightPathState::emission), for a light sample and |
// |            | for a ray that meets the lamp alike                                         |
// | the others | those of a point on no object (write_objectless_inputs); the C ABI refuses a |
// |            | program that reads one                                                      |
//
// The factor is per channel at least 0 and finite: a NaN reads 0 and an infinity the largest
// float, as the lamp's own colour is limited. Cycles' light_sample_shader_eval is the reference:
// the emission at the sample's distance ls->t, for next-event estimation and for a ray that meets
// the lamp alike. Light tracing applies it at the first surface a particle meets.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/math.h"
#include "shading/light_path_state.h"
#include "shading/shader_program.h"

namespace stratum {

class LampProgram {
public:
    // `at_infinity`: a lamp at infinity (a sun), whose every distance is Cycles' FLT_MAX.
    LampProgram(std::shared_ptr<const ShaderProgram> program, uint32_t register_index,
                std::vector<std::shared_ptr<const Texture>> textures, bool at_infinity);

    // The factor on the lamp's radiance at `distance` from the point on the lamp, for the
    // Light Path inputs `path` (already the emission's: LightPathState::emission).
    Rgb scale(float distance, const LightPathState& path) const;

private:
    std::shared_ptr<const ShaderProgram> program_;
    uint32_t register_;
    std::vector<std::shared_ptr<const Texture>> textures_;
    bool at_infinity_;
};

}  // namespace stratum
