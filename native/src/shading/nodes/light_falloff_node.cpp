// Light Falloff (Blender's ShaderNodeLightFalloff), as Cycles' svm_node_light_falloff
// (kernel/svm/light_path.h).
//
// | node          | modes                           | inputs                  | outputs              |
// |---------------|---------------------------------|-------------------------|----------------------|
// | light_falloff | 0 revision: 0 Blender < 4.4,    | 0 strength, 1 smooth,   | 0 quadratic,         |
// |               | 1 Blender 4.4 and later         | 2 ray length (the       | 1 linear, 2 constant |
// |               |                                 | renderer's RAY_LENGTH)  |                      |
//
// With l the ray length (on a surface the distance the ray travelled to it; in a lamp's program
// the distance from the shaded point to the point on the lamp) and s the strength: Quadratic = s,
// Linear = s l, Constant = s l², each then times l² / (smooth + l²) when smooth > 0. Cycles
// compiles one node per linked output; they share these inputs, so one node gives all three.
// A ray length of FLT_MAX or more (the world, a sun: Cycles sets FLT_MAX there) is FLT_MAX:
//   revision 0 (3.4 to 4.3): the products as above (Linear s FLT_MAX, Constant infinite for
//     s > 0), and no smoothing (Cycles skips it when l² is not finite);
//   revision 1 (4.4 and later): every output is s.
#include <cfloat>

#include "shading/node_registry.h"

namespace stratum {

namespace {

enum Revision : int32_t { Before44, From44, RevisionCount };

std::string check_light_falloff(const ShaderNode& n, const ShaderProgram&) {
    return check_mode(n, 0, "revision", RevisionCount);
}

// One output: `strength` times l (power 1) or l l (power 2), then smoothed, in Cycles' order of
// operations. Before 4.4 Cycles skips the smoothing when l² is not finite; 4.4 leaves that check
// out (it returns early at FLT_MAX instead), so an l² that overflows below FLT_MAX gives NaN there.
float falloff(float strength, float smooth, float l, int power, int32_t revision) {
    if (power == 1) strength *= l;
    if (power == 2) strength *= l * l;
    if (smooth > 0.0f) {
        const float squared = l * l;
        if (revision == From44 || squared <= FLT_MAX) strength *= squared / (smooth + squared);
    }
    return strength;
}

void evaluate_light_falloff(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const float strength = r[n.inputs[0]], smooth = r[n.inputs[1]];
    const int32_t revision = n.modes[0];
    float l = r[n.inputs[2]];
    if (l >= FLT_MAX) {
        if (revision == From44) {
            for (int k = 0; k < 3; ++k) r[n.outputs[k]] = strength;
            return;
        }
        l = FLT_MAX;
    }
    for (int power = 0; power < 3; ++power)
        r[n.outputs[power]] = falloff(strength, smooth, l, power, revision);
}

}  // namespace

const NodeRegistration kLightFalloffNode{{.value = 37,
                                          .name = "light_falloff",
                                          .input_widths = {1, 1, 1},
                                          .output_widths = {1, 1, 1},
                                          .check = check_light_falloff,
                                          .evaluate = evaluate_light_falloff}};

}  // namespace stratum
