// Checker Texture (Blender's ShaderNodeTexChecker), as Cycles' svm/checker.h (3.4 and 5.0 agree).
//
// | node    | modes | inputs                                          | outputs          |
// |---------|-------|-------------------------------------------------|------------------|
// | checker | none  | 0 vector (3), 1 color1 (3), 2 color2 (3), 3 scale | 0 color (3), 1 fac |
//
// The point p = vector x scale is nudged by (p + 1e-6) x 0.999999 (so that unit coordinates do not
// fall on a cell edge); fac is 1 where the parities of floor(x), floor(y), floor(z) (of their
// absolute values as ints) satisfy (x even == y even) == z odd, else 0; color is color1 where fac
// is 1, else color2.
#include <cstdlib>

#include "shading/node_registry.h"
#include "shading/pattern_math.h"

namespace stratum {

namespace {

// |int| % 2 of floor(v); INT_MIN (a NaN or huge v) is even, as abs(INT_MIN) wraps to itself.
int parity(float v) {
    const int32_t i = pattern_math::floor_to_int((v + 0.000001f) * 0.999999f);
    return i == INT32_MIN ? 0 : std::abs(i) % 2;
}

std::string check_checker(const ShaderNode&, const ShaderProgram&) { return ""; }

void evaluate_checker(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Vec3 p = r.vec3(n.inputs[0]) * r[n.inputs[3]];
    const bool xy_same = parity(p.x) == parity(p.y);
    const float fac = (static_cast<int>(xy_same) == parity(p.z)) ? 1.0f : 0.0f;
    r.set(n.outputs[0], fac == 1.0f ? r.rgb(n.inputs[1]) : r.rgb(n.inputs[2]));
    r[n.outputs[1]] = fac;
}

}  // namespace

const NodeRegistration kCheckerNode{{.value = 22,
                                     .name = "checker",
                                     .input_widths = {3, 3, 3, 1},
                                     .output_widths = {3, 1},
                                     .check = check_checker,
                                     .evaluate = evaluate_checker}};

}  // namespace stratum
