// Bump and Normal Map nodes (ShaderNodeBump, ShaderNodeNormalMap) of node programs.
//
// | node       | modes                          | inputs                                      | out    |
// |------------|--------------------------------|---------------------------------------------|--------|
// | bump       | 0 invert                       | h_c, h_x, h_y, strength, distance, normal 3,| normal |
// |            |                                | dP_x 3, dP_y 3                              |        |
// | normal_map | 0 space (0 tangent, 1 world),  | colour 3, strength, normal 3, tangent 3     | normal |
// |            | 1 strength rule (0 3.x, 1 4.x) |                                             |        |
//
// Bump: Cycles' svm_node_set_bump (kernel/svm/displace.h, 3.4 and 5.0). The compiler evaluates
// the Height input three times, at the point and at the point moved by dP_x and dP_y (the
// renderer's DPDX / DPDY inputs, two steps in the tangent plane); with R_x = dP_y × N,
// R_y = N × dP_x and det = dP_x · R_x, the surface gradient is (h_x − h_c) R_x + (h_y − h_c) R_y
// and N' = normalize(|det| N − distance sign(det) gradient), blended with N by strength. Cycles
// steps by the ray differential (5.0: times the node's Filter Width, which it also divides
// out), so both compute the same limit, the gradient of the height along the surface; only the
// finite-difference error of the step differs. Cycles then bends N' to keep the view's
// reflection above the surface, which the shading point does for every normal it is given.
//
// Normal Map: kernel/svm/tex_coord.h svm_node_normal_map. c = 2 colour − 1. Tangent space with the
// TANGENT input as T (the UV map's dpdu; Cycles uses the mesh's MikkTSpace tangent, equal on
// planar UV layouts) and B = N × T; world space: N' = normalize(c). Strength: 4.x+ scales c.xy by
// it and mixes c.z toward 1 by saturate(strength); 3.x blends N' with N after mapping.
#include <algorithm>
#include <cmath>

#include "shading/node_registry.h"

namespace stratum {

namespace {

Vec3 safe_normalize(Vec3 v) {
    const float l = length(v);
    return l > 0.0f && std::isfinite(l) ? v / l : Vec3(0.0f, 0.0f, 0.0f);
}

bool is_zero(Vec3 v) { return v.x == 0.0f && v.y == 0.0f && v.z == 0.0f; }

std::string check_bump(const ShaderNode& n, const ShaderProgram&) { return check_mode(n, 0, "invert", 2); }

void evaluate_bump(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const float h_c = r[n.inputs[0]], h_x = r[n.inputs[1]], h_y = r[n.inputs[2]];
    const float strength = std::max(r[n.inputs[3]], 0.0f);
    const float distance = n.modes[0] ? -r[n.inputs[4]] : r[n.inputs[4]];
    const Vec3 normal = r.vec3(n.inputs[5]), dx = r.vec3(n.inputs[6]), dy = r.vec3(n.inputs[7]);
    const Vec3 rx = cross(dy, normal), ry = cross(normal, dx);
    const float det = dot(dx, rx);
    const Vec3 gradient = rx * (h_x - h_c) + ry * (h_y - h_c);
    const float sign = det > 0.0f ? 1.0f : (det < 0.0f ? -1.0f : 0.0f);
    Vec3 out = safe_normalize(normal * std::fabs(det) - gradient * (distance * sign));
    if (is_zero(out)) {
        out = normal;
    } else {
        out = safe_normalize(out * strength + normal * (1.0f - strength));
    }
    r.set(n.outputs[0], out);
}

std::string check_normal_map(const ShaderNode& n, const ShaderProgram&) {
    std::string e = check_mode(n, 0, "space", 2);
    return e.empty() ? check_mode(n, 1, "strength rule", 2) : e;
}

void evaluate_normal_map(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Vec3 c0 = r.vec3(n.inputs[0]);
    Vec3 c(2.0f * (c0.x - 0.5f), 2.0f * (c0.y - 0.5f), 2.0f * (c0.z - 0.5f));
    const float strength = r[n.inputs[1]];
    const Vec3 normal = r.vec3(n.inputs[2]);
    const bool modern = n.modes[1] == 1;
    Vec3 mapped;
    if (n.modes[0] == 0) {
        const Vec3 tangent = r.vec3(n.inputs[3]);
        if (is_zero(tangent)) {
            r.set(n.outputs[0], normal);
            return;
        }
        if (modern) {
            c.x *= strength;
            c.y *= strength;
            const float s = std::clamp(strength, 0.0f, 1.0f);
            c.z = 1.0f + (c.z - 1.0f) * s;
        }
        const Vec3 bitangent = cross(normal, tangent);
        mapped = safe_normalize(tangent * c.x + bitangent * c.y + normal * c.z);
    } else {
        mapped = safe_normalize(c);
    }
    if (is_zero(mapped)) {
        r.set(n.outputs[0], normal);
        return;
    }
    if (!(modern && n.modes[0] == 0) && strength != 1.0f) {
        mapped = safe_normalize(normal + (mapped - normal) * std::max(strength, 0.0f));
        if (is_zero(mapped)) mapped = normal;
    }
    r.set(n.outputs[0], mapped);
}

}  // namespace

const NodeRegistration kBumpNode{{.value = 29,
                                  .name = "bump",
                                  .input_widths = {1, 1, 1, 1, 1, 3, 3, 3},
                                  .output_widths = {3},
                                  .check = check_bump,
                                  .evaluate = evaluate_bump}};

const NodeRegistration kNormalMapNode{{.value = 30,
                                       .name = "normal_map",
                                       .input_widths = {3, 1, 3, 3},
                                       .output_widths = {3},
                                       .check = check_normal_map,
                                       .evaluate = evaluate_normal_map}};

}  // namespace stratum
