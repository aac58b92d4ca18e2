#include "api/shader_program_validation.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "api/validation.h"
#include "shading/light_path_state.h"
#include "shading/node_registry.h"

namespace stratum {

namespace {

constexpr uint32_t kMaxNodes = 65536, kMaxRegisters = 65536, kMaxData = 1u << 24;

const char* const kParamNames[] = {"BASE_COLOR", "ROUGHNESS", "METALLIC",       "NORMAL",
                                   "EMISSION",   "WEIGHT",    "TRANSMISSION",   "SPECULAR",
                                   "IOR",        "COAT",      "COAT_ROUGHNESS", "COAT_TINT"};

void check_registers(const char* kind, const uint32_t* regs, const uint8_t* widths, size_t n,
                     uint32_t register_count, const std::string& where) {
    for (size_t i = 0; i < n; ++i) {
        if (widths[i] == 0) continue;
        // 64-bit sum: a register near UINT32_MAX must not wrap into range.
        require(static_cast<uint64_t>(regs[i]) + widths[i] <= register_count,
                where + ": " + kind + " " + std::to_string(i) + " register " + std::to_string(regs[i]) +
                    (widths[i] == 3 ? " (3 wide)" : "") + " is outside the program's " +
                    std::to_string(register_count) + " registers");
    }
}

}  // namespace

std::shared_ptr<const ShaderProgram> validate_shader_program(const StratumShaderProgramDesc& d,
                                                             size_t texture_count) {
    // A library whose node files filed conflicting entries runs no program: which of two nodes
    // claiming one value a program meant cannot be known (shading/node_registry.h).
    const std::string registry_problem = node_registry_problem();
    require(registry_problem.empty(),
            "the library's shader node registry is inconsistent: " + registry_problem);
    require(d.node_count <= kMaxNodes,
            "program node_count " + std::to_string(d.node_count) + " exceeds 65536");
    require(d.node_count == 0 || d.nodes != nullptr,
            "program nodes is NULL with node_count " + std::to_string(d.node_count));
    require(d.register_count >= kShaderInputRegisters && d.register_count <= kMaxRegisters,
            "program register_count " + std::to_string(d.register_count) + " is outside [" +
                std::to_string(kShaderInputRegisters) + ", 65536]");
    require(d.registers != nullptr, "program registers is NULL");
    require(d.data_count <= kMaxData, "program data_count " + std::to_string(d.data_count) + " exceeds 2^24");
    require(d.data_count == 0 || d.data != nullptr,
            "program data is NULL with data_count " + std::to_string(d.data_count));
    auto program = std::make_shared<ShaderProgram>();
    program->registers.assign(d.registers, d.registers + d.register_count);
    if (d.data_count) program->data.assign(d.data, d.data + d.data_count);
    // Finite constants: a program's arithmetic then starts from numbers a saved scene can hold.
    for (uint32_t i = kShaderInputRegisters; i < d.register_count; ++i)
        require(std::isfinite(d.registers[i]), "program register " + std::to_string(i) + " = " +
                                                   std::to_string(d.registers[i]) + " is not finite");
    for (uint32_t i = 0; i < d.data_count; ++i)
        require(std::isfinite(d.data[i]),
                "program data " + std::to_string(i) + " = " + std::to_string(d.data[i]) + " is not finite");
    std::fill(program->registers.begin(), program->registers.begin() + kShaderInputRegisters, 0.0f);
    program->nodes.reserve(d.node_count);
    for (uint32_t i = 0; i < d.node_count; ++i) {
        const StratumShaderNode& s = d.nodes[i];
        const NodeEntry* entry = node_entry(s.type);
        require(entry != nullptr,
                "program node " + std::to_string(i) + " has unknown type " + std::to_string(s.type));
        const std::string where = "program node " + std::to_string(i) + " (" + entry->name + ")";
        ShaderNode n;
        n.type = s.type;
        for (int k = 0; k < 6; ++k) n.modes[k] = s.modes[k];
        for (int k = 0; k < 12; ++k) n.inputs[k] = s.inputs[k];
        for (int k = 0; k < 6; ++k) n.outputs[k] = s.outputs[k];
        n.data_offset = s.data_offset;
        n.data_count = s.data_count;
        check_registers("input", n.inputs.data(), entry->input_widths.data(), 12, d.register_count, where);
        check_registers("output", n.outputs.data(), entry->output_widths.data(), 6, d.register_count, where);
        for (size_t k = 0; k < 6; ++k) {
            // A node writing an input register would change what later programs' geometry reads.
            if (entry->output_widths[k] == 0) continue;
            require(n.outputs[k] >= kShaderInputRegisters,
                    where + ": output " + std::to_string(k) + " register " + std::to_string(n.outputs[k]) +
                        " is one of the renderer's input registers (below " +
                        std::to_string(kShaderInputRegisters) + ")");
        }
        require(static_cast<uint64_t>(n.data_offset) + n.data_count <= d.data_count,
                where + ": data range [" + std::to_string(n.data_offset) + ", +" +
                    std::to_string(n.data_count) + ") is outside the program's " +
                    std::to_string(d.data_count) + " data values");
        const std::string problem = entry->check(n, *program);
        require(problem.empty(), where + ": " + problem);
        if (entry->texture_mode >= 0) {
            const int32_t texture = n.modes[static_cast<size_t>(entry->texture_mode)];
            require(texture >= 0 && static_cast<size_t>(texture) < texture_count,
                    where + ": texture " + std::to_string(texture) + " is not a texture (the scene has " +
                        std::to_string(texture_count) + ")");
        }
        if (entry->prepare) {
            n.table = static_cast<uint32_t>(program->tables.size());
            program->tables.push_back(entry->prepare(n, program->data));
        }
        program->nodes.push_back(n);
    }
    return program;
}

ProgramBinding validate_program_binding(const StratumProgramBinding& b, const Scene& scene) {
    require(b.material_id < scene.materials.size(),
            "program binding material_id " + std::to_string(b.material_id) +
                " is not a material (the scene has " + std::to_string(scene.materials.size()) + ")");
    const size_t closures = scene.materials[b.material_id].closures.size();
    require(b.closure_index < closures, "program binding closure_index " + std::to_string(b.closure_index) +
                                            " is not a closure of material " + std::to_string(b.material_id) +
                                            " (it has " + std::to_string(closures) + ")");
    require(b.param >= 0 && b.param < kProgramParamCount,
            "program binding param " + std::to_string(b.param) + " is not a StratumProgramParam (0..11)");
    require(b.program_id < scene.programs.size(),
            "program binding program_id " + std::to_string(b.program_id) +
                " is not a program (the scene has " + std::to_string(scene.programs.size()) + ")");
    const ProgramParam param = static_cast<ProgramParam>(b.param);
    const uint32_t width = program_param_width(param);
    const size_t count = scene.programs[b.program_id]->registers.size();
    require(static_cast<uint64_t>(b.register_index) + width <= count,
            std::string("program binding of ") + kParamNames[b.param] + ": register " +
                std::to_string(b.register_index) + " (" + std::to_string(width) +
                " wide) is outside program " + std::to_string(b.program_id) + "'s " + std::to_string(count) +
                " registers");
    return {b.material_id, b.closure_index, param, b.program_id, b.register_index};
}

LightProgram validate_light_program(uint32_t light_id, uint32_t program_id, uint32_t register_index,
                                    const Scene& scene) {
    require(light_id < scene.lights.size(), "light_id " + std::to_string(light_id) +
                                                " is not a light (the scene has " +
                                                std::to_string(scene.lights.size()) + ")");
    require(program_id < scene.programs.size(), "program_id " + std::to_string(program_id) +
                                                    " is not a program (the scene has " +
                                                    std::to_string(scene.programs.size()) + ")");
    const ShaderProgram& program = *scene.programs[program_id];
    require(static_cast<uint64_t>(register_index) + 3 <= program.registers.size(),
            "light program register " + std::to_string(register_index) + " (3 wide) is outside program " +
                std::to_string(program_id) + "'s " + std::to_string(program.registers.size()) + " registers");
    for (size_t i = 0; i < program.nodes.size(); ++i) {
        const ShaderNode& n = program.nodes[i];
        const NodeEntry& entry = *node_entry(n.type);
        for (size_t k = 0; k < n.inputs.size(); ++k) {
            if (entry.input_widths[k] == 0 || n.inputs[k] >= kShaderInputRegisters) continue;
            const bool ray_length = entry.input_widths[k] == 1 && n.inputs[k] == shader_input::kRayLength;
            const bool light_path = entry.input_widths[k] == 1 && is_light_path_input(n.inputs[k]);
            require(ray_length || light_path,
                    "program " + std::to_string(program_id) + " node " + std::to_string(i) + " (" +
                        entry.name + ") reads renderer input register " + std::to_string(n.inputs[k]) +
                        "; a light's program may read only RAY_LENGTH (" +
                        std::to_string(shader_input::kRayLength) + ") and the Light Path node's (" +
                        std::to_string(shader_input::kIsCameraRay) + " to " +
                        std::to_string(shader_input::kPortalDepth) + ")");
        }
    }
    return {light_id, program_id, register_index};
}

}  // namespace stratum
