// Color Ramp (ShaderNodeValToRGB) and the curve nodes (RGB Curves, Vector Curves, Float Curve) as
// tables baked by the host, looked up as Cycles' svm_node_rgb_ramp, svm_node_curves and
// svm_node_curve do (kernel/svm/ramp.h, rgb_ramp_lookup / float_ramp_lookup; the same in 3.4 and
// 5.0). Cycles bakes a ramp by evaluating Blender's ColorRamp at i / (n - 1), and a curve mapping
// at min_x + i / (n - 1) (max_x - min_x), n = 256 (blender/util.h); the host does the same.
//
// | node       | modes                              | inputs                  | outputs          |
// |------------|------------------------------------|-------------------------|------------------|
// | color_ramp | 0 interpolate                      | fac                     | color (3), alpha |
// | curves     | 0 kind (CurveKind), 1 extrapolate  | fac, value (3; 1 if     | value (3; 1 if   |
// |            |                                    | FLOAT)                  | FLOAT)           |
//
// Data: color_ramp, n >= 1 entries of (r, g, b, a); curves, (min_x, max_x) then n >= 2 entries
// of (r, g, b) (RGB and VECTOR) or of one value (FLOAT). A lookup at f in [0, 1] reads position
// f (n - 1) of the table, interpolating linearly between entries when asked (a ramp whose
// interpolation is CONSTANT is not interpolated; curves always are). Outside [0, 1], a curve with
// extrapolate continues the slope of its first or last two entries; otherwise f is clamped.
// Curves read each channel c at (c - min_x) / (max_x - min_x) and blend the result with the
// input by fac.
#include <algorithm>
#include <cmath>

#include "shading/node_registry.h"

namespace stratum {

namespace {

enum CurveKind : int32_t { CurveRgb, CurveVector, CurveFloat, CurveKindCount };

// The value of component `c` of a table of `n` entries `stride` floats apart at f, as
// rgb_ramp_lookup / float_ramp_lookup.
float lookup(const float* table, uint32_t n, uint32_t stride, uint32_t c, float f, bool interpolate,
             bool extrapolate) {
    const auto at = [&](uint32_t i) { return table[i * stride + c]; };
    const float last = static_cast<float>(n - 1);
    if (extrapolate && (f < 0.0f || f > 1.0f)) {
        if (f < 0.0f) return at(0) + (at(0) - at(1)) * (-f) * last;
        return at(n - 1) + (at(n - 1) - at(n - 2)) * (f - 1.0f) * last;
    }
    // fmin/fmax send NaN to 0 (the first entry, as Cycles' clamped index gives).
    f = std::fmin(std::fmax(f, 0.0f), 1.0f) * last;
    const uint32_t i = std::min(static_cast<uint32_t>(f), n - 1);
    const float t = f - static_cast<float>(i);
    float v = at(i);
    if (interpolate && t > 0.0f) v = (1.0f - t) * v + t * at(i + 1);
    return v;
}

std::string check_ramp(const ShaderNode& n, const ShaderProgram&) {
    std::string e = check_mode(n, 0, "interpolate", 2);
    if (!e.empty()) return e;
    if (n.data_count < 4 || n.data_count % 4 != 0)
        return "data count " + std::to_string(n.data_count) + " is not 4 x n entries (r, g, b, a), n >= 1";
    return "";
}

void evaluate_ramp(const ShaderNode& n, const ShaderEvalContext& context, ShaderRegisters& r) {
    const float* table = context.data(n);
    const uint32_t count = n.data_count / 4;
    const float f = r[n.inputs[0]];
    const bool interpolate = n.modes[0] != 0;
    float c[4];
    for (uint32_t k = 0; k < 4; ++k) c[k] = lookup(table, count, 4, k, f, interpolate, false);
    r.set(n.outputs[0], Rgb(c[0], c[1], c[2]));
    r[n.outputs[1]] = c[3];
}

std::string check_curves(const ShaderNode& n, const ShaderProgram& program) {
    std::string e = check_mode(n, 0, "kind", CurveKindCount);
    if (e.empty()) e = check_mode(n, 1, "extrapolate", 2);
    if (!e.empty()) return e;
    const uint32_t stride = n.modes[0] == CurveFloat ? 1 : 3;
    if (n.data_count < 2 + 2 * stride || (n.data_count - 2) % stride != 0)
        return "data count " + std::to_string(n.data_count) + " is not 2 (min_x, max_x) + " +
               std::to_string(stride) + " x n entries, n >= 2";
    if (stride == 3) {
        const uint64_t count = program.registers.size();
        if (static_cast<uint64_t>(n.inputs[1]) + 3 > count) return "input 1 (value) register is not 3 wide";
        if (static_cast<uint64_t>(n.outputs[0]) + 3 > count) return "output 0 (value) register is not 3 wide";
    }
    return "";
}

void evaluate_curves(const ShaderNode& n, const ShaderEvalContext& context, ShaderRegisters& r) {
    const float* data = context.data(n);
    const float min_x = data[0], range = data[1] - data[0];
    const float* table = data + 2;
    const bool extrapolate = n.modes[1] != 0;
    const float fac = r[n.inputs[0]];
    const uint32_t in = n.inputs[1], out = n.outputs[0];
    if (n.modes[0] == CurveFloat) {
        const float v = r[in];
        const float mapped = lookup(table, n.data_count - 2, 1, 0, (v - min_x) / range, true, extrapolate);
        r[out] = (1.0f - fac) * v + fac * mapped;
        return;
    }
    const uint32_t count = (n.data_count - 2) / 3;
    float result[3];
    for (uint32_t k = 0; k < 3; ++k) {
        const float v = r[in + k];
        const float mapped = lookup(table, count, 3, k, (v - min_x) / range, true, extrapolate);
        result[k] = (1.0f - fac) * v + fac * mapped;
    }
    r.set(out, Vec3(result[0], result[1], result[2]));
}

}  // namespace

const NodeRegistration kColorRampNode{{.value = 12,
                                       .name = "color_ramp",
                                       .input_widths = {1},
                                       .output_widths = {3, 1},
                                       .check = check_ramp,
                                       .evaluate = evaluate_ramp}};

// The value widths depend on the kind: 1 here, and check_curves checks the vector ones.
const NodeRegistration kCurvesNode{{.value = 13,
                                    .name = "curves",
                                    .input_widths = {1, 1},
                                    .output_widths = {1},
                                    .check = check_curves,
                                    .evaluate = evaluate_curves}};

}  // namespace stratum
