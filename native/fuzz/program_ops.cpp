// The shader-program operations of the fuzzer (stratum/shader_nodes.h): programs of random nodes
// (mostly valid types, modes and registers, sometimes not), their bindings, the world's program,
// and evaluations on hostile inputs (NaN, infinities, huge values). A program the library accepts
// must evaluate without a crash or a sanitizer report, whatever its registers hold.
#include <algorithm>
#include <string>
#include <vector>

#include "checked_call.h"
#include "describe.h"
#include "program.h"

namespace stratum::fuzz {

namespace {

constexpr uint32_t kInputs = STRATUM_SHADER_INPUT_REGISTERS;

std::string describe_program(const StratumShaderProgramDesc& d) {
    std::string s = "{nodes " + std::to_string(d.node_count) + ": ";
    for (uint32_t i = 0; i < d.node_count && d.nodes; ++i) {
        const StratumShaderNode& n = d.nodes[i];
        s += "[type " + std::to_string(n.type) + " modes";
        for (int32_t m : n.modes) s += " " + std::to_string(m);
        s += " in";
        for (uint32_t r : n.inputs) s += " " + std::to_string(r);
        s += " out";
        for (uint32_t r : n.outputs) s += " " + std::to_string(r);
        s += " data " + std::to_string(n.data_offset) + "+" + std::to_string(n.data_count) + "] ";
    }
    s += "registers " + std::to_string(d.register_count) + ": " +
         (d.registers ? describe_floats(d.registers, d.register_count) : std::string("NULL"));
    s += " data " + std::to_string(d.data_count) + ": " +
         (d.data ? describe_floats(d.data, d.data_count) : std::string("NULL")) + "}";
    return s;
}

// A node type from the library's listing (stratum_model_entry): index u8 % (count + 2) names a
// listed type, and the two past the listing are the two values after the largest listed one
// (unknown types). While the listed values are 0..count - 1, index and value coincide, so
// committed inputs keep the types they were written with.
int32_t node_type(ByteReader& in) {
    const int32_t count = stratum_model_count(STRATUM_MODEL_SHADER_NODE);
    const int32_t index = static_cast<int32_t>(in.u8() % static_cast<uint32_t>(count + 2));
    int32_t value = -1;
    if (index < count) {
        stratum_model_entry(STRATUM_MODEL_SHADER_NODE, index, nullptr, &value);
        return value;
    }
    stratum_model_entry(STRATUM_MODEL_SHADER_NODE, count - 1, nullptr, &value);
    return value + 1 + (index - count);
}

}  // namespace

// A program of u8 % 8 nodes over kInputs + u8 % 48 registers (selector 255: any count), each
// node a type (node_type), six modes (u8 % 8 - 1), twelve inputs and six outputs (ids among the
// registers), and a range of the u8 % 300 data values.
void op_add_shader_program(ByteReader& in, ProgramState& s) {
    const uint32_t node_count = in.u8() % 8u;
    const uint8_t size = in.u8();
    const uint32_t register_count = size == 255 ? in.u32() % 70000u : kInputs + size % 48u;
    std::vector<float> registers(std::min<uint32_t>(register_count, 70000u));
    for (size_t i = kInputs; i < registers.size(); ++i)
        registers[i] = (i % 7 == 0) ? in.f32(FloatKind::Signed) : 0.5f;
    std::vector<float> data(in.u8() % 300u);
    for (size_t i = 0; i < data.size(); ++i)
        data[i] = (i % 5 == 0) ? in.f32(FloatKind::Unit) : static_cast<float>(i) / 300.0f;
    std::vector<StratumShaderNode> nodes(node_count);
    for (StratumShaderNode& n : nodes) {
        n.type = node_type(in);
        for (int32_t& m : n.modes) m = static_cast<int32_t>(in.u8() % 8) - 1;
        for (uint32_t& r : n.inputs) r = in.id(register_count);
        for (uint32_t& r : n.outputs)
            r = kInputs + in.id(register_count > kInputs ? register_count - kInputs : 1);
        n.data_offset = in.id(static_cast<uint32_t>(data.size()));
        n.data_count = in.u8() % 260u;
    }
    const StratumShaderProgramDesc d{nodes.data(),     node_count,
                                     registers.data(), static_cast<uint32_t>(registers.size()),
                                     data.data(),      static_cast<uint32_t>(data.size())};
    uint32_t id = UINT32_MAX;
    const StratumStatus status = checked(
        "stratum_scene_add_shader_program",
        [&] { return stratum_scene_add_shader_program(s.scene, &d, &id); },
        [&] { return "scene, &(StratumShaderProgramDesc)" + describe_program(d) + ", &id"; });
    if (status != STRATUM_OK) return;
    if (id != s.programs)
        finding("stratum_scene_add_shader_program returned id " + std::to_string(id) + ", expected " +
                std::to_string(s.programs));
    ++s.programs;
    // Evaluated at once on drawn inputs: every register, NaN and infinities included.
    std::vector<float> inputs(kInputs);
    for (float& v : inputs) v = in.f32(FloatKind::Signed);
    std::vector<float> out(registers.size());
    checked(
        "stratum_scene_evaluate_program",
        [&] {
            return stratum_scene_evaluate_program(s.scene, id, inputs.data(), 0,
                                                  static_cast<uint32_t>(out.size()), out.data());
        },
        [&] {
            return "scene, " + std::to_string(id) + ", (float[])" + describe_floats(inputs.data(), kInputs) +
                   ", 0, " + std::to_string(out.size()) + ", out";
        });
}

// A binding of a drawn (material, closure, param (one past the last is invalid), program,
// register); then, for the world, the program's register as background at a small size.
void op_bind_program(ByteReader& in, ProgramState& s) {
    StratumProgramBinding b{};
    b.material_id = in.id(s.materials());
    b.closure_index = in.id(b.material_id < s.materials() ? s.closures[b.material_id] : 1);
    b.param = static_cast<int32_t>(in.u8() % 13u);
    b.program_id = in.id(s.programs);
    b.register_index = in.id(kInputs + 48);
    checked(
        "stratum_scene_bind_program", [&] { return stratum_scene_bind_program(s.scene, &b); },
        [&] {
            return "scene, &(StratumProgramBinding){" + std::to_string(b.material_id) + ", " +
                   std::to_string(b.closure_index) + ", " + std::to_string(b.param) + ", " +
                   std::to_string(b.program_id) + ", " + std::to_string(b.register_index) + "}";
        });
    if (in.flag()) {
        const uint32_t program = in.id(s.programs), reg = in.id(kInputs + 48);
        const uint32_t width = in.u8() % 20u, height = in.u8() % 12u;
        checked(
            "stratum_scene_set_background_program",
            [&] { return stratum_scene_set_background_program(s.scene, program, reg, width, height); },
            [&] {
                return "scene, " + std::to_string(program) + ", " + std::to_string(reg) + ", " +
                       std::to_string(width) + ", " + std::to_string(height);
            });
    }
}

// A lamp's program: a drawn light (one past the last is invalid), then a flag for
// STRATUM_NO_PROGRAM (which removes it) or a drawn program (one past the last is invalid), and a
// register.
void op_set_light_program(ByteReader& in, ProgramState& s) {
    const uint32_t light = in.id(s.lights);
    const uint32_t program = in.flag() ? STRATUM_NO_PROGRAM : in.id(s.programs);
    const uint32_t reg = in.id(kInputs + 48);
    checked(
        "stratum_scene_set_light_program",
        [&] { return stratum_scene_set_light_program(s.scene, light, program, reg); },
        [&] {
            return "scene, " + std::to_string(light) + ", " + std::to_string(program) + ", " +
                   std::to_string(reg);
        });
}

}  // namespace stratum::fuzz
