// Colour adjustments: Invert, Gamma, Bright/Contrast, Hue/Saturation/Value and RGB to BW, as
// Cycles' svm_node_invert (kernel/svm/invert.h), svm_node_gamma (gamma.h, svm_math_gamma_color in
// math_util.h), svm_node_brightness (brightness.h, svm_brightness_contrast in color_util.h),
// svm_node_hsv (hsv.h) and the colour-to-float conversion (convert.h, rgb_to_gray).
//
// | node            | modes                     | inputs                                | outputs   |
// |-----------------|---------------------------|---------------------------------------|-----------|
// | invert          | -                         | fac, color (3)                        | color (3) |
// | gamma           | -                         | color (3), gamma                      | color (3) |
// | bright_contrast | -                         | color (3), bright, contrast           | color (3) |
// | hsv             | 0 hue wrap (HueWrap)      | hue, saturation, value, fac, color (3)| color (3) |
// | rgb_to_bw       | 0 luminance weights       | color (3)                             | val       |
//
// Hue/Saturation/Value shifts the hue by (hue - 0.5) and wraps it to [0, 1): Cycles 3.4 wraps with
// fmodf, which leaves a negative sum negative (a Hue input below 0 - 0.5 - h), 4.0 and later with
// fractf; the sum is the same otherwise. RGB to BW is the luminance with the colour
// configuration's weights (node_registry.h luminance()), as the Math node's colour input
// (math_node.cpp).
#include <algorithm>
#include <cmath>

#include "shading/color_math.h"
#include "shading/node_registry.h"

namespace stratum {

namespace {

std::string no_modes(const ShaderNode&, const ShaderProgram&) { return ""; }

void evaluate_invert(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const float fac = r[n.inputs[0]];
    const Rgb c = r.rgb(n.inputs[1]);
    const auto invert = [fac](float v) { return fac * (1.0f - v) + (1.0f - fac) * v; };
    r.set(n.outputs[0], Rgb(invert(c.r), invert(c.g), invert(c.b)));
}

void evaluate_gamma(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Rgb c = r.rgb(n.inputs[0]);
    const float gamma = r[n.inputs[1]];
    // A zero exponent gives white; a channel <= 0 is left as it is.
    const auto power = [gamma](float v) { return v > 0.0f ? std::pow(v, gamma) : v; };
    r.set(n.outputs[0], gamma == 0.0f ? Rgb(1.0f) : Rgb(power(c.r), power(c.g), power(c.b)));
}

void evaluate_bright_contrast(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Rgb c = r.rgb(n.inputs[0]);
    const float bright = r[n.inputs[1]], contrast = r[n.inputs[2]];
    const float slope = 1.0f + contrast, offset = bright - contrast * 0.5f;
    const auto adjust = [&](float v) { return std::max(slope * v + offset, 0.0f); };
    r.set(n.outputs[0], Rgb(adjust(c.r), adjust(c.g), adjust(c.b)));
}

enum HueWrap : int32_t { HueFract, HueFmod, HueWrapCount };

std::string check_hsv(const ShaderNode& n, const ShaderProgram&) {
    return check_mode(n, 0, "hue wrap", HueWrapCount);
}

void evaluate_hsv(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const float hue = r[n.inputs[0]], sat = r[n.inputs[1]], val = r[n.inputs[2]], fac = r[n.inputs[3]];
    const Rgb in = r.rgb(n.inputs[4]);
    Rgb hsv = rgb_to_hsv(in);
    const float shifted = hsv.r + hue + 0.5f;
    hsv.r = n.modes[0] == HueFmod ? std::fmod(shifted, 1.0f) : shifted - std::floor(shifted);
    hsv.g = std::fmin(std::fmax(hsv.g * sat, 0.0f), 1.0f);
    hsv.b *= val;
    const Rgb c = hsv_to_rgb(hsv);
    const auto blend = [fac](float changed, float original) {
        // Over-saturation can make a channel negative: Cycles clamps it to 0.
        return std::max(fac * changed + (1.0f - fac) * original, 0.0f);
    };
    r.set(n.outputs[0], Rgb(blend(c.r, in.r), blend(c.g, in.g), blend(c.b, in.b)));
}

void evaluate_rgb_to_bw(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    r[n.outputs[0]] = luminance(r.rgb(n.inputs[0]), n.modes[0]);
}

std::string check_rgb_to_bw(const ShaderNode& n, const ShaderProgram&) {
    return check_mode(n, 0, "luminance weights", kLuminanceWeightsCount);
}

}  // namespace

const NodeRegistration kInvertNode{{.value = 5,
                                    .name = "invert",
                                    .input_widths = {1, 3},
                                    .output_widths = {3},
                                    .check = no_modes,
                                    .evaluate = evaluate_invert}};
const NodeRegistration kGammaNode{{.value = 6,
                                   .name = "gamma",
                                   .input_widths = {3, 1},
                                   .output_widths = {3},
                                   .check = no_modes,
                                   .evaluate = evaluate_gamma}};
const NodeRegistration kBrightContrastNode{{.value = 7,
                                            .name = "bright_contrast",
                                            .input_widths = {3, 1, 1},
                                            .output_widths = {3},
                                            .check = no_modes,
                                            .evaluate = evaluate_bright_contrast}};
const NodeRegistration kHsvNode{{.value = 8,
                                 .name = "hsv",
                                 .input_widths = {1, 1, 1, 1, 3},
                                 .output_widths = {3},
                                 .check = check_hsv,
                                 .evaluate = evaluate_hsv}};
const NodeRegistration kRgbToBwNode{{.value = 11,
                                     .name = "rgb_to_bw",
                                     .input_widths = {3},
                                     .output_widths = {1},
                                     .check = check_rgb_to_bw,
                                     .evaluate = evaluate_rgb_to_bw}};

}  // namespace stratum
