// Mapping (Blender's ShaderNodeMapping), Vector Rotate (ShaderNodeVectorRotate) and Vector
// Transform (ShaderNodeVectorTransform) between equal spaces.
//
// | node             | modes                                    | inputs                      | outputs  |
// |------------------|------------------------------------------|-----------------------------|----------|
// | mapping          | 0 type (POINT, TEXTURE, VECTOR, NORMAL)  | vector 3, location 3,       | vector 3 |
// |                  |                                          | rotation 3, scale 3         |          |
// | vector_rotate    | 0 type (AXIS_ANGLE, X_AXIS, Y_AXIS,      | vector 3, center 3, axis 3, | vector 3 |
// |                  | Z_AXIS, EULER_XYZ), 1 invert             | angle 1, rotation 3         |          |
// | vector_transform | 0 type (VECTOR, POINT, NORMAL), 1 from,  | vector 3                    | vector 3 |
// |                  | 2 to (WORLD, OBJECT, CAMERA), 3 revision |                             |          |
//
// Mapping is svm_mapping (kernel/svm/mapping_util.h), Vector Rotate svm_node_vector_rotate
// (kernel/svm/vector_rotate.h), both unchanged from 3.4 to 5.0. The rotation is Cycles'
// euler_to_transform (util/transform.h): R = Rz Ry Rx, applied as R v, or as R^T v (TEXTURE
// mapping, inverted rotation). Vector Transform (kernel/svm/vector_transform.h) between two
// different spaces needs the object's or the camera's transform, which a program does not carry:
// the check rejects it. Between equal spaces it is the identity, except that Cycles before 4.0
// (revision 0) normalises a NORMAL (revision 1: 4.0 and later leave it).
#include <cmath>

#include "shading/node_registry.h"

namespace stratum {

namespace {

enum MappingType : int32_t { Point, Texture, VectorMapping, NormalMapping, MappingTypeCount };
enum RotateType : int32_t { AxisAngle, AxisX, AxisY, AxisZ, EulerXyz, RotateTypeCount };
enum TransformType : int32_t { TransformVector, TransformPoint, TransformNormal, TransformTypeCount };

// The rows of R = Rz(z) Ry(y) Rx(x).
struct Rotation {
    Vec3 rows[3];
};

Rotation euler_rotation(Vec3 euler) {
    const float cx = std::cos(euler.x), cy = std::cos(euler.y), cz = std::cos(euler.z);
    const float sx = std::sin(euler.x), sy = std::sin(euler.y), sz = std::sin(euler.z);
    return {{Vec3(cy * cz, sy * sx * cz - cx * sz, sy * cx * cz + sx * sz),
             Vec3(cy * sz, sy * sx * sz + cx * cz, sy * cx * sz - sx * cz), Vec3(-sy, cy * sx, cy * cx)}};
}

Vec3 rotate(const Rotation& m, Vec3 v) { return {dot(m.rows[0], v), dot(m.rows[1], v), dot(m.rows[2], v)}; }

Vec3 rotate_transposed(const Rotation& m, Vec3 v) {
    return m.rows[0] * v.x + m.rows[1] * v.y + m.rows[2] * v.z;
}

Vec3 times(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }

Vec3 over(Vec3 a, Vec3 b) {
    return {b.x != 0.0f ? a.x / b.x : 0.0f, b.y != 0.0f ? a.y / b.y : 0.0f, b.z != 0.0f ? a.z / b.z : 0.0f};
}

Vec3 unit_or_same(Vec3 v) {
    const float l = length(v);
    return l != 0.0f ? v * (1.0f / l) : v;
}

Vec3 mapping(int32_t type, Vec3 v, Vec3 location, Vec3 euler, Vec3 scale) {
    const Rotation m = euler_rotation(euler);
    switch (type) {
        case Point:
            return rotate(m, times(v, scale)) + location;
        case Texture:
            return over(rotate_transposed(m, v - location), scale);
        case VectorMapping:
            return rotate(m, times(v, scale));
        default:
            return unit_or_same(rotate(m, over(v, scale)));
    }
}

std::string check_mapping(const ShaderNode& n, const ShaderProgram&) {
    return check_mode(n, 0, "type", MappingTypeCount);
}

void evaluate_mapping(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    r.set(n.outputs[0], mapping(n.modes[0], r.vec3(n.inputs[0]), r.vec3(n.inputs[1]), r.vec3(n.inputs[2]),
                                r.vec3(n.inputs[3])));
}

// Rodrigues' rotation of p by `angle` about the unit `axis`, term by term as Cycles'
// rotate_around_axis (util/math_float3.h).
Vec3 rotate_about(Vec3 p, Vec3 axis, float angle) {
    const float c = std::cos(angle), s = std::sin(angle), t = 1.0f - c;
    const Vec3 a = axis;
    return {(c + t * a.x * a.x) * p.x + (t * a.x * a.y - a.z * s) * p.y + (t * a.x * a.z + a.y * s) * p.z,
            (t * a.x * a.y + a.z * s) * p.x + (c + t * a.y * a.y) * p.y + (t * a.y * a.z - a.x * s) * p.z,
            (t * a.x * a.z - a.y * s) * p.x + (t * a.y * a.z + a.x * s) * p.y + (c + t * a.z * a.z) * p.z};
}

std::string check_vector_rotate(const ShaderNode& n, const ShaderProgram&) {
    std::string e = check_mode(n, 0, "type", RotateTypeCount);
    return e.empty() ? check_mode(n, 1, "invert", 2) : e;
}

void evaluate_vector_rotate(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Vec3 v = r.vec3(n.inputs[0]), center = r.vec3(n.inputs[1]);
    const bool invert = n.modes[1] != 0;
    if (n.modes[0] == EulerXyz) {
        const Rotation m = euler_rotation(r.vec3(n.inputs[4]));
        r.set(n.outputs[0], (invert ? rotate_transposed(m, v - center) : rotate(m, v - center)) + center);
        return;
    }
    Vec3 axis = r.vec3(n.inputs[2]);
    float axis_length = 1.0f;
    switch (n.modes[0]) {
        case AxisX:
            axis = {1.0f, 0.0f, 0.0f};
            break;
        case AxisY:
            axis = {0.0f, 1.0f, 0.0f};
            break;
        case AxisZ:
            axis = {0.0f, 0.0f, 1.0f};
            break;
        default:
            axis_length = length(axis);
            break;
    }
    const float angle = invert ? -r[n.inputs[3]] : r[n.inputs[3]];
    r.set(n.outputs[0],
          axis_length != 0.0f ? rotate_about(v - center, axis / axis_length, angle) + center : v);
}

std::string check_vector_transform(const ShaderNode& n, const ShaderProgram&) {
    std::string e = check_mode(n, 0, "type", TransformTypeCount);
    if (e.empty()) e = check_mode(n, 1, "from", 3);
    if (e.empty()) e = check_mode(n, 2, "to", 3);
    if (e.empty()) e = check_mode(n, 3, "revision", 2);
    if (e.empty() && n.modes[1] != n.modes[2])
        e = "mode 1 (from) is " + std::to_string(n.modes[1]) + " and mode 2 (to) " +
            std::to_string(n.modes[2]) +
            "; only equal spaces (the program has no object or camera transform)";
    return e;
}

void evaluate_vector_transform(const ShaderNode& n, const ShaderEvalContext&, ShaderRegisters& r) {
    const Vec3 v = r.vec3(n.inputs[0]);
    r.set(n.outputs[0], n.modes[0] == TransformNormal && n.modes[3] == 0 ? normalize(v) : v);
}

}  // namespace

const NodeRegistration kMappingNode{{.value = 14,
                                     .name = "mapping",
                                     .input_widths = {3, 3, 3, 3},
                                     .output_widths = {3},
                                     .check = check_mapping,
                                     .evaluate = evaluate_mapping}};

const NodeRegistration kVectorRotateNode{{.value = 15,
                                          .name = "vector_rotate",
                                          .input_widths = {3, 3, 3, 1, 3},
                                          .output_widths = {3},
                                          .check = check_vector_rotate,
                                          .evaluate = evaluate_vector_rotate}};

const NodeRegistration kVectorTransformNode{{.value = 33,
                                             .name = "vector_transform",
                                             .input_widths = {3},
                                             .output_widths = {3},
                                             .check = check_vector_transform,
                                             .evaluate = evaluate_vector_transform}};

}  // namespace stratum
