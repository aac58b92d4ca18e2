// Checks of the shader-program entry points (stratum/shader_nodes.h): a program as the host
// describes it becomes a ShaderProgram only if every node, register and data range is valid.
#pragma once

#include <memory>

#include "scene/scene.h"
#include "shading/program_binding.h"
#include "stratum/shader_nodes.h"

namespace stratum {

// The checked program, its nodes' tables prepared. `texture_count`: textures an IMAGE node may
// name. Throws ValidationError naming the node, its type and the field.
std::shared_ptr<const ShaderProgram> validate_shader_program(const StratumShaderProgramDesc& desc,
                                                             size_t texture_count);

ProgramBinding validate_program_binding(const StratumProgramBinding& binding, const Scene& scene);

// A lamp's program (stratum_scene_set_light_program): the light and program exist, the three
// registers lie in the program, and no node reads a renderer input other than RAY_LENGTH and the
// Light Path node's.
LightProgram validate_light_program(uint32_t light_id, uint32_t program_id, uint32_t register_index,
                                    const Scene& scene);

}  // namespace stratum
