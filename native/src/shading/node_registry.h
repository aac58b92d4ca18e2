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

// Cycles' colour-to-float conversion (svm/convert.h rgb_to_gray): dot(c, rgb_to_y), the luminance
// weights Cycles derives from Blender's colour configuration when it starts (the add-on's
// blender_versions.color_config): 0 Blender 3.x, 1 4.0 to 4.5, 2 5.0 and later. Measured: Cycles
// 3.4, 4.2, 4.5 and 5.0 render RGB to BW of unit red, green and blue as exactly these floats (4.2
// and 4.5 alike); docs/blender_versions.md derives them from each configuration.
inline constexpr int32_t kLuminanceWeightsCount = 3;
inline float luminance(Rgb c, int32_t weights) {
    static constexpr float kWeights[kLuminanceWeightsCount][3] = {
        {0.212672979f, 0.715152621f, 0.0721754432f},
        {0.212674037f, 0.715151608f, 0.0721754208f},
        {0.212639123f, 0.715169132f, 0.0721927583f}};
    const float* w = kWeights[weights];
    return w[0] * c.r + w[1] * c.g + w[2] * c.b;
}

// "" when a mode lies in [0, count), else the message naming it.
std::string check_mode(const ShaderNode& node, int index, const char* what, int32_t count);

}  // namespace stratum
