// Separate Color and Combine Color (Blender 3.3+'s ShaderNodeSeparateColor / CombineColor, and
// 3.x's Separate/Combine RGB and HSV, which are their RGB and HSV modes), as Cycles'
// svm_node_separate_color / svm_node_combine_color (kernel/svm/sepcomb_color.h, the conversions
// svm_separate_color / svm_combine_color in color_util.h, the same in 3.4 and 5.0) and 3.4's
// svm_node_separate_hsv / combine_hsv (sepcomb_hsv.h, the same conversions).
//
// | node           | modes                   | inputs                | outputs                  |
// |----------------|-------------------------|-----------------------|--------------------------|
// | separate_color | 0 model (ColorModel)    | color (3)             | components (3: r g b,    |
// |                |                         |                       | h s v or h s l)          |
// | combine_color  | 0 model (ColorModel)    | three floats (any     | color (3)                |
// |                |                         | registers)            |                          |
//
// The conversions are shading/color_math.h's; components are not clamped (Cycles' are not).
#include "shading/color_math.h"
#include "shading/node_registry.h"

namespace stratum {

namespace {

enum ColorModel : int32_t { ModelRgb, ModelHsv, ModelHsl, ColorModelCount };

std::string check_model(const ShaderNode& n, const ShaderProgram&) {
    return check_mode(n, 0, "model", ColorModelCount);
}

void evaluate_separate(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Rgb c = r.rgb(n.inputs[0]);
    switch (n.modes[0]) {
        case ModelHsv:
            r.set(n.outputs[0], rgb_to_hsv(c));
            break;
        case ModelHsl:
            r.set(n.outputs[0], rgb_to_hsl(c));
            break;
        default:
            r.set(n.outputs[0], c);
            break;
    }
}

void evaluate_combine(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Rgb c(r[n.inputs[0]], r[n.inputs[1]], r[n.inputs[2]]);
    switch (n.modes[0]) {
        case ModelHsv:
            r.set(n.outputs[0], hsv_to_rgb(c));
            break;
        case ModelHsl:
            r.set(n.outputs[0], hsl_to_rgb(c));
            break;
        default:
            r.set(n.outputs[0], c);
            break;
    }
}

}  // namespace

const NodeRegistration kSeparateColorNode{{.value = 9,
                                           .name = "separate_color",
                                           .input_widths = {3},
                                           .output_widths = {3},
                                           .check = check_model,
                                           .evaluate = evaluate_separate}};
const NodeRegistration kCombineColorNode{{.value = 10,
                                          .name = "combine_color",
                                          .input_widths = {1, 1, 1},
                                          .output_widths = {3},
                                          .check = check_model,
                                          .evaluate = evaluate_combine}};

}  // namespace stratum
