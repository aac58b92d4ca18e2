// Tangent (Blender's ShaderNodeTangent), as Cycles' svm_node_tangent (kernel/svm/tex_coord.h;
// the same in 3.4 and 5.0).
//
// | node    | modes                          | inputs                                  | outputs     |
// |---------|--------------------------------|-----------------------------------------|-------------|
// | tangent | 0 direction (0 RADIAL,         | 0 generated (3), 1 normal (3), 2 3 4    | 0 tangent 3 |
// |         | 1 UV_MAP), 1 axis (0 X, 1 Y,   | the normal transform's X, Y, Z axes (3  |             |
// |         | 2 Z; radial only)              | each), 5 MikkTSpace tangent (3)         |             |
//
// The translator feeds the renderer's GENERATED (or a Bump offset's stand-in), NORMAL,
// NORMAL_TRANSFORM (+0, +3, +6) and MIKKTSPACE_TANGENT. Radial: with g the generated point, the
// tangent around the axis through the texture space's centre, X (0, -(g.z - ½), g.y - ½),
// Y (-(g.z - ½), 0, g.x - ½), Z (-(g.y - ½), g.x - ½, 0), taken to world space as a normal is
// (x X + y Y + z Z). UV map: the mesh's MikkTSpace tangent, which the renderer gives in world
// space already; none (all 0) gives 0, as Cycles' missing attribute. Then T' = N x normalize(T x N)
// (each normalisation a division by the length, as Cycles': a tangent along N gives NaN there).
#include <cmath>

#include "shading/node_registry.h"

namespace stratum {

namespace {

enum Direction : int32_t { Radial, UvMap, DirectionCount };
enum Axis : int32_t { AxisX, AxisY, AxisZ, AxisCount };

std::string check_tangent(const ShaderNode& n, const ShaderProgram&) {
    std::string e = check_mode(n, 0, "direction", DirectionCount);
    return e.empty() ? check_mode(n, 1, "axis", AxisCount) : e;
}

Vec3 radial(Vec3 g, int32_t axis) {
    if (axis == AxisX) return {0.0f, -(g.z - 0.5f), g.y - 0.5f};
    if (axis == AxisY) return {-(g.z - 0.5f), 0.0f, g.x - 0.5f};
    return {-(g.y - 0.5f), g.x - 0.5f, 0.0f};
}

void evaluate_tangent(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    Vec3 t;
    if (n.modes[0] == UvMap) {
        t = r.vec3(n.inputs[5]);
        if (t.x == 0.0f && t.y == 0.0f && t.z == 0.0f) {
            r.set(n.outputs[0], t);
            return;
        }
    } else {
        const Vec3 v = radial(r.vec3(n.inputs[0]), n.modes[1]);
        t = r.vec3(n.inputs[2]) * v.x + r.vec3(n.inputs[3]) * v.y + r.vec3(n.inputs[4]) * v.z;
    }
    const Vec3 normal = r.vec3(n.inputs[1]);
    const Vec3 across = cross(t, normal);
    const float l = std::sqrt(dot(across, across));
    r.set(n.outputs[0], cross(normal, Vec3(across.x / l, across.y / l, across.z / l)));
}

}  // namespace

const NodeRegistration kTangentNode{{.value = 39,
                                     .name = "tangent",
                                     .input_widths = {3, 3, 3, 3, 3, 3},
                                     .output_widths = {3},
                                     .check = check_tangent,
                                     .evaluate = evaluate_tangent}};

}  // namespace stratum
