// The node types a program may hold, one entry each: the registers its inputs and outputs take
// (0 unused, 1 a float, 3 a vector or colour), how its modes and data are checked, an optional
// prepare step (tables built once when the program is added) and its evaluation. Each family of
// nodes lives in its own file under shading/nodes/ and registers its entries in node_registry.cpp.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "shading/shader_program.h"

namespace stratum {

// Returns "" when the node's modes and data are valid, else what is wrong ("mode 0 (operation)
// is 57; 0..39"). Registers are checked by the registry from the widths; `program` holds the
// registers and data (its nodes are being checked).
using NodeCheck = std::string (*)(const ShaderNode& node, const ShaderProgram& program);
// Builds the node's table (e.g. the Sky's precomputed radiance); called after the checks pass.
using NodePrepare = std::vector<float> (*)(const ShaderNode& node, const std::vector<float>& data);
using NodeEvaluate = void (*)(const ShaderNode& node, const ShaderEvalContext& context, ShaderRegisters& r);

struct NodeEntry {
    const char* name;  // "math", as docs/shader_nodes.md names it
    std::array<uint8_t, 12> input_widths;
    std::array<uint8_t, 6> output_widths;
    NodeCheck check;
    NodePrepare prepare;  // may be null
    NodeEvaluate evaluate;
};

// The entry of `type`, or null for an unknown type.
const NodeEntry* node_entry(int32_t type);

// Cycles' colour-to-float conversion (svm/convert.h rgb_to_gray): the luminance weights of the
// colour configuration's scene-linear space. `weights` 0: Blender 3.x's config (Rec.709,
// 0.2126729, 0.7151522, 0.0721750); 1: Blender 4.x/5.x's (0.2126390, 0.7151687, 0.0721923,
// measured: Cycles 5.0 renders RGB to BW with exactly these).
inline float luminance(Rgb c, int32_t weights) {
    if (weights == 1) return 0.2126390f * c.r + 0.7151687f * c.g + 0.0721923f * c.b;
    return kLuminanceR * c.r + kLuminanceG * c.g + kLuminanceB * c.b;
}

// "" when a mode lies in [0, count), else the message naming it.
std::string check_mode(const ShaderNode& node, int index, const char* what, int32_t count);

}  // namespace stratum
