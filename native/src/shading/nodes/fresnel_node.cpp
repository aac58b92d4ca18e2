// Fresnel (Blender's ShaderNodeFresnel), Layer Weight (ShaderNodeLayerWeight) and Normal
// (ShaderNodeNormal).
//
// | node         | modes | inputs                                       | outputs            |
// |--------------|-------|----------------------------------------------|--------------------|
// | fresnel      | -     | ior 1, normal 3, incoming 3, backfacing 1    | fac 1              |
// | layer_weight | -     | blend 1, normal 3, incoming 3, backfacing 1  | fresnel 1, facing 1|
// | normal       | -     | normal 3, direction 3                        | normal 3, dot 1    |
//
// Cycles' svm_node_fresnel and svm_node_layer_weight (kernel/svm/fresnel.h) with
// fresnel_dielectric_cos (kernel/closure/bsdf_util.h), and svm_node_normal
// (kernel/svm/normal.h); all unchanged from 3.4 to 5.0. `incoming` and `backfacing` are the
// renderer's inputs (Cycles' sd->wi and SD_BACKFACING) and `normal` is the node's Normal input
// when linked, else the shading normal (the compiler passes those registers). The IOR is at
// least 1e-5 and inverted on a back face; Layer Weight's Fresnel uses 1 / (1 - blend), inverted
// on a back face likewise. Normal's `direction` is the node's own vector (normalised here, as
// Cycles does), its Dot that direction against the normalised input.
#include <cmath>

#include "shading/node_registry.h"

namespace stratum {

namespace {

// Unpolarised Fresnel reflectance of a dielectric, relative IOR `eta`, without the refracted
// direction; 1 under total internal reflection.
float dielectric_fresnel(float cos_i, float eta) {
    const float c = std::fabs(cos_i);
    float g = eta * eta - 1.0f + c * c;
    if (!(g > 0.0f)) return 1.0f;
    g = std::sqrt(g);
    const float a = (g - c) / (g + c);
    const float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
    return 0.5f * a * a * (1.0f + b * b);
}

std::string no_modes(const ShaderNode&, const ShaderProgram&) { return ""; }

void evaluate_fresnel(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    float eta = std::fmax(r[n.inputs[0]], 1e-5f);
    if (r[n.inputs[3]] != 0.0f) eta = 1.0f / eta;
    r[n.outputs[0]] = dielectric_fresnel(dot(r.vec3(n.inputs[2]), r.vec3(n.inputs[1])), eta);
}

void evaluate_layer_weight(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const float blend = r[n.inputs[0]];
    const float cos_i = dot(r.vec3(n.inputs[2]), r.vec3(n.inputs[1]));
    const bool backfacing = r[n.inputs[3]] != 0.0f;

    float eta = std::fmax(1.0f - blend, 1e-5f);
    if (!backfacing) eta = 1.0f / eta;
    r[n.outputs[0]] = dielectric_fresnel(cos_i, eta);

    float facing = std::fabs(cos_i);
    if (blend != 0.5f) {
        float b = blend > 0.0f ? blend : 0.0f;
        b = b < 1.0f - 1e-5f ? b : 1.0f - 1e-5f;
        b = b < 0.5f ? 2.0f * b : 0.5f / (1.0f - b);
        facing = std::pow(facing, b);
    }
    r[n.outputs[1]] = 1.0f - facing;
}

void evaluate_normal(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Vec3 direction = normalize(r.vec3(n.inputs[1]));
    r.set(n.outputs[0], direction);
    r[n.outputs[1]] = dot(direction, normalize(r.vec3(n.inputs[0])));
}

}  // namespace

const NodeRegistration kFresnelNode{{.value = 16,
                                     .name = "fresnel",
                                     .input_widths = {1, 3, 3, 1},
                                     .output_widths = {1},
                                     .check = no_modes,
                                     .evaluate = evaluate_fresnel}};

const NodeRegistration kLayerWeightNode{{.value = 17,
                                         .name = "layer_weight",
                                         .input_widths = {1, 3, 3, 1},
                                         .output_widths = {1, 1},
                                         .check = no_modes,
                                         .evaluate = evaluate_layer_weight}};

const NodeRegistration kNormalNode{{.value = 34,
                                    .name = "normal",
                                    .input_widths = {3, 3},
                                    .output_widths = {3, 1},
                                    .check = no_modes,
                                    .evaluate = evaluate_normal}};

}  // namespace stratum
