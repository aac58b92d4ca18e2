// Mix node: Blender's ShaderNodeMix (3.4+: float, vector, colour) and ShaderNodeMixRGB (3.x files),
// as Cycles' svm_node_mix_float / _vector / _vector_non_uniform / _color and svm_node_mix
// (kernel/svm/mix.h, the blends in kernel/svm/color_util.h; the same in 3.4 and 5.0 but for
// EXCLUSION, new in 4.0).
//
// | modes                                   | inputs                          | outputs    |
// |-----------------------------------------|---------------------------------|------------|
// | 0 kind (MixKind), 1 blend (MixBlend),   | factor (1; 3 if non-uniform),   | result     |
// | 2 clamp factor, 3 clamp result (colour) | a, b (1 if float, else 3)       | (1 or 3)   |
//
// The blend numbering is Cycles' NodeMix (svm/types.h). MixRGB is a colour mix whose factor is
// always clamped (svm_mix_clamped_factor) and whose Clamp option clamps the result; the Mix node's
// Clamp Factor and Clamp Result options choose each. The blend is read for colours only.
#include <algorithm>
#include <cmath>
#include <tuple>

#include "shading/color_math.h"
#include "shading/node_registry.h"

namespace stratum {

namespace {

enum MixKind : int32_t { MixFloat, MixVector, MixVectorNonUniform, MixColor, MixKindCount };

enum MixBlend : int32_t {
    Blend,
    Add,
    Multiply,
    Subtract,
    Screen,
    Divide,
    Difference,
    Darken,
    Lighten,
    Overlay,
    Dodge,
    Burn,
    Hue,
    Saturation,
    Value,
    Color,
    SoftLight,
    LinearLight,
    Exclusion,
    MixBlendCount
};

// Cycles' interp(a, b, t) = a + t (b - a), per channel.
float towards(float a, float b, float t) { return a + t * (b - a); }
Rgb towards(Rgb a, Rgb b, float t) {
    return {towards(a.r, b.r, t), towards(a.g, b.g, t), towards(a.b, b.b, t)};
}

float saturate(float v) { return std::fmin(std::fmax(v, 0.0f), 1.0f); }

// One channel of the blends that act per channel; `s` = 1 - t.
float blend_channel(int32_t blend, float t, float a, float b) {
    const float s = 1.0f - t;
    switch (blend) {
        case Add:
            return towards(a, a + b, t);
        case Multiply:
            return towards(a, a * b, t);
        case Subtract:
            return towards(a, a - b, t);
        case Screen:
            return 1.0f - (s + t * (1.0f - b)) * (1.0f - a);
        case Divide:
            return b != 0.0f ? s * a + t * a / b : a;
        case Difference:
            return towards(a, std::fabs(a - b), t);
        case Darken:
            return towards(a, std::min(a, b), t);
        case Lighten:
            return towards(a, std::max(a, b), t);
        case Overlay:
            return a < 0.5f ? a * (s + 2.0f * t * b) : 1.0f - (s + 2.0f * t * (1.0f - b)) * (1.0f - a);
        case Dodge: {
            if (a == 0.0f) return a;
            const float d = 1.0f - t * b;
            if (d <= 0.0f) return 1.0f;
            const float q = a / d;
            return q > 1.0f ? 1.0f : q;
        }
        case Burn: {
            const float d = s + t * b;
            if (d <= 0.0f) return 0.0f;
            const float q = 1.0f - (1.0f - a) / d;
            return q < 0.0f ? 0.0f : (q > 1.0f ? 1.0f : q);
        }
        case SoftLight: {
            const float screen = 1.0f - (1.0f - b) * (1.0f - a);
            return s * a + t * ((1.0f - a) * b * a + a * screen);
        }
        case LinearLight:
            return a + t * (2.0f * b - 1.0f);
        case Exclusion:
            return std::max(towards(a, a + b - 2.0f * a * b, t), 0.0f);
        default:  // Blend
            return towards(a, b, t);
    }
}

Rgb mix_colors(int32_t blend, float t, Rgb a, Rgb b) {
    switch (blend) {
        case Hue: {
            const Rgb hsv_b = rgb_to_hsv(b);
            if (hsv_b.g == 0.0f) return a;
            Rgb hsv = rgb_to_hsv(a);
            hsv.r = hsv_b.r;
            return towards(a, hsv_to_rgb(hsv), t);
        }
        case Saturation: {
            Rgb hsv = rgb_to_hsv(a);
            if (hsv.g == 0.0f) return a;
            hsv.g = (1.0f - t) * hsv.g + t * rgb_to_hsv(b).g;
            return hsv_to_rgb(hsv);
        }
        case Value: {
            Rgb hsv = rgb_to_hsv(a);
            hsv.b = (1.0f - t) * hsv.b + t * rgb_to_hsv(b).b;
            return hsv_to_rgb(hsv);
        }
        case Color: {
            const Rgb hsv_b = rgb_to_hsv(b);
            if (hsv_b.g == 0.0f) return a;
            Rgb hsv = rgb_to_hsv(a);
            hsv.r = hsv_b.r;
            hsv.g = hsv_b.g;
            return towards(a, hsv_to_rgb(hsv), t);
        }
        default:
            return {blend_channel(blend, t, a.r, b.r), blend_channel(blend, t, a.g, b.g),
                    blend_channel(blend, t, a.b, b.b)};
    }
}

std::string check_mix(const ShaderNode& n, const ShaderProgram& program) {
    for (const auto& [index, what, count] :
         {std::tuple{0, "kind", int32_t{MixKindCount}}, std::tuple{1, "blend", int32_t{MixBlendCount}},
          std::tuple{2, "clamp factor", int32_t{2}}, std::tuple{3, "clamp result", int32_t{2}}}) {
        std::string e = check_mode(n, index, what, count);
        if (!e.empty()) return e;
    }
    const int32_t kind = n.modes[0];
    const uint64_t count = program.registers.size();
    const auto wide = [&](uint32_t reg) { return static_cast<uint64_t>(reg) + 3 <= count; };
    if (kind == MixVectorNonUniform && !wide(n.inputs[0])) return "input 0 (factor) register is not 3 wide";
    if (kind != MixFloat) {
        if (!wide(n.inputs[1])) return "input 1 (a) register is not 3 wide";
        if (!wide(n.inputs[2])) return "input 2 (b) register is not 3 wide";
        if (!wide(n.outputs[0])) return "output 0 (result) register is not 3 wide";
    }
    return "";
}

void evaluate_mix(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const bool clamp_factor = n.modes[2] != 0;
    const uint32_t f = n.inputs[0], a = n.inputs[1], b = n.inputs[2], out = n.outputs[0];
    switch (n.modes[0]) {
        case MixFloat: {
            float t = r[f];
            if (clamp_factor) t = saturate(t);
            r[out] = r[a] * (1.0f - t) + r[b] * t;
            break;
        }
        case MixVector:
        case MixVectorNonUniform: {
            const bool uniform = n.modes[0] == MixVector;
            float t[3] = {r[f], uniform ? r[f] : r[f + 1], uniform ? r[f] : r[f + 2]};
            const float av[3] = {r[a], r[a + 1], r[a + 2]}, bv[3] = {r[b], r[b + 1], r[b + 2]};
            float result[3];
            for (int k = 0; k < 3; ++k) {
                if (clamp_factor) t[k] = saturate(t[k]);
                result[k] = av[k] * (1.0f - t[k]) + bv[k] * t[k];
            }
            r.set(out, Vec3(result[0], result[1], result[2]));
            break;
        }
        default: {
            float t = r[f];
            if (clamp_factor) t = saturate(t);
            Rgb c = mix_colors(n.modes[1], t, r.rgb(a), r.rgb(b));
            if (n.modes[3]) c = {saturate(c.r), saturate(c.g), saturate(c.b)};
            r.set(out, c);
            break;
        }
    }
}

}  // namespace

const NodeRegistration kMixNode{{.value = 2,
                                 .name = "mix",
                                 .input_widths = {1, 1, 1},
                                 .output_widths = {1},
                                 .check = check_mix,
                                 .evaluate = evaluate_mix}};

}  // namespace stratum
