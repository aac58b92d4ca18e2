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

void evaluate(const ShaderProgram& program, const ShaderEvalContext& context, ShaderRegisters& registers) {
    // Every node was checked when the program was added: its type is known.
    for (const ShaderNode& node : program.nodes) node_entry(node.type)->evaluate(node, context, registers);
}

}  // namespace stratum
