// Wireframe (Blender's ShaderNodeWireframe), as Cycles' wireframe() and svm_node_wireframe
// (kernel/svm/wireframe.h; the test is the same in 3.4 and 5.0).
//
// | node      | modes              | inputs                                      | outputs |
// |-----------|--------------------|---------------------------------------------|---------|
// | wireframe | 0 use pixel size   | 0 position (3), 1 size, 2 true normal (3),  | 0 fac   |
// |           | (0 world size, 1   | 3 incoming (3), 4 pixel footprint, 5 6 7    |         |
// |           | size in pixels)    | the triangle's vertices (3 each)            |         |
//
// The translator feeds the renderer's POSITION (or a Bump offset's stand-in), TRUE_NORMAL,
// INCOMING, PIXEL_FOOTPRINT and TRIANGLE (+0, +3, +6). With w = size / 2 (half the width: the
// neighbouring face draws the other half), times, with pixel size, the pixel's width at the
// point: the mean over the two axes (a, b) = make_orthonormals(true normal), scaled by the
// footprint, of their lengths once the incoming direction's part is taken out. Fac is 1 when the
// point lies within w of an edge's line, tested as Cycles tests it without a square root:
// |edge x (P - vertex)|² < |edge|² w². Edges run from vertex i - 1 to i. Without a triangle (the
// world: every vertex 0) every edge is empty and Fac is 0, as Cycles' for no primitive.
// Inside a Bump's Height, 5.0 evaluates the node at the offset point (the position stand-in
// does that); 3.4 adds a difference quotient instead, which is not reproduced.
#include <cmath>

#include "shading/node_registry.h"

namespace stratum {

namespace {

std::string check_wireframe(const ShaderNode& n, const ShaderProgram&) {
    return check_mode(n, 0, "use pixel size", 2);
}

// Cycles' make_orthonormals (util/math_float3.h): a = normalize((1, 1, 1) x N) unless N's
// components are all equal, then (-1, 1, 1) x N; b = N x a.
void orthonormals(Vec3 n, Vec3* a, Vec3* b) {
    Vec3 t = n.x != n.y || n.x != n.z ? Vec3(n.z - n.y, n.x - n.z, n.y - n.x)
                                      : Vec3(n.z - n.y, n.x + n.z, -n.y - n.x);
    const float l = std::sqrt(dot(t, t));
    t = Vec3(t.x / l, t.y / l, t.z / l);
    *a = t;
    *b = cross(n, t);
}

// |d - (d . i) i| of a step d across the view direction i.
float across(Vec3 d, Vec3 i) { return length(d - i * dot(d, i)); }

void evaluate_wireframe(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Vec3 p = r.vec3(n.inputs[0]);
    float width = 1.0f;
    if (n.modes[0] == 1) {
        const Vec3 incoming = r.vec3(n.inputs[3]);
        const float footprint = r[n.inputs[4]];
        Vec3 a, b;
        orthonormals(r.vec3(n.inputs[2]), &a, &b);
        width = (across(a * footprint, incoming) + across(b * footprint, incoming)) * 0.5f;
    }
    width *= 0.5f * r[n.inputs[1]];
    width *= width;
    const Vec3 corner[3] = {r.vec3(n.inputs[5]), r.vec3(n.inputs[6]), r.vec3(n.inputs[7])};
    float fac = 0.0f;
    for (int i = 0; i < 3; ++i) {
        const Vec3 edge = corner[i] - corner[i == 0 ? 2 : i - 1];
        const Vec3 c = cross(edge, p - corner[i]);
        if (dot(c, c) < dot(edge, edge) * width) {
            fac = 1.0f;
            break;
        }
    }
    r[n.outputs[0]] = fac;
}

}  // namespace

const NodeRegistration kWireframeNode{{.value = 38,
                                       .name = "wireframe",
                                       .input_widths = {3, 1, 3, 3, 1, 3, 3, 3},
                                       .output_widths = {1},
                                       .check = check_wireframe,
                                       .evaluate = evaluate_wireframe}};

}  // namespace stratum
