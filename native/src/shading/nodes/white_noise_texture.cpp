// White Noise Texture node (Blender's ShaderNodeTexWhiteNoise), as Cycles' svm_node_tex_white_noise
// (kernel/svm/white_noise.h, the same in 3.4 and 5.0): the lookup3 hash (cycles_hash.h) of the
// point's float bit patterns, no scale.
//
// | modes                   | inputs            | outputs            |
// |-------------------------|-------------------|--------------------|
// | 0 dimensions - 1 (0..3) | 0 vector (3), 1 w | 0 value, 1 color   |
//
// 1D hashes w; 2D (x, y); 3D (x, y, z); 4D (x, y, z, w). Value is hash_floatN_to_float, Color
// hash_floatN_to_float3.
#include "shading/cycles_hash.h"
#include "shading/node_registry.h"

namespace stratum {

namespace {

std::string check_white_noise(const ShaderNode& n, const ShaderProgram&) {
    return check_mode(n, 0, "dimensions", 4);
}

void evaluate_white_noise(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    namespace h = cycles_hash;
    const Vec3 v = r.vec3(n.inputs[0]);
    const float w = r[n.inputs[1]];
    float value = 0.0f;
    h::Hash3 color{};
    switch (n.modes[0]) {
        case 0:
            value = h::hash_float(w);
            color = h::hash_float_to_float3(w);
            break;
        case 1:
            value = h::hash_float2(v.x, v.y);
            color = h::hash_float2_to_float3(v.x, v.y);
            break;
        case 2:
            value = h::hash_float3(v.x, v.y, v.z);
            color = h::hash_float3_to_float3(v.x, v.y, v.z);
            break;
        default:
            value = h::hash_float4(v.x, v.y, v.z, w);
            color = h::hash_float4_to_float3(v.x, v.y, v.z, w);
            break;
    }
    r[n.outputs[0]] = value;
    r.set(n.outputs[1], Rgb(color.x, color.y, color.z));
}

}  // namespace

const NodeRegistration kWhiteNoiseNode{{.value = 26,
                                        .name = "white_noise",
                                        .input_widths = {3, 1},
                                        .output_widths = {1, 3},
                                        .check = check_white_noise,
                                        .evaluate = evaluate_white_noise}};

}  // namespace stratum
