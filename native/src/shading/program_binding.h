// A closure parameter driven by a shader node program (stratum_scene_bind_program), and a lamp's
// emission scaled by one (stratum_scene_set_light_program), as stored in the Scene. Kept apart from the code
// that applies it (render_scene/material_programs.h) so that scene/scene.h depends on data only.
#pragma once

#include <cstdint>

#include "shading/shader_program.h"

namespace stratum {

// Mirrors StratumProgramParam.
enum class ProgramParam : int32_t {
    BaseColor = 0,
    Roughness = 1,
    Metallic = 2,
    Normal = 3,
    Emission = 4,
    Weight = 5,
    Transmission = 6,
    Specular = 7,
    Ior = 8,
    Coat = 9,
    CoatRoughness = 10,
    CoatTint = 11
};
inline constexpr int32_t kProgramParamCount = 12;

// Registers a parameter reads: 3 for a colour or vector, 1 for a scalar.
inline uint32_t program_param_width(ProgramParam p) {
    switch (p) {
        case ProgramParam::BaseColor:
        case ProgramParam::Normal:
        case ProgramParam::Emission:
        case ProgramParam::Weight:
        case ProgramParam::CoatTint:
            return 3;
        default:
            return 1;
    }
}

struct ProgramBinding {
    uint32_t material_id = 0;
    uint32_t closure_index = 0;
    ProgramParam param = ProgramParam::BaseColor;
    uint32_t program_id = 0;
    uint32_t register_index = 0;
};

// A lamp whose emission a program scales (stratum_scene_set_light_program): the RGB of registers
// register_index .. + 2 of program_id (lights/lamp_program.h).
struct LightProgram {
    uint32_t light_id = 0;
    uint32_t program_id = 0;
    uint32_t register_index = 0;
};

}  // namespace stratum
