#include "shading/shader_program.h"

#include <algorithm>

#include "shading/node_registry.h"

namespace stratum {

ShaderRegisters::ShaderRegisters(const ShaderProgram& program) {
    const size_t n = program.registers.size();
    if (n <= kStackRegisters) {
        values_ = stack_.data();
    } else {
        heap_.resize(n);
        values_ = heap_.data();
    }
    std::copy(program.registers.begin(), program.registers.end(), values_);
}

void write_objectless_inputs(float* r) {
    std::fill(r, r + kShaderInputRegisters, 0.0f);
    for (uint32_t slot = 0; slot < shader_input::kAttributeSlots; ++slot)
        r[shader_input::kAttribute0 + slot * shader_input::kAttributeWidth + 3] = 1.0f;
    for (uint32_t axis = 0; axis < 3; ++axis) r[shader_input::kNormalTransform + 4 * axis] = 1.0f;
}

void evaluate(const ShaderProgram& program, const ShaderEvalContext& context, ShaderRegisters& registers) {
    // Every node was checked when the program was added: its type is known.
    for (const ShaderNode& node : program.nodes) node_entry(node.type)->evaluate(node, context, registers);
}

}  // namespace stratum
