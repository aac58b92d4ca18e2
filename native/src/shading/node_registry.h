// The node types a program may hold, each filed once by its own file under shading/nodes/: its
// C ABI value and name (the node's identity, written nowhere else), the registers its inputs and
// outputs take (0 unused, 1 a float, 3 a vector or colour), how its modes and data are checked,
// an optional prepare step (tables built once when the program is added) and its evaluation.
//
// | entry field   | meaning                                                                  |
// |---------------|--------------------------------------------------------------------------|
// | value         | StratumShaderNode::type. Published: programs in captured scene files and |
// |               | the fuzzer's corpus hold it, so a value is never changed or reused       |
// | name          | as docs/shader_nodes.md names the node ("vector_math"); hosts look the   |
// |               | value up by it (stratum_model_entry with STRATUM_MODEL_SHADER_NODE)      |
// | input_widths, output_widths | registers per input / output; the registry checks them     |
// | check         | the node's modes and data ("" when valid)                                |
// | prepare       | optional: the node's table, built after the checks pass                  |
// | evaluate      | the node at one shading point                                            |
// | texture_mode  | the mode that holds a scene texture id (checked against the scene's), -1 |
//
// A node file files its entry with one object at namespace scope, run at static initialisation:
//     const NodeRegistration kMathNode{{.value = 0, .name = "math", ...}};
// The library's objects are linked whole (CMakeLists.txt: the shared library is made of them, the
// static one is linked WHOLE_ARCHIVE), so no registration is dropped by the linker. A value or a
// name filed twice, or a value out of range, is not filed and makes the registry inconsistent:
// then every program is refused with the conflict named (node_registry_problem), and
// tests/native/shading/test_node_registry.cpp fails.
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
    int32_t value = -1;
    const char* name = nullptr;
    std::array<uint8_t, 12> input_widths{};
    std::array<uint8_t, 6> output_widths{};
    NodeCheck check = nullptr;
    NodePrepare prepare = nullptr;
    NodeEvaluate evaluate = nullptr;
    int8_t texture_mode = -1;
};

// The node types filed so far, by value. A registry is filled at static initialisation and read
// only afterwards: lookups take no lock.
class NodeRegistry {
public:
    // Values are 0 .. kValueLimit - 1.
    static constexpr int32_t kValueLimit = 1024;

    // "" when `entry` can be filed, else what conflicts: its value out of range, or its value or
    // name filed already (naming both nodes).
    std::string conflict(const NodeEntry& entry) const;
    // Files `entry` (which must outlive the registry) unless it conflicts; returns conflict().
    std::string file(const NodeEntry& entry);
    // The entry of `value`, or null.
    const NodeEntry* find(int32_t value) const {
        return value >= 0 && value < kValueLimit ? by_value_[static_cast<uint32_t>(value)] : nullptr;
    }
    // The entries in value order: `index` runs over 0 .. count() - 1.
    int32_t count() const { return count_; }
    const NodeEntry* listed(int32_t index) const;

private:
    std::array<const NodeEntry*, kValueLimit> by_value_{};
    int32_t count_ = 0;
};

// Files an entry in the library's registry at static initialisation (header). A conflict is kept
// (node_registry_problem), never thrown: this runs while a host loads the library.
class NodeRegistration {
public:
    explicit NodeRegistration(const NodeEntry& entry) noexcept;
    NodeRegistration(const NodeRegistration&) = delete;
    NodeRegistration& operator=(const NodeRegistration&) = delete;

private:
    NodeEntry entry_;
};

// The library's registry.
const NodeRegistry& node_registry();
// The entry of `type`, or null for an unknown type.
inline const NodeEntry* node_entry(int32_t type) { return node_registry().find(type); }
// "" when every registration was filed, else the first conflict ("shader node 'x' (value 3):
// value 3 is filed already, by 'map_range'").
std::string node_registry_problem();

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
