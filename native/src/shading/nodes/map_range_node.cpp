// Map Range (Blender's ShaderNodeMapRange) and Clamp (ShaderNodeClamp).
//
// | node      | modes                              | inputs                         | outputs  |
// |-----------|------------------------------------|--------------------------------|----------|
// | map_range | 0 data type (0 float, 1 vector),   | value, from min, from max,     | result   |
// |           | 1 interpolation (LINEAR, STEPPED,  | to min, to max, steps          | (1 or 3) |
// |           | SMOOTHSTEP, SMOOTHERSTEP), 2 clamp | (each 1 wide, or 3 for vector) |          |
// | clamp     | 0 type (MINMAX, RANGE)             | value, min, max                | result   |
//
// Cycles' svm_node_map_range and svm_node_vector_map_range (kernel/svm/map_range.h) and
// svm_node_clamp (kernel/svm/clamp.h), unchanged from 3.4 to 5.0. The float node maps nothing
// when From Min equals From Max (result 0), and its clamp is the RANGE clamp Cycles inserts after
// it (MapRangeNode::expand) for every interpolation; the vector node divides safely per
// component, and clamps only LINEAR and STEPPED results.
#include <cmath>

#include "shading/node_registry.h"

namespace stratum {

namespace {

enum DataType : int32_t { FloatData, VectorData, DataTypeCount };
enum Interpolation : int32_t { Linear, Stepped, Smoothstep, Smootherstep, InterpolationCount };
enum ClampType : int32_t { MinMax, Range, ClampTypeCount };

// Cycles' clamp: min(max(a, lo), hi) with the ternary min and max.
float clamp_between(float a, float lo, float hi) {
    const float m = a > lo ? a : lo;
    return m < hi ? m : hi;
}

// RANGE clamp: the bounds in either order.
float clamp_range(float a, float lo, float hi) {
    return lo > hi ? clamp_between(a, hi, lo) : clamp_between(a, lo, hi);
}

float smooth_step(float e0, float e1, float x) {
    if (x < e0) return 0.0f;
    if (x >= e1) return 1.0f;
    const float t = (x - e0) / (e1 - e0);
    return (3.0f - 2.0f * t) * (t * t);
}

float smoother_step(float e0, float e1, float x) {
    const float d = e1 - e0;
    const float t = clamp_between(d != 0.0f ? (x - e0) / d : 0.0f, 0.0f, 1.0f);
    return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f);
}

float stepped(float factor, float steps) {
    return steps > 0.0f ? std::floor(factor * (steps + 1.0f)) / steps : 0.0f;
}

float map_float(int32_t interpolation, bool clamp, float value, float from_min, float from_max, float to_min,
                float to_max, float steps) {
    float result = 0.0f;
    if (from_max != from_min) {
        float factor = value;
        switch (interpolation) {
            case Stepped:
                factor = stepped((value - from_min) / (from_max - from_min), steps);
                break;
            case Smoothstep:
                factor = from_min > from_max ? 1.0f - smooth_step(from_max, from_min, value)
                                             : smooth_step(from_min, from_max, value);
                break;
            case Smootherstep:
                factor = from_min > from_max ? 1.0f - smoother_step(from_max, from_min, value)
                                             : smoother_step(from_min, from_max, value);
                break;
            default:
                factor = (value - from_min) / (from_max - from_min);
                break;
        }
        result = to_min + factor * (to_max - to_min);
    }
    return clamp ? clamp_range(result, to_min, to_max) : result;
}

// One component of the vector node.
float map_component(int32_t interpolation, bool clamp, float value, float from_min, float from_max,
                    float to_min, float to_max, float steps) {
    const float d = from_max - from_min;
    float factor = d != 0.0f ? (value - from_min) / d : 0.0f;
    switch (interpolation) {
        case Stepped:
            factor = stepped(factor, steps);
            break;
        case Smoothstep:
            factor = clamp_between(factor, 0.0f, 1.0f);
            factor = (3.0f - 2.0f * factor) * (factor * factor);
            break;
        case Smootherstep:
            factor = clamp_between(factor, 0.0f, 1.0f);
            factor = factor * factor * factor * (factor * (factor * 6.0f - 15.0f) + 10.0f);
            break;
        default:
            break;
    }
    const float result = to_min + factor * (to_max - to_min);
    const bool clamps = clamp && (interpolation == Linear || interpolation == Stepped);
    return clamps ? clamp_range(result, to_min, to_max) : result;
}

std::string check_map_range(const ShaderNode& n, const ShaderProgram& program) {
    std::string e = check_mode(n, 0, "data type", DataTypeCount);
    if (e.empty()) e = check_mode(n, 1, "interpolation", InterpolationCount);
    if (e.empty()) e = check_mode(n, 2, "clamp", 2);
    if (!e.empty() || n.modes[0] != VectorData) return e;
    const size_t count = program.registers.size();
    for (int i = 0; i < 6; ++i)
        if (static_cast<uint64_t>(n.inputs[i]) + 3 > count)
            return "input " + std::to_string(i) + " register is not 3 wide";
    if (static_cast<uint64_t>(n.outputs[0]) + 3 > count) return "output register is not 3 wide";
    return "";
}

void evaluate_map_range(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const int32_t interpolation = n.modes[1];
    const bool clamp = n.modes[2] != 0;
    if (n.modes[0] == FloatData) {
        r[n.outputs[0]] = map_float(interpolation, clamp, r[n.inputs[0]], r[n.inputs[1]], r[n.inputs[2]],
                                    r[n.inputs[3]], r[n.inputs[4]], r[n.inputs[5]]);
        return;
    }
    float out[3];
    for (uint32_t k = 0; k < 3; ++k)
        out[k] =
            map_component(interpolation, clamp, r[n.inputs[0] + k], r[n.inputs[1] + k], r[n.inputs[2] + k],
                          r[n.inputs[3] + k], r[n.inputs[4] + k], r[n.inputs[5] + k]);
    r.set(n.outputs[0], Vec3(out[0], out[1], out[2]));
}

std::string check_clamp(const ShaderNode& n, const ShaderProgram&) {
    return check_mode(n, 0, "type", ClampTypeCount);
}

void evaluate_clamp(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const float value = r[n.inputs[0]], lo = r[n.inputs[1]], hi = r[n.inputs[2]];
    r[n.outputs[0]] = n.modes[0] == Range ? clamp_range(value, lo, hi) : clamp_between(value, lo, hi);
}

}  // namespace

// The widths are those of the float node; check_map_range checks the vector node's.
const NodeRegistration kMapRangeNode{{.value = 3,
                                      .name = "map_range",
                                      .input_widths = {1, 1, 1, 1, 1, 1},
                                      .output_widths = {1},
                                      .check = check_map_range,
                                      .evaluate = evaluate_map_range}};

const NodeRegistration kClampNode{{.value = 4,
                                   .name = "clamp",
                                   .input_widths = {1, 1, 1},
                                   .output_widths = {1},
                                   .check = check_clamp,
                                   .evaluate = evaluate_clamp}};

}  // namespace stratum
